// One island's step after velocity integration; see island.h and af/dynamics/world.h.

#include "island.h"

#include <algorithm>
#include <cmath>

namespace af {

namespace {

// A point counts as apart for leaveOutFarPoints beyond this fraction of the contact slop: a
// resting point sits at the slop, its gap zero give or take rounding, and pushes.
constexpr Real kFarGap = 0.01;
// A velocity solve may end with this share more kinetic energy than it began with, rounding, and
// count as not gaining (see gainedEnergy).
constexpr Real kEnergyRounding = 1e-9;

}  // namespace

void Island::step(Real dt, IslandContext& context) {
    if (!settingsSet_) {
        exact_.setSettings(context.tuning.exact);
        exactPosition_.setSettings(context.tuning.exact);
        tree_.setSettings(context.tuning.exact);
        pgs_.setSettings(context.tuning.pgs);
        settingsSet_ = true;
    }
    leaveOutFarPoints(dt, context);
    plainTargets_ = false;
    bool solved = solveVelocityRows(dt, context, true);
    while (bringBackClosingPoints(dt, context)) solved = solveVelocityRows(dt, context, false);
    nearPointsOnly_ = false;
    farPointsApart_ = true;
    context.report.rows += static_cast<int>(rows_.size());
    if (!solved) ++context.report.failures;
    // Doom caps the speeds after the constraint forces too (docs/doom-physics.md §4.9): a whipping chain end
    // must not outrun what one step can follow.
    for (RigidBody& b : bodies_) clampVelocity(b, context.settings.integration);

    // The joint's impulse of this step bounds its friction in the next step, as in Doom.
    const std::span<const Real> lambda = system_.solution();
    for (std::size_t k = 0; k < joints_.size(); ++k) {
        Real sum = 0;
        for (int r = 0; r < ranges_[k].equalityRows; ++r) {
            const Real l = lambda[static_cast<std::size_t>(ranges_[k].first + r)];
            sum += l * l;
        }
        joints_[k].lastImpulse = std::sqrt(sum);
    }
    velocityCache_.remember(rowKeys_, system_.states(), lambda);

    for (RigidBody& b : bodies_) {
        integratePosition(b, dt);
        applyAirFriction(b, dt);
    }
    // SHAKE's velocity change closes an O(dt²) drift. After PGS the joints hold only as far as
    // its sweeps got, the drift is O(dt), and giving it back as velocity pumps energy (a
    // resting ragdoll's head kept spinning at 5 rad/s): the projection alone removes it.
    const int passes = context.counters.projectionPasses;
    const bool jointErrorsAtPoses = !iterative(context) && !closeDrift(dt, context);
    projectPositions(context, jointErrorsAtPoses);
    farPointsApart_ = false;
    restedLastStep_ = jointErrorsAtPoses && context.counters.projectionPasses == passes;
}

void Island::project(IslandContext& context) { projectPositions(context, false); }

// Returns whether the solve succeeded; the step counts a failure only of its last solve (one
// that left out a point it needed is solved again).
bool Island::solveVelocityRows(Real dt, IslandContext& context, bool firstSolve) {
    writeRows(context, true);
    // The tree solver and PGS read the rows themselves: A is built only for the dense solve.
    system_.buildResponses(rows_, bodies_, rowInertia_);
    if (context.settings.solver == SolverKind::Exact && !large(context)) system_.buildMatrix(rows_);
    const bool plain = plainTargets_;
    if (plain) {
        std::fill(system_.states().begin(), system_.states().end(), LcpRowState::Unknown);
        std::fill(system_.solution().begin(), system_.solution().end(), Real(0));
    } else {
        context.velocityWarmStart.recall(rowKeys_, system_.states(), system_.solution());
    }
    const bool resting = firstSolve && restedLastStep_;
    system_.setVelocityRhs(rows_, bodies_, [dt, resting, plain](ConstraintRow& row, Real cdot, Real previous) {
        if (plain && isBounce(row)) row.target = 0;
        allowApproach(row, cdot, dt, resting ? previous : 0);
        if (!plain) holdDespiteSoftness(row, previous);
    });
    // A drag's rows do work on purpose: its solves are not judged.
    const bool judged = !plain && !context.extraRows;
    if (judged) rememberVelocities(velocitiesBeforeSolve_);
    const bool solved = solveVelocities(context) == LcpStatus::Solved;
    applyImpulses();
    if (judged && gainedEnergy()) {
        restoreVelocities(velocitiesBeforeSolve_);
        plainTargets_ = true;
        ++context.counters.plainResolves;
        return solveVelocityRows(dt, context, firstSolve);
    }
    return solved;
}

// With every target ≤ 0 a velocity solve cannot gain kinetic energy: its answer has λ·Cdot ≤ 0 on
// every row (a pushing contact or limit moves at its target, friction opposes the sliding it
// leaves, a joint row is held), and KE₁ − KE₀ = λᵀJv₁ − ½λᵀJM⁻¹Jᵀλ. Two kinds of target are
// positive and can make a solve gain:
// - Newton's restitution, −e times the approach, asked of each contact on its own. Through joints,
//   or for an approach the joints would have taken away in the same solve, it can ask for more
//   motion than the impact had: a lopsided humanoid's speculative chest–forearm contact kept a
//   bounce target of 149 units/s, and the solve took the figure's kinetic energy from 2.9e5 to
//   7.7e6 through its heavy arm.
// - holdDespiteSoftness' c·λ_previous, meant for a steady impulse. A chain launched into a brush
//   left a statically indeterminate loop of its fixed joint and the brush's contacts with impulses
//   of 1e10 to 1e12 (bounded only by the rows' softness): c·λ asked its joints to come apart at
//   up to 46 units/s, and the solve took 8.0e4 to 4.4e6.
// A solve that ends with more kinetic energy than it started with (beyond rounding) is done again
// with plain targets (no bounce, no hold): the impact is then inelastic, a soft row leaks as it
// would without the hold.
bool Island::gainedEnergy() const {
    Real before = 0, after = 0;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
        RigidBody body = bodies_[b];
        after += body.kineticEnergy();
        body.linearVelocity = velocitiesBeforeSolve_.linear[b];
        body.angularVelocity = velocitiesBeforeSolve_.angular[b];
        before += body.kineticEnergy();
    }
    return after > before * (1 + kEnergyRounding);
}

