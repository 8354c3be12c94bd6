// af-gen's constraints: the kind of each body's joint to its parent, from the bone's name where
// the name says and from its place in the tree otherwise, and limits centred on the af_pose
// (docs/af-gen.md, "Constraints"; the limit forms are docs/figures.md §3.8).

#include "gen_figure.h"

#include "af/text/strings.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace af::gen {

namespace {

// Lower-case substrings of a body's name, tried in this order ("lowerleg" is a knee before "leg"
// could say anything; bare "arm" and "leg" say nothing, as every bone of a limb has them).
constexpr std::array kKneeNames{"knee", "shin", "calf", "lowerleg", "lowleg", "loleg"};
constexpr std::array kElbowNames{"elbow", "loarm", "forearm", "lowerarm", "lowarm"};
constexpr std::array kShoulderNames{"shoulder", "uparm", "upperarm", "humerus"};
constexpr std::array kHipNames{"thigh", "upleg", "upperleg", "hip", "femur"};
constexpr std::array kNeckNames{"neck", "head"};
constexpr std::array kSpineNames{"spine", "waist", "chest", "torso", "back", "abdomen", "belly", "rib", "tail"};
constexpr std::array kWristNames{"hand", "wrist", "paw"};
constexpr std::array kAnkleNames{"foot", "ankle", "hoof"};

// A hinge bends from 5° past straight to 150°, as our humanoid's knees and elbows do
// (af/humanoid.af: limit 70, 150, 0), whatever bend the af_pose starts in.
constexpr Real kHingeStraightDeg = -5;
constexpr Real kHingeBentDeg = 150;
// A hinge bent less than this in the af_pose is taken as straight: its bend comes from its name.
constexpr Real kStraightDeg = 5;
// Full cone angles (docs/figures.md §3.8: the shaft may lean half of it), after our humanoid's.
constexpr Real kShoulderConeDeg = 150;
constexpr Real kHipConeDeg = 120;
constexpr Real kLimbConeDeg = 120;
constexpr Real kWristConeDeg = 100;
constexpr Real kAnkleConeDeg = 60;
constexpr Real kSpineConeDeg = 50;
constexpr Real kNeckConeDeg = 70;
constexpr Real kContinuationConeDeg = 60;
// A shoulder's cone leans forward and down, a hip's forward: the way arms and legs swing most.
constexpr Real kConeLeanDeg = 30;


Real radians(Real degrees) { return degrees * std::acos(Real(-1)) / 180; }
Real degrees(Real radians) { return radians * 180 / std::acos(Real(-1)); }

// The part of `v` across the unit vector `d`, normalised; `fallback` when `v` runs along `d`.
Vec3 across(const Vec3& v, const Vec3& d, const Vec3& fallback) {
    const Vec3 a = v - v.dot(d) * d;
    if (a.norm() > 0.3 * v.norm()) return a.normalized();
    const Vec3 b = fallback - fallback.dot(d) * d;
    return b.normalized();
}

// `d` turned by `angle` toward `toward`.
Vec3 lean(const Vec3& d, const Vec3& toward, Real angleDeg) {
    const Vec3 t = across(toward, d, kUp);
    return (std::cos(radians(angleDeg)) * d + std::sin(radians(angleDeg)) * t).normalized();
}

AFVector jointVector(const std::string& name) {
    AFVector v;
    v.kind = AFVector::Kind::Joint;
    v.joint1 = name;
    return v;
}

bool isMainChild(const std::vector<GenBody>& bodies, const Skeleton& pose, int body) {
    const GenBody& parent = bodies[static_cast<std::size_t>(bodies[static_cast<std::size_t>(body)].parent)];
    return (pose.joints[static_cast<std::size_t>(bodies[static_cast<std::size_t>(body)].joint)].position -
            parent.boneEnd)
               .norm() < 1e-9;
}

JointKind placeKind(const std::vector<GenBody>& bodies, const Skeleton& pose, int body) {
    const GenBody& b = bodies[static_cast<std::size_t>(body)];
    const GenBody& parent = bodies[static_cast<std::size_t>(b.parent)];
    if (parent.children.size() > 1 && !isMainChild(bodies, pose, body)) return JointKind::Limb;
    // The second bone of a limb that goes on (an upper arm, then a forearm, then a hand).
    if (b.parent > 0 && !b.children.empty() && placeKind(bodies, pose, b.parent) == JointKind::Limb)
        return JointKind::Hinge;
    return JointKind::Continuation;
}

}  // namespace

