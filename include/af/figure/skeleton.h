#pragma once
// A skeleton pose: every joint's transform, in model (or world) space.
//
// Convention: a JointTransform maps joint-local points to the enclosing space,
// p = position + rotation * p_local, with column vectors (af/types.h). md5 files store Doom's
// conjugated quaternions (docs/conventions.md §0.2); rotationFromMd5 converts them, and nothing else does.

#include "af/geometry/math.h"
#include "af/text/md5.h"

#include <string>
#include <string_view>
#include <vector>

namespace af {

struct JointTransform {
    Vec3 position = Vec3::Zero();
    Mat3 rotation = Mat3::Identity();
};

// The rotation (joint-local → parent or model space) of an md5 quaternion.
Mat3 rotationFromMd5(const Md5Quat& q);
// The inverse: the md5 quaternion (Doom's conjugated convention, w ≥ 0) of a rotation.
Md5Quat md5FromRotation(const Mat3& rotation);

struct Skeleton {
    std::vector<std::string> names;
    std::vector<int> parents;             // -1 for the root; parents precede children
    std::vector<JointTransform> joints;   // model (or world) space

    std::size_t size() const { return names.size(); }
    // The index of a joint, matched ignoring case as all AF code does, or -1.
    int find(std::string_view name) const;
    // The transform of joint i relative to its parent (the root's is its own transform).
    JointTransform local(std::size_t i) const;
};

// The bind pose of an md5mesh, which is written in model space.
Skeleton skeletonFromMd5Mesh(const Md5Mesh& mesh);

// The AF pose of docs/formats.md §2.3: frame `frame` of an md5anim, composed from parent-relative poses into
// model space (parents first), with `rootOffset` (a model decl's `offset`) added to the root.
Skeleton skeletonFromMd5Anim(const Md5Anim& anim, int frame, const Vec3& rootOffset = Vec3::Zero());

}  // namespace af
