#include "af/figure/skeleton.h"

#include "af/text/strings.h"

#include <Eigen/Geometry>

namespace af {

Mat3 rotationFromMd5(const Md5Quat& q) {
    // Doom uses the Hamilton matrix of q as a row-vector axis, i.e. the column rotation of q*.
    const Eigen::Quaternion<Real> conjugate(q.w, -q.x, -q.y, -q.z);
    return conjugate.normalized().toRotationMatrix();
}

Md5Quat md5FromRotation(const Mat3& rotation) {
    Eigen::Quaternion<Real> q(rotation);
    q.normalize();
    if (q.w() < 0) q.coeffs() = -q.coeffs();
    return {-q.x(), -q.y(), -q.z(), q.w()};
}

int Skeleton::find(std::string_view name) const {
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return static_cast<int>(i);
    for (std::size_t i = 0; i < names.size(); ++i)
        if (equalsIgnoreCase(names[i], name)) return static_cast<int>(i);
    return -1;
}

JointTransform Skeleton::local(std::size_t i) const {
    const int p = parents[i];
    if (p < 0) return joints[i];
    const JointTransform& parent = joints[static_cast<std::size_t>(p)];
    return {parent.rotation.transpose() * (joints[i].position - parent.position),
            parent.rotation.transpose() * joints[i].rotation};
}

Skeleton skeletonFromMd5Mesh(const Md5Mesh& mesh) {
    Skeleton s;
    for (const Md5Joint& j : mesh.joints) {
        s.names.push_back(j.name);
        s.parents.push_back(j.parent);
        s.joints.push_back({Vec3(j.position[0], j.position[1], j.position[2]), rotationFromMd5(j.orientation)});
    }
    return s;
}

Skeleton skeletonFromMd5Anim(const Md5Anim& anim, int frame, const Vec3& rootOffset) {
    const std::vector<Md5JointPose> local = evaluateMd5AnimFrame(anim, frame);
    Skeleton s;
    for (std::size_t i = 0; i < anim.joints.size(); ++i) {
        const Md5AnimJoint& j = anim.joints[i];
        const Vec3 t(local[i].translation[0], local[i].translation[1], local[i].translation[2]);
        const Mat3 r = rotationFromMd5(local[i].orientation);
        s.names.push_back(j.name);
        s.parents.push_back(j.parent);
        if (j.parent < 0) {
            s.joints.push_back({t + rootOffset, r});
        } else {
            const JointTransform& parent = s.joints[static_cast<std::size_t>(j.parent)];
            s.joints.push_back({parent.position + parent.rotation * t, parent.rotation * r});
        }
    }
    return s;
}

}  // namespace af