void Island::rememberVelocities(BodyVelocities& into) const {
    into.linear.resize(bodies_.size());
    into.angular.resize(bodies_.size());
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
        into.linear[b] = bodies_[b].linearVelocity;
        into.angular[b] = bodies_[b].angularVelocity;
    }
}

void Island::restoreVelocities(const BodyVelocities& from) {
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
        bodies_[b].linearVelocity = from.linear[b];
        bodies_[b].angularVelocity = from.angular[b];
    }
}

// Most of a resting figure's contact points are speculative ones apart by more than one step of
// its motion (the bench ragdoll at rest: 34 of 45 points, 0.3 to 25 mm apart, 102 of its 209
// rows). While the island rests (its last step neither moved by SHAKE nor projected), a point is
// left out of the velocity solve when it is apart (its normal row's error C, beyond kFarGap of
// the slop) and the last step's approach along its normal, twice over, would not close C within
// the step, and it could not bounce (its row's target would be −C/dt). That is a guess;
// bringBackClosingPoints makes the answer exact. A moving figure's
// guesses failed in most steps (bench drop: 52 of its 84 first steps solved twice), and a second
// solve costs more than the rows left out save.
void Island::leaveOutFarPoints(Real dt, const IslandContext& context) {
    nearPoints_.clear();
    farPoints_.clear();
    nearPointsOnly_ = false;
    if (!restedLastStep_) return;
    // Locals: the far points' stores might otherwise alias the settings and the points' bounds.
    const Real slop = context.settings.contact.slop;
    const Real farGap = kFarGap * slop;
    const Real restitutionThreshold = context.settings.contact.restitutionThreshold;
    const ContactPoint* const points = points_.data();
    const std::size_t count = points_.size();
    for (std::size_t k = 0; k < count; ++k) {
        const ContactPoint& p = points[k];
        // A kept point was placed at the step's start poses, which the bodies still have.
        FarPoint at = p.placed ? FarPoint{k, p.onA, p.onB}
                               : FarPoint{k, contact_detail::toWorld(contact_detail::bodyOrNull(bodies_, p.bodyA), p.localA),
                                          contact_detail::toWorld(contact_detail::bodyOrNull(bodies_, p.bodyB), p.localB)};
        at.gap = slop + p.normal.dot(at.onA - at.onB);  // slop − currentDepth, bit for bit
        const bool bounces = p.restitution > 0 && -p.approachVelocity > restitutionThreshold;
        const bool far = !bounces && at.gap > farGap &&
                         at.gap + 2 * dt * std::min(p.approachVelocity, Real(0)) > 0;
        far ? farPoints_.push_back(at) : nearPoints_.push_back(p);
    }
    if (farPoints_.empty()) return;
    nearPointsOnly_ = true;
    rememberVelocities(velocitiesAtStart_);
}

