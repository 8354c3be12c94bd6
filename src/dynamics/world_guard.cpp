// The step's guard (world.h, step 7; docs/solver.md, "Invalid motion"): what the bodies were
// before the step, and the figures put back there when the step made their motion invalid.
//
// Figures that touched in the step (a contact or a joint between them) are judged together,
// since a collision hands energy from one to the other. A group's motion is invalid when a body
// ends the step with a non-finite pose or velocity, or when the group ends it with
//     E₁ > 2 (E₀ + W) + floor,
// E the kinetic energy plus the energy held in springs, W a bound on the work the step could do
// on it: gravity m|g|·|Δx| per body (its centre's move, whatever moved it), and each applied force
// or torque times its impulse's lever, |F| dt · max(|v₀|, |v₁|), and the energy the position
// projection stored in springs: it moves bodies that no force moved, and closing a joint or
// lifting a body out of a brush can stretch a spring (a lamp started inside the step brushes:
// 5.3e3 -> 1.6e5 with no speed at all). Contacts, joints and friction do no work and the
// projection moves no velocity, so a sound step ends with E₁ ≤ E₀ + W up to rounding; twice
// that is room for what the bounds miss (Doom's spring damping can push). The floor,
// 2 Σ m (|g| dt + slop/dt)², is the energy of the group moving at what gravity adds in a step and
// a contact slop per step: it keeps a nearly still group's rounding from tripping the factor. A
// dragged figure's group is judged by its numbers only: the drag does work that nothing here
// bounds.

#include "world_state.h"

#include "disjoint_sets.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace af {

namespace {

bool finiteMotion(const RigidBody& b) {
    return b.position.allFinite() && b.orientation.coeffs().allFinite() && b.linearVelocity.allFinite() &&
           b.angularVelocity.allFinite();
}

}  // namespace

void World::State::rememberBeforeStep() {
    before.bodies = bodies;
    before.touched.resize(figures.size() + 1);
    std::iota(before.touched.begin(), before.touched.end(), 0);
    before.jointImpulses.resize(joints.size());
    for (std::size_t k = 0; k < joints.size(); ++k) before.jointImpulses[k] = joints[k].lastImpulse;
    before.projectedSpringWork.assign(figures.size() + 1, 0);
    before.forceImpulse.resize(bodies.size());
    before.torqueImpulse.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        before.forceImpulse[i] = bodies[i].force.norm() * settings.timeStep;
        before.torqueImpulse[i] = bodies[i].torque.norm() * settings.timeStep;
    }
}

// The figures that touch in the current contacts (those of a velocity solve, or of a settle) join
// one group for the guard: a contact between them may have handed energy from one to the other.
// Groups are figure slots, and one more for the bodies of no figure.
void World::State::joinTouchingForGuard() {
    for (const ContactPoint& p : contacts.points())
        if (p.bodyA != kWorldBody && p.bodyB != kWorldBody) joinSets(before.touched, guardGroupOf(p.bodyA), guardGroupOf(p.bodyB));
}

