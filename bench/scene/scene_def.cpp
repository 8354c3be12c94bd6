#include "scene_def.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <numbers>

namespace benchscene {
namespace {

constexpr double kGolden = 2.399963229728653;  // π(3 − √5)

const std::array<BoxBody, kBodiesPerRagdoll> kBodies = {{
    {"pelvis", {0.170, 0.100, 0.070}, {0.000, 0.000, 0.930}, 9.940},
    {"belly", {0.150, 0.100, 0.110}, {0.000, 0.000, 1.110}, 9.730},
    {"chest", {0.205, 0.110, 0.140}, {0.000, 0.000, 1.360}, 15.120},
    {"head", {0.080, 0.100, 0.140}, {0.000, 0.000, 1.640}, 5.670},
    {"r_upper_arm", {0.150, 0.050, 0.050}, {0.355, 0.000, 1.370}, 1.960},
    {"r_forearm", {0.125, 0.045, 0.045}, {0.630, 0.000, 1.370}, 1.120},
    {"r_hand", {0.065, 0.045, 0.020}, {0.820, 0.000, 1.370}, 0.420},
    {"l_upper_arm", {0.150, 0.050, 0.050}, {-0.355, 0.000, 1.370}, 1.960},
    {"l_forearm", {0.125, 0.045, 0.045}, {-0.630, 0.000, 1.370}, 1.120},
    {"l_hand", {0.065, 0.045, 0.020}, {-0.820, 0.000, 1.370}, 0.420},
    {"r_thigh", {0.075, 0.075, 0.190}, {0.140, 0.000, 0.670}, 7.000},
    {"r_shin", {0.060, 0.060, 0.200}, {0.140, 0.000, 0.280}, 3.255},
    {"r_foot", {0.050, 0.130, 0.040}, {0.140, 0.070, 0.040}, 1.015},
    {"l_thigh", {0.075, 0.075, 0.190}, {-0.140, 0.000, 0.670}, 7.000},
    {"l_shin", {0.060, 0.060, 0.200}, {-0.140, 0.000, 0.280}, 3.255},
    {"l_foot", {0.050, 0.130, 0.040}, {-0.140, 0.070, 0.040}, 1.015},
}};

const Vec3 kZero = Vec3::Zero();
const Vec3 kShoulderConeR = Vec3(1, 4, -1) / std::sqrt(18.0);
const Vec3 kShoulderConeL = Vec3(-1, 4, -1) / std::sqrt(18.0);

const std::array<JointDef, kJointsPerRagdoll> kJoints = {{
    {"lower_spine", JointKind::Fixed, 0, 1, {0, 0, 1.00}, kZero, kZero, 0, 0, 0, 0},
    {"upper_spine", JointKind::Fixed, 1, 2, {0, 0, 1.22}, kZero, kZero, 0, 0, 0, 0},
    {"neck", JointKind::ConeTwist, 2, 3, {0, 0, 1.50}, {0, 0, 1}, {0, 0, 1}, 0, 0.25 * std::numbers::pi, -0.25 * std::numbers::pi, 0.25 * std::numbers::pi},
    {"r_shoulder", JointKind::ConeTwist, 2, 4, {0.205, 0, 1.37}, kShoulderConeR, {1, 0, 0}, 0, 0.5 * std::numbers::pi,
     -0.25 * std::numbers::pi, 0.25 * std::numbers::pi},
    {"r_elbow", JointKind::Hinge, 4, 5, {0.505, 0, 1.37}, {0, 0, 1}, kZero, 0, 0.6 * std::numbers::pi, 0, 0},
    {"r_wrist", JointKind::Hinge, 5, 6, {0.755, 0, 1.37}, {0, 1, 0}, kZero, -0.1 * std::numbers::pi, 0.2 * std::numbers::pi, 0, 0},
    {"l_shoulder", JointKind::ConeTwist, 2, 7, {-0.205, 0, 1.37}, kShoulderConeL, {-1, 0, 0}, 0, 0.5 * std::numbers::pi,
     -0.25 * std::numbers::pi, 0.25 * std::numbers::pi},
    {"l_elbow", JointKind::Hinge, 7, 8, {-0.505, 0, 1.37}, {0, 0, -1}, kZero, 0, 0.6 * std::numbers::pi, 0, 0},
    {"l_wrist", JointKind::Hinge, 8, 9, {-0.755, 0, 1.37}, {0, -1, 0}, kZero, -0.1 * std::numbers::pi, 0.2 * std::numbers::pi, 0, 0},
    {"r_hip", JointKind::Universal, 0, 10, {0.14, 0, 0.86}, {0, -1, 0}, {1, 0, 0}, -0.1 * std::numbers::pi, 0.3 * std::numbers::pi,
     -0.15 * std::numbers::pi, 0.75 * std::numbers::pi},
    {"r_knee", JointKind::Hinge, 10, 11, {0.14, 0, 0.48}, {-1, 0, 0}, kZero, 0, 0.75 * std::numbers::pi, 0, 0},
    {"r_ankle", JointKind::Hinge, 11, 12, {0.14, 0, 0.08}, {1, 0, 0}, kZero, -0.1 * std::numbers::pi, 0.05 * std::numbers::pi, 0, 0},
    {"l_hip", JointKind::Universal, 0, 13, {-0.14, 0, 0.86}, {0, 1, 0}, {1, 0, 0}, -0.1 * std::numbers::pi, 0.3 * std::numbers::pi,
     -0.15 * std::numbers::pi, 0.75 * std::numbers::pi},
    {"l_knee", JointKind::Hinge, 13, 14, {-0.14, 0, 0.48}, {-1, 0, 0}, kZero, 0, 0.75 * std::numbers::pi, 0, 0},
    {"l_ankle", JointKind::Hinge, 14, 15, {-0.14, 0, 0.08}, {1, 0, 0}, kZero, -0.1 * std::numbers::pi, 0.05 * std::numbers::pi, 0, 0},
}};

Quat axisAngle(const Vec3& axis, double angle) { return Quat(Eigen::AngleAxisd(angle, axis)); }

// S(ψ) = Rz(ψ) · Ry(0.10) · Rx(0.15): standing, tilted a little backward and sideways.
Quat standing(double yaw) {
    return axisAngle(Vec3::UnitZ(), yaw) * axisAngle(Vec3::UnitY(), 0.10) * axisAngle(Vec3::UnitX(), 0.15);
}

std::vector<Placement> grid(int n) {
    std::vector<Placement> out;
    const double centre = (n - 1) / 2.0;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const int k = n * i + j;
            out.push_back({Vec3((i - centre) * 2, (j - centre) * 2, 1.9), standing(0.3 + k * kGolden),
                           Vec3(0, 0, 0.5)});
        }
    }
    return out;
}