// A point left out has λ = 0 (and its friction rows, boxed by it, too), which is its part of the
// whole problem's answer when its row is complementary at λ = 0: with the velocities the solve
// gave, Cdot ≥ target = −C/dt (allowApproach; the point does not close its gap within the step,
// so no bounce either). Points that would close it are put back and the step's velocities
// restored for another solve; true if there were any.
//
// A point's gap closes in the step by at most dt · Σ (|v| + |ω|·|r|) over its two bodies (r its
// lever, |r| = |local|): a gap more than twice that, far above the rounding of the test, stays
// open, and the point's velocities need no computing (resting bench ragdoll: its 34 far points
// all so, bringBackClosingPoints 3.5k -> 2.8k instructions a step).
bool Island::bringBackClosingPoints(Real dt, const IslandContext& context) {
    const Real slop = context.settings.contact.slop;
    const std::size_t before = farPoints_.size();
    bodySpeeds_.resize(bodies_.size());
    for (std::size_t b = 0; b < bodies_.size(); ++b)
        bodySpeeds_[b] = {bodies_[b].linearVelocity.norm(), bodies_[b].angularVelocity.norm()};
    const auto reach = [&](int body, const Vec3& local) {
        if (body == kWorldBody) return Real(0);
        const BodySpeed& speed = bodySpeeds_[static_cast<std::size_t>(body)];
        return speed.linear + speed.angular * local.norm();
    };
    const auto closing = [&](FarPoint& far) {
        const ContactPoint& p = points_[far.point];
        far.staysApart = 2 * dt * (reach(p.bodyA, p.localA) + reach(p.bodyB, p.localB)) < far.gap;
        if (far.staysApart) return false;
        const RigidBody* a = contact_detail::bodyOrNull(bodies_, p.bodyA);
        const RigidBody* b = contact_detail::bodyOrNull(bodies_, p.bodyB);
        Vec3 velocity = Vec3::Zero();
        if (a) velocity += a->velocityAt(far.onA);
        if (b) velocity -= b->velocityAt(far.onB);
        if (slop + p.normal.dot(far.onA - far.onB + dt * velocity) >= 0) return false;
        nearPoints_.push_back(p);
        return true;
    };
    // A loop of its own rather than std::remove_if, whose two calls of closing GCC left out of line.
    FarPoint* const points = farPoints_.data();
    std::size_t kept = 0;
    for (std::size_t k = 0; k < before; ++k) {
        if (closing(points[k])) continue;
        if (kept != k) points[kept] = points[k];
        ++kept;
    }
    if (kept == before) return false;
    farPoints_.resize(kept);
    restoreVelocities(velocitiesAtStart_);
    return true;
}

