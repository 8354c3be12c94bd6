// Measurements for the af_show* cvars (show_geometry.h), from the joints' own data: the same
// angles the limit rows hold (src/dynamics/joint_shaft_limits.cpp, joint_hinge.cpp).

#include "console/show_geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace af::console {

namespace {

constexpr Real kDegrees = 180 / std::numbers::pi_v<Real>;

Real wrapRadians(Real a) { return std::remainder(a, 2 * std::numbers::pi_v<Real>); }

LimitReading::Angle symmetric(Real radians, Real halfWidth) {
    return {radians * kDegrees, -halfWidth * kDegrees, halfWidth * kDegrees};
}

std::optional<LimitReading> shaftLimit(const Joint& j, std::span<const RigidBody> bodies) {
    const Vec3 shaft = directionOn(bodies, j.bodyA, j.limitShaft);
    if (j.limit == LimitType::Cone) {
        const Vec3 axis = directionOn(bodies, j.bodyB, j.cone.axis);
        const Real angle = std::atan2(shaft.cross(axis).norm(), shaft.dot(axis));
        return LimitReading{"cone", {{angle * kDegrees, 0, j.cone.halfAngle * kDegrees}}};
    }
    if (j.limit == LimitType::Pyramid) {
        const Mat3 basis = (j.bodyB == kWorldBody ? Mat3::Identity() : bodies[std::size_t(j.bodyB)].rotation()) * j.pyramid.basis;
        LimitReading r{"pyramid", {}};
        for (int i = 0; i < 2; ++i)
            r.angles.push_back(symmetric(std::atan2(shaft.dot(basis.col(i)), shaft.dot(basis.col(2))), j.pyramid.halfAngles[i]));
        return r;
    }
    return std::nullopt;
}

}  // namespace

Vec3 pointOn(std::span<const RigidBody> bodies, int body, const Vec3& local) {
    if (body == kWorldBody) return local;
    const RigidBody& b = bodies[std::size_t(body)];
    return b.position + b.rotation() * local;
}

Vec3 directionOn(std::span<const RigidBody> bodies, int body, const Vec3& local) {
    return body == kWorldBody ? local : Vec3(bodies[std::size_t(body)].rotation() * local);
}

Vec3 jointAnchor(const Joint& joint, std::span<const RigidBody> bodies) { return pointOn(bodies, joint.bodyA, joint.anchorA); }

Real LimitReading::past() const {
    Real worst = 0;
    for (const Angle& a : angles) worst = std::max({worst, a.lower - a.value, a.value - a.upper});
    return worst;
}

std::vector<LimitReading> limitReadings(const Joint& joint, std::span<const RigidBody> bodies) {
    std::vector<LimitReading> out;
    switch (joint.type) {
    case ConstraintType::BallAndSocket:
        if (auto r = shaftLimit(joint, bodies)) out.push_back(*r);
        if (joint.twistHalfAngle > 0 && joint.twistHalfAngle < std::numbers::pi_v<Real>)
            out.push_back({"twist", {symmetric(twistAngle(joint, bodies), joint.twistHalfAngle)}});
        break;
    case ConstraintType::Universal:
        if (joint.cardan.enabled) {
            const std::array<Real, 2> a = cardanAngles(joint, bodies);
            LimitReading r{"cardan", {}};
            for (int k = 0; k < 2; ++k) r.angles.push_back({a[k] * kDegrees, joint.cardan.lower[k] * kDegrees, joint.cardan.upper[k] * kDegrees});
            out.push_back(r);
        } else if (auto r = shaftLimit(joint, bodies)) {
            out.push_back(*r);
        }
        break;
    case ConstraintType::Hinge:
        if (joint.limit != LimitType::None) {
            // Read around the V's centre, so an interval across ±180° reads as one stretch.
            const Real c = joint.hinge.center, angle = c + wrapRadians(hingeAngle(joint, bodies) - c);
            out.push_back({"hinge", {{angle * kDegrees, (c - joint.hinge.halfWidth) * kDegrees, (c + joint.hinge.halfWidth) * kDegrees}}});
        }
        break;
    default: break;
    }
    return out;
}

std::vector<std::pair<int, int>> treeEdges(const Figure& figure) {
    const int n = int(figure.bodies.size());
    std::vector<char> reached(std::size_t(n), 0);
    std::vector<std::pair<int, int>> edges;
    for (int root = 0; root < n; ++root) {
        if (reached[std::size_t(root)]) continue;
        reached[std::size_t(root)] = 1;
        std::vector<int> queue{root};
        for (std::size_t next = 0; next < queue.size(); ++next) {
            const int parent = queue[next];
            for (const FigureConstraint& c : figure.constraints) {
                if (c.body2 == kWorld) continue;
                const int child = c.body1 == parent ? c.body2 : c.body2 == parent ? c.body1 : -1;
                if (child < 0 || reached[std::size_t(child)]) continue;
                reached[std::size_t(child)] = 1;
                edges.emplace_back(parent, child);
                queue.push_back(child);
            }
        }
    }
    return edges;
}

std::vector<const Joint*> figureJoints(const World& world, FigureId figure) {
    const World::FigureRange own = world.range(figure);
    std::vector<char> ownedByAFigure(world.joints().size(), 0);
    for (const FigureId id : world.figureIds()) {
        const World::FigureRange r = world.range(id);
        std::fill_n(ownedByAFigure.begin() + r.firstJoint, r.jointCount, 1);
    }
    std::vector<const Joint*> out;
    for (int k = own.firstJoint; k < own.firstJoint + own.jointCount; ++k) out.push_back(&world.joints()[std::size_t(k)]);
    // A bind belongs to no figure's range; it holds body A of the figure that asked for it.
    for (std::size_t k = 0; k < world.joints().size(); ++k) {
        const Joint& j = world.joints()[k];
        if (!ownedByAFigure[k] && j.bodyA >= own.firstBody && j.bodyA < own.firstBody + own.bodyCount) out.push_back(&j);
    }
    return out;
}

}  // namespace af::console