const char* toString(JointKind kind) {
    switch (kind) {
    case JointKind::Hinge: return "hinge";
    case JointKind::Shoulder: return "shoulder";
    case JointKind::Hip: return "hip";
    case JointKind::Spine: return "spine";
    case JointKind::Neck: return "neck";
    case JointKind::Wrist: return "wrist";
    case JointKind::Ankle: return "ankle";
    case JointKind::Limb: return "limb";
    case JointKind::Continuation: return "continuation";
    }
    return "?";
}

JointKind classifyJoint(const std::vector<GenBody>& bodies, const Skeleton& pose, int body) {
    const std::string name = toLower(bodies[static_cast<std::size_t>(body)].name);
    if (nameHas(name, kKneeNames) || nameHas(name, kElbowNames)) return JointKind::Hinge;
    if (nameHas(name, kShoulderNames)) return JointKind::Shoulder;
    if (nameHas(name, kHipNames)) return JointKind::Hip;
    if (nameHas(name, kNeckNames)) return JointKind::Neck;
    if (nameHas(name, kSpineNames)) return JointKind::Spine;
    if (nameHas(name, kWristNames)) return JointKind::Wrist;
    if (nameHas(name, kAnkleNames)) return JointKind::Ankle;
    return placeKind(bodies, pose, body);
}

AFConstraint makeConstraint(const std::vector<GenBody>& bodies, const Skeleton& /*afPose*/, int body, JointKind kind) {
    const GenBody& b = bodies[static_cast<std::size_t>(body)];
    const GenBody& parent = bodies[static_cast<std::size_t>(b.parent)];
    const Vec3 d = b.shape.rotation.col(2);       // the body's bone
    const Vec3 u = parent.shape.rotation.col(2);  // its parent's

    AFConstraint c;
    c.name = b.name;
    c.body1 = b.name;
    c.body2 = parent.name;
    c.anchor = jointVector(b.name);
    switch (kind) {
    case JointKind::Hinge: {
        // The axis about which a positive turn bends the joint further: the af_pose's own bend
        // when it has one, else knees bend back and elbows forward.
        const Vec3 bend = u.cross(d);
        Vec3 axis;
        if (bend.norm() > std::sin(radians(kStraightDeg))) {
            axis = bend.normalized();
        } else {
            const bool knee = nameHas(toLower(b.name), kKneeNames) || (!nameHas(toLower(b.name), kElbowNames) &&
                                                                        d.dot(kUp) < -0.5);
            axis = d.cross(across(knee ? Vec3(-kForward) : kForward, d, kUp)).normalized();
        }
        const Real bent = degrees(std::atan2(u.cross(d).dot(axis), u.dot(d)));
        // The hinge angle is 0 at the af_pose (docs/figures.md §3.8); keep that pose inside.
        const Real lo = std::min(kHingeStraightDeg - bent, kHingeStraightDeg);
        const Real hi = std::max(kHingeBentDeg - bent, -kHingeStraightDeg);
        c.type = ConstraintType::Hinge;
        c.axis = literal(axis);
        c.limit = LimitType::Cone;
        // Our interval is centred on a3 − a1 with half-width a2/2 (docs/figures.md §3.8), a3 = 0.
        c.limitAngles = {static_cast<float>(-(lo + hi) / 2), static_cast<float>(hi - lo), 0};
        return c;
    }
    case JointKind::Spine:
    case JointKind::Neck:
    case JointKind::Continuation: {
        // A universal joint: bends both ways, never twists (our humanoid's waist and chest).
        c.type = ConstraintType::Universal;
        c.shafts = {literal(d), literal(-d)};
        c.limit = LimitType::Cone;
        c.limitAxis = literal(d);
        const Real cone = kind == JointKind::Spine ? kSpineConeDeg
                          : kind == JointKind::Neck ? kNeckConeDeg
                                                    : kContinuationConeDeg;
        c.limitAngles = {cone, 0, 0};
        return c;
    }
    default: break;
    }
    Vec3 axis = d;
    Real cone = kLimbConeDeg;
    if (kind == JointKind::Shoulder) {
        axis = lean(d, kForward - kUp, kConeLeanDeg);
        cone = kShoulderConeDeg;
    } else if (kind == JointKind::Hip) {
        axis = lean(d, kForward, kConeLeanDeg);
        cone = kHipConeDeg;
    } else if (kind == JointKind::Wrist) {
        cone = kWristConeDeg;
    } else if (kind == JointKind::Ankle) {
        cone = kAnkleConeDeg;
    }
    c.type = ConstraintType::BallAndSocket;
    c.limit = LimitType::Cone;
    c.limitAxis = literal(axis);
    c.limitAngles = {cone, 0, 0};
    c.shafts[0] = literal(d);
    return c;
}

}  // namespace af::gen