// Limit and contact rows are written a little before they are reached (speculatively), so that
// they hold from the first step they are needed. Until the gap C > 0 is closed such a row must
// not push: it allows approaching by the gap within the step, Cdot ≥ −C/dt. A bounce
// (restitution target > 0) stays only if the bodies close the gap within this step.
// At rest (`previous`, the row's last impulse, is given only then) a pushing row's gap within
// one step's leak of its softness, dt·c·λ, is left open: closing it makes the softness hold
// (holdDespiteSoftness) of an indeterminate loop leak it again, a drift of 0.988 a step on the
// resting bench ragdoll that kept its solves from holding their guess.
void Island::allowApproach(ConstraintRow& r, Real cdot, Real dt, Real previous) {
    if (r.lo != 0 || r.frictionSource >= 0 || r.error <= 0) return;
    if (previous > 0 && r.error <= dt * r.cfm * previous) {
        r.target = std::min(r.target, Real(0));
        return;
    }
    const bool impactThisStep = -cdot * dt >= r.error;
    if (r.target > 0 && impactThisStep) return;
    r.target = std::min(r.target > 0 ? Real(0) : r.target, -r.error / dt);
}

// A row with CFM c ends its solve with Cdot = target − c·λ: a resting row leaks c·λ·dt of
// position every step, which the projection then has to take back (a limit holding a leg up
// leaked 5.5e-7 rad per step). Asking for target + c·λ_previous instead cancels the leak where
// the impulse is steady and changes nothing else by more than the CFM's share of the answer.
void Island::holdDespiteSoftness(ConstraintRow& r, Real previous) { r.target += r.cfm * previous; }

// Warm-started from the rows with the same keys in the previous step (recalled by step()). PGS
// running out of sweeps is its normal way of stopping, not a failure.
LcpStatus Island::solveVelocities(IslandContext& context) {
    std::span<Real> x = system_.solution();
    std::span<LcpRowState> states = system_.states();
    sparseAnswered_ = false;
    if (large(context)) ++context.counters.largeIslands;
    if (blocked(context))
        return solveByFigures(BlockProblem::Velocity, context,
                              context.tuning.blocks.velocityShare * context.settings.contact.slop / context.settings.timeStep);
    if (iterative(context)) {
        const LcpPgsResult r = rowPgs_.solve(rows_, system_, bodies_.size(), x, context.tuning.pgs);
        context.counters.iterations = std::max(context.counters.iterations, r.iterations);
        context.report.residual = std::max(context.report.residual, r.residual);
        return r.status == LcpStatus::NotConverged ? LcpStatus::Solved : r.status;
    }
    if (context.settings.solver == SolverKind::Tree) {
        bool frozen = false;
        if (solveWithTree(context, frozen)) return frozen ? LcpStatus::NotConverged : LcpStatus::Solved;
        ++context.counters.treeFallbacks;
        system_.buildMatrix(rows_);
    }
    const LcpProblem problem = system_.problem();
    const LcpResult r = exact_.solve(problem, x, states);
    context.counters.pivots += r.pivots;
    context.report.residual = std::max(context.report.residual, r.residual);
    if (r.status != LcpStatus::Solved) solveWithFrozenFriction(problem, context);
    return r.status;
}

// The problem in system_ (b set, its warm start recalled) by the figures' blocks.
LcpStatus Island::solveByFigures(BlockProblem problem, IslandContext& context, Real stopChange) {
    if (!blocksReady_) {
        blocks_.setStructure(bodies_, joints_);
        blocksReady_ = true;
    }
    blocks_.setPivotRowLimit(context.settings.exactRowLimit);
    const BlockSolveResult r =
        blocks_.solve(problem, rows_, ranges_, rowKeys_, system_, bodies_, context.tuning, stopChange, context.pool);
    context.counters.iterations = std::max(context.counters.iterations, r.sweeps);
    context.counters.treeFallbacks += r.treeFallbacks;
    context.report.residual = std::max(context.report.residual, r.residual);
    return r.status;
}

