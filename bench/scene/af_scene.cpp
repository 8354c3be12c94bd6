#include "af_scene.h"

#include "af/geometry/shapes.h"

#include <numbers>

namespace benchscene {
namespace {

constexpr double kDegPerRad = 180 / std::numbers::pi;

af::Mat3 toMat(const Quat& q) { return q.normalized().toRotationMatrix(); }

af::FigureBody makeBody(const BoxBody& box, const Placement& pl, int index) {
    af::FigureBody b;
    b.name = box.name;
    b.shapeKind = af::ShapeKind::box;
    b.shape = af::makeBox(-box.halfExtents, box.halfExtents);
    b.volume = 8 * box.halfExtents.prod();
    b.mass = box.mass;
    b.inertia = boxInertia(box).asDiagonal();
    b.pose.position = placeBody(pl, index).x;
    b.pose.rotation = toMat(pl.R);
    b.linearFriction = 0;
    b.angularFriction = 0;
    b.contactFriction = kFriction;  // pairs take the smaller of their two: 0.5
    b.bounciness = 0;
    b.contents = af::contents::Corpse;
    b.clipMask = af::contents::Solid | af::contents::Corpse;
    return b;
}

af::FigureConstraint makeConstraint(const JointDef& j, const Placement& pl) {
    af::FigureConstraint c;
    c.name = j.name;
    c.body1 = j.child;
    c.body2 = j.parent;
    c.anchor = placePoint(pl, j.anchor);
    const Quat R = pl.R.normalized();
    switch (j.kind) {
        case JointKind::Fixed: c.type = af::ConstraintType::Fixed; break;
        case JointKind::Hinge:
            c.type = af::ConstraintType::Hinge;
            c.axis = R * j.axis1;
            c.limit = af::LimitType::Cone;  // a hinge's "cone" is its V limit
            // center = a3 − a1, halfWidth = a2 / 2 (joint_make.cpp).
            c.limitAngles = {0, (j.hi1 - j.lo1) * kDegPerRad, (j.lo1 + j.hi1) / 2 * kDegPerRad};
            break;
        case JointKind::Universal:
            // docs/bench-scene.md §2's universal joint is a Cardan cross with a range per axis: our Cardan
            // extension (Doom's homokinetic joint lets the arms leave ⟂). Body1, the child, carries axis 2.
            c.type = af::ConstraintType::Universal;
            c.cardan = true;
            c.shafts[0] = R * j.axis2;
            c.shafts[1] = R * j.axis1;
            c.cardanLower = {j.lo1 * kDegPerRad, j.lo2 * kDegPerRad};
            c.cardanUpper = {j.hi1 * kDegPerRad, j.hi2 * kDegPerRad};
            break;
        case JointKind::ConeTwist:
            c.type = af::ConstraintType::BallAndSocket;
            c.shafts[0] = R * j.axis2;  // the bone, on the child
            c.limit = af::LimitType::Cone;
            c.limitAxis = R * j.axis1;        // the cone axis, on the parent
            c.limitAngles = {2 * j.hi1 * kDegPerRad, 0, 0};  // Doom's cone angle is the full apex angle
            c.twistLimit = j.hi2 * kDegPerRad;                   // our extension: ±twist about the bone
            break;
    }
    return c;
}

}  // namespace

af::WorldSettings afWorldSettings(af::SolverKind solver, bool comeToRest) {
    const af::WorldSettings doom;
    af::WorldSettings s;
    s.gravity = af::Vec3(0, 0, -kGravity);
    s.timeStep = kTimeStep;
    s.substeps = 1;
    s.solver = solver;
    s.comeToRest = comeToRest;
    s.contactMargin = doom.contactMargin * kMetresPerUnit;
    s.contact.slop = doom.contact.slop * kMetresPerUnit;
    s.contact.restitutionThreshold = doom.contact.restitutionThreshold * kMetresPerUnit;
    s.impulseThreshold = doom.impulseThreshold * kMetresPerUnit;
    s.integration.maxLinearSpeed = doom.integration.maxLinearSpeed * kMetresPerUnit;
    s.rows.springLimitMargin = doom.rows.springLimitMargin * kMetresPerUnit;
    return s;
}

af::Figure afRagdoll(const Placement& pl) {
    af::Figure f;
    f.name = "bench_ragdoll";
    // Doom's rest thresholds (the .af decl defaults) with their lengths in metres; no air friction.
    af::AFSettings& s = f.settings;
    s.linearFriction = 0;
    s.angularFriction = 0;
    s.contactFriction = kFriction;
    s.suspendLinearVelocity *= kMetresPerUnit;
    s.suspendLinearAcceleration *= kMetresPerUnit;
    s.noMoveTranslation *= kMetresPerUnit;
    f.placement.rotation = toMat(pl.R);
    f.placement.position = pl.p - pl.R * kPivot;
    const auto bodies = ragdollBodies();
    for (int i = 0; i < kBodiesPerRagdoll; ++i) f.bodies.push_back(makeBody(bodies[i], pl, i));
    for (const JointDef& j : ragdollJoints()) f.constraints.push_back(makeConstraint(j, pl));
    return f;
}

af::World buildAfWorld(std::string_view scene, af::SolverKind solver, bool comeToRest, int count) {
    const std::vector<Placement> placements = scenePlacements(scene, count);
    af::World world(afWorldSettings(solver, comeToRest));
    world.addStaticPlane(af::Plane{af::Vec3::UnitZ(), 0});
    for (const Placement& pl : placements) {
        const af::FigureId figure = world.addFigure(afRagdoll(pl));
        for (int i = 0; i < kBodiesPerRagdoll; ++i) {
            const BodyState s = placeBody(pl, i);
            world.setVelocity({figure, i}, s.v, s.w);
        }
    }
    return world;
}

void readStates(const af::World& world, std::vector<BodyState>& out) {
    const auto& bodies = world.bodies();
    out.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        out[i] = {bodies[i].position, bodies[i].orientation, bodies[i].linearVelocity, bodies[i].angularVelocity};
    }
}

}  // namespace benchscene