void World::State::restoreInvalidMotion() {
    const std::size_t figureCount = figures.size();
    std::vector<int>& touched = before.touched;
    for (const Joint& j : joints)
        if (j.bodyA != kWorldBody && j.bodyB != kWorldBody) joinSets(touched, guardGroupOf(j.bodyA), guardGroupOf(j.bodyB));

    std::vector<GroupEnergy>& energy = before.energy;
    energy.assign(figureCount + 1, GroupEnergy{});
    const auto of = [&](int g) -> GroupEnergy& { return energy[static_cast<std::size_t>(findRoot(touched, g))]; };
    const Real gravity = settings.gravity.norm();
    const Real stepSpeed = gravity * settings.timeStep + settings.contact.slop / settings.timeStep;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (!bodyAwake[i]) continue;  // a resting body did not move
        const RigidBody& b0 = before.bodies[i];
        const RigidBody& b1 = bodies[i];
        GroupEnergy& e = of(guardGroupOf(static_cast<int>(i)));
        if (!finiteMotion(b1)) {
            e.nonFinite = true;
            continue;
        }
        const Real mass = b1.mass();
        e.before += b0.kineticEnergy();
        e.after += b1.kineticEnergy();
        e.work += mass * gravity * (b1.position - b0.position).norm() +
                  before.forceImpulse[i] * std::max(b0.linearVelocity.norm(), b1.linearVelocity.norm()) +
                  before.torqueImpulse[i] * std::max(b0.angularVelocity.norm(), b1.angularVelocity.norm());
        e.floor += 2 * mass * stepSpeed * stepSpeed;
    }
    // Springs hold the energy of the law the substeps applied (capped, see applySpringForces).
    const Real substep = settings.timeStep / std::max(1, settings.substeps);
    for (const Joint& j : joints) {
        if (j.type != ConstraintType::Spring) continue;
        GroupEnergy& e = of(guardGroupOf(j.bodyA != kWorldBody ? j.bodyA : j.bodyB));
        e.before += springPotentialEnergy(j, before.bodies, substep);
        e.after += springPotentialEnergy(j, bodies, substep);
    }
    for (std::size_t g = 0; g <= figureCount; ++g) of(static_cast<int>(g)).work += before.projectedSpringWork[g];
    if (drag) of(slotOfId[static_cast<std::size_t>(drag->body.figure.value)]).dragged = true;

    bool restored = false;
    for (std::size_t g = 0; g <= figureCount; ++g) {
        const GroupEnergy& e = of(static_cast<int>(g));
        const Real budget = 2 * (e.before + e.work) + e.floor;
        const bool gained = !e.dragged && !(e.after <= budget);
        if (!e.nonFinite && !gained) continue;
        restoreFigure(static_cast<int>(g));
        RestoredFigure r;
        r.figure = g < figureCount ? ids[g] : FigureId{};
        r.reason = e.nonFinite || !std::isfinite(e.after) ? InvalidMotion::NonFinite : InvalidMotion::EnergyGain;
        if (r.reason == InvalidMotion::EnergyGain) {
            r.energy = e.after;
            r.budget = budget;
        }
        report.restored.push_back(r);
        restored = true;
    }
    if (!restored) return;
    refreshAwake();
    // What the invalid step left in the caches is forgotten, and only that: others' islands keep
    // their solvers and warm starts. The contacts need nothing: the figures that rest now make
    // the next search a whole one.
    for (std::size_t k = 0; k < islandCount; ++k) {
        const std::vector<int>& islandBodies = members[k].bodies;
        if (std::any_of(islandBodies.begin(), islandBodies.end(),
                        [&](int b) { return bodyAwake[static_cast<std::size_t>(b)] == 0; }))
            islands[k] = Island{};
    }
    warmStart.forgetNonFinite();
}

// The bodies of figure slot g (or, for g = figures.size(), of no figure) as before the step,
// still; a figure let go by the drag, and at rest unless a joint is open there.
void World::State::restoreFigure(int g) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (guardGroupOf(static_cast<int>(i)) != g) continue;
        bodies[i] = before.bodies[i];
        bodies[i].linearVelocity.setZero();
        bodies[i].angularVelocity.setZero();
    }
    for (std::size_t k = 0; k < joints.size(); ++k) {
        const Joint& j = joints[k];
        const int body = j.bodyA != kWorldBody ? j.bodyA : j.bodyB;
        if (body == kWorldBody) continue;
        if (guardGroupOf(body) == g) joints[k].lastImpulse = before.jointImpulses[k];
    }
    if (g == static_cast<int>(figures.size())) return;
    if (drag && slotOfId[static_cast<std::size_t>(drag->body.figure.value)] == g) {
        drag.reset();
        useRowSources();
    }
    // Put back where a hostile start left a joint open, the figure is not at rest: it stays awake
    // to close it, and the rest test reports it stuck if it cannot. (Its contacts are not judged
    // here: those of this step were found at the poses it is taken back from.)
    if (stuckness(g).jointError <= kStuckJointError) putToRest(g);
}

}  // namespace af