// The sparse path first: from the guess of the previous step's states it usually needs one
// factorisation. Then the tree solver, whose answer is the dense one, from the same guess: its own
// last solve is as old as the sparse path's last give-up (our humanoid on the default map, from
// it: 12 tree solves of 69 to 3410 pivots, two of them and the dense solve after them
// NotConverged). Its impulses go where the dense solve's would, so that applying them and SHAKE
// work alike. False when neither can serve these rows. A tree solve whose coupled friction did
// not settle serves, on an island beyond SolverTuning::denseRescueRows, with its frozen-box
// answer: `frozen` then says the solve failed (counted as a failure), though joints hold.
// An island without contact points (in the air) goes to the tree at once: its LCP holds only
// limit rows, and the sparse path factorised every step (a refinement gains only ω·dt; bench
// ragdoll's fall: w 1e-6 after one, tolerance 1e-11; 203k instructions against the tree's 107k).
bool Island::solveWithTree(IslandContext& context, bool& frozen) {
    frozen = false;
    if (!points_.empty() && solveSparse(context.velocityWarmStart, context)) return true;
    if (!treeReady_) {
        tree_.setStructure(bodies_, joints_);
        treeReady_ = true;
    }
    tree_.factor(rows_, ranges_, bodies_, TreeProblems::VelocityAndPosition, rowKeys_);
    const TreeSolveResult r = tree_.solveVelocity(rows_, bodies_, system_.states(), system_.solution());
    frozen = r.status != LcpStatus::Solved && r.frozenAnswer && rows_.size() > context.tuning.denseRescueRows;
    if (r.status != LcpStatus::Solved && !frozen) return false;
    const std::span<const Real> lambda = tree_.impulses();
    std::copy(lambda.begin(), lambda.end(), system_.solution().begin());
    statesFromImpulses(context);
    context.counters.pivots += r.pivots;
    context.report.residual = std::max(context.report.residual, r.residual);
    return true;
}

// The sparse path (sparse_lcp.h) on the problem in system_, from the states and impulses there
// (recalled from `guess`), with the exact solver's tolerance. When it gives up, the guess is put
// back for the solver that takes over, and the give-up is counted.
bool Island::solveSparse(const WarmStartCache& guess, IslandContext& context) {
    std::span<Real> x = system_.solution();
    std::span<LcpRowState> states = system_.states();
    const SparseLcpResult r =
        sparse_.solve(rows_.all(), system_.responses(), system_.problem(), bodies_, x, states, context.tuning.exact);
    if (r.status == LcpStatus::Solved) {
        context.report.residual = std::max(context.report.residual, r.residual);
        sparseAnswered_ = true;
        return true;
    }
    ++context.counters.sparseFallbacks;
    guess.recall(rowKeys_, states, x);
    return false;
}

// The row states of the impulses in system_ (the tree solver keeps its own), so that the next
// solve's guess, which the sparse path starts from, is this answer.
void Island::statesFromImpulses(const IslandContext& context) {
    af::statesFromImpulses(rows_, system_.solution(), system_.states(), context.tuning.exact.tolerance);
}

// Never apply the impulses of a failed pivoting solve: the failure is counted, and the step goes
// on with the frozen-box answer (frozen_boxes.h), PGS started from the warm start.
void Island::solveWithFrozenFriction(const LcpProblem& problem, IslandContext& context) {
    std::span<Real> x = system_.solution();
    std::span<LcpRowState> states = system_.states();
    context.velocityWarmStart.recall(rowKeys_, states, x);
    const FrozenBoxResult r = frozenBoxes_.solve(problem, x, states, exact_, pgs_);
    context.counters.iterations = std::max(context.counters.iterations, r.estimate.iterations);
    context.report.residual = std::max(context.report.residual, r.estimate.residual);
    if (r.frozen.status == LcpStatus::Solved) context.report.residual = std::max(context.report.residual, r.frozen.residual);
}

// A settling figure's contacts cost as much to write as its joints, and SHAKE moves along the
// joints alone. Each body's rotation once, for its inertia and every joint side it has, rather
// than once for each (the bench ragdoll: 16 rotations instead of 46 per write).
void Island::writeJointRowsOnly(const IslandContext& context) {
    rows_.clear();
    ranges_.clear();
    rowKeys_.clear();
    rowRotations_.resize(bodies_.size());
    for (std::size_t b = 0; b < bodies_.size(); ++b) rowRotations_[b] = bodies_[b].rotation();
    rowInertia_ = system_.inverseInertiasWorld(bodies_, rowRotations_);
    for (const Joint& joint : joints_)
        ranges_.push_back(writeJointRows(joint, bodies_, rowRotations_, rowInertia_, context.settings.rows, rows_));
}


}  // namespace af