double wrapAngle(double a) {
    while (a > std::numbers::pi) a -= 2 * std::numbers::pi;
    while (a <= -std::numbers::pi) a += 2 * std::numbers::pi;
    return a;
}

Quat relative(const Quat& qA, const Quat& qB) { return (qA.conjugate() * qB).normalized(); }

}  // namespace

Vec3 boxInertia(const BoxBody& b) {
    const Vec3 h2 = b.halfExtents.cwiseProduct(b.halfExtents);
    return b.mass / 3 * Vec3(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y());
}

std::span<const BoxBody> ragdollBodies() { return kBodies; }
std::span<const JointDef> ragdollJoints() { return kJoints; }

std::vector<Placement> scenePlacements(std::string_view scene, int count) {
    if (count < 0 || (count > 0 && scene != "pile"))
        throw std::invalid_argument("a ragdoll count is for the pile scene only, and at least 1");
    if (scene == "single") return {{Vec3(0, 0, 1.9), standing(0.3), Vec3(0, 0, 0.5)}};
    if (scene == "grid4") return grid(4);
    if (scene == "grid16") return grid(16);
    if (scene == "pile") {
        std::vector<Placement> out;
        for (int k = 0; k < (count > 0 ? count : 32); ++k) {
            out.push_back({Vec3(0, 0, 0.5 + 0.6 * k),
                           axisAngle(Vec3::UnitZ(), 0.3 + k * kGolden) * axisAngle(Vec3::UnitX(), std::numbers::pi / 2),
                           Vec3::Zero()});
        }
        return out;
    }
    throw std::invalid_argument("unknown scene '" + std::string(scene) + "' (single, grid4, grid16, pile)");
}

Vec3 placePoint(const Placement& pl, const Vec3& modelPoint) { return pl.p + pl.R * (modelPoint - kPivot); }

BodyState placeBody(const Placement& pl, int body) {
    BodyState s;
    s.x = placePoint(pl, kBodies.at(static_cast<std::size_t>(body)).centre);
    s.q = pl.R;
    s.w = pl.spin;
    s.v = pl.spin.cross(s.x - pl.p);
    return s;
}

double hingeAngle(const JointDef& j, const Quat& qA, const Quat& qB) {
    const Quat q = relative(qA, qB);
    return wrapAngle(2 * std::atan2(q.vec().dot(j.axis1), q.w()));
}

std::array<double, 2> universalAngles(const JointDef& j, const Quat& qA, const Quat& qB) {
    const Quat q = relative(qA, qB);
    const Vec3 a3 = j.axis1.cross(j.axis2);
    const Vec3 qa2 = q * j.axis2;
    const Vec3 qInvA1 = q.conjugate() * j.axis1;
    return {std::atan2(qa2.dot(a3), qa2.dot(j.axis2)), std::atan2(qInvA1.dot(a3), qInvA1.dot(j.axis1))};
}

std::array<Quat, 2> coneTwistFrames(const JointDef& j) {
    const Quat frameA = Quat::FromTwoVectors(Vec3::UnitX(), j.axis1);
    const Quat frameB = Quat::FromTwoVectors(j.axis1, j.axis2) * frameA;
    return {frameA, frameB};
}

std::array<double, 2> swingTwist(const JointDef& j, const Quat& qA, const Quat& qB) {
    const auto [frameA, frameB] = coneTwistFrames(j);
    const Quat qj = (frameA.conjugate() * relative(qA, qB) * frameB).normalized();
    const Vec3 bone = qj * Vec3::UnitX();
    const double swing = std::atan2(bone.tail<2>().norm(), bone.x());
    return {swing, wrapAngle(2 * std::atan2(qj.x(), qj.w()))};
}

}  // namespace benchscene
