// SHAKE's part of an island's step (island_step.cpp): closing the drift the step's own motion
// opened in the joints, see shake.h.

#include "island.h"

#include <algorithm>
#include <utility>

namespace af {

namespace {

constexpr Real kShakeTrust = 8;          // a SHAKE move may be at most this many times its drift
constexpr Real kShakeTolerance = 1e-9;   // length units: drift this small counts as closed
constexpr Real kCheckedTurn = 0.1;       // radians a step: slower steps are not checked (keepsMoreEnergy)
constexpr Real kKeptEnergySlack = 1e-3;  // the share of kinetic energy SHAKE may add (keepsMoreEnergy)
constexpr Real kContactShakeGain = 2;     // with contacts, SHAKE is checked beyond this gain (keepsMoreEnergy)

}  // namespace

// Two Newton steps of SHAKE (shake.h) close the in-step drift, which is O(dt²) to begin with.
// They are kept only when they behave like a correction: each move at most kShakeTrust times
// the drift it closes, and the second step's drift a tenth of the first's.
// Otherwise (a long chain whipping through a large turn in one step) the step keeps its
// pre-SHAKE state and leaves the drift to the position-only pass, which can only remove energy.
// A figure turning as one body moves its hands 2.5 times its largest drift (each joint of the
// arm closes a share); with a trust of 2 the bench ragdoll's SHAKE was refused in every step
// of its fall, and the projection then let limits be crossed by 0.022 rad. Bench drop with 2 /
// 4 / 8: 32 / 1 / 0 refusals, 181 / 152 / 137 projection passes, 403M / - / 386M
// instructions, the limit crossed by 0.022 / 9e-11 / 6e-11 rad; 4 gained 0.1 J of energy.
//
// The second step reuses the first one's factors (one solve) on the errors measured without
// writing the rows (17k instructions against 35k for the bench ragdoll), and moves any drift
// the first left, however small: that remainder, about 8e-11 m a step in the bench ragdoll's
// fall, piled up past positionTolerance and sent every other step into a projection pass.
// Its move is trusted no more than the first's: a 20-link chain whipping round (world test,
// tree solver) once had a remainder below 1e-9 turned into a move that blew it apart.
//
// Returns whether it moved the bodies; if not, the joint errors are measured at the current poses.
bool Island::closeDrift(Real dt, IslandContext& context) {
    driftedLastStep_ = captureDrift(context);
    if (!driftedLastStep_) return false;
    farPointsApart_ = false;
    beforeShake_.assign(bodies_.begin(), bodies_.end());
    const ShakeCorrection::Step first = shake_.apply(rows_, ranges_, bodies_, dt, kShakeTolerance);
    measureJointErrors(context, false);
    const ShakeCorrection::Step second = shake_.applyAgain(jointErrors_, errorRanges_, bodies_, dt);
    const bool wellConditioned = first.move <= kShakeTrust * first.drift + kShakeTolerance &&
                                 second.move <= kShakeTrust * second.drift + kShakeTolerance;
    const bool converging = second.drift <= 0.1 * first.drift + kShakeTolerance;
    if (!wellConditioned || !converging || outrunsItsMove(dt, first.move + second.move) || keepsMoreEnergy(dt, context)) {
        std::copy(beforeShake_.begin(), beforeShake_.end(), bodies_.begin());
        ++context.counters.shakeRefusals;
    }
    return true;
}

// SHAKE changes each body point's velocity by its move over dt, less the share of the limits it
// holds, which moves without changing velocity (limitsToHold). Where the two shares nearly cancel
// (a figure started in a broken pose, a joint and a limit far past it pulling apart) the move is
// small and the velocity change is not: a chain of mass ratios up to 1:4430 started inside the
// step brushes (af-soak seed 1000) had SHAKE move no point more than 0.017 units at 1/162 s and
// take its kinetic energy from 5.1e3 to 5.3e6 (the guard put it back). Such a move is refused
// when it leaves more than twice the kinetic energy it found plus that of every body moving at
// the largest move per step, which no correction of that size can give.
bool Island::outrunsItsMove(Real dt, Real move) const {
    Real before = 0, after = 0, mass = 0;
    for (const RigidBody& b : beforeShake_) before += b.kineticEnergy();
    for (const RigidBody& b : bodies_) {
        after += b.kineticEnergy();
        mass += b.mass();
    }
    const Real speed = move / dt;
    return after > 2 * before + mass * speed * speed;
}

// SHAKE's velocity change along the start-of-step rows raises the kinetic energy by ½|Δv|²_M
// (the velocity solve left the velocities M-orthogonal to those rows), and the next velocity
// solve takes it back: exactly for a lone pendulum (the chord's speed along the new tangent is
// the old speed), only in part for a chain turning fast (20 links released from 45-80° gained up
// to 11 % of their energy in single steps whose end links turned 0.4 to 2 rad). So SHAKE is
// refused where its velocities, projected onto the joint rows at the moved poses (what that
// solve would keep), carry more kinetic energy than the step had before SHAKE. Over 48 release
// angles from 30 to 89° the chain then gains nothing; in half of the steps checked the two
// energies agree within 2e-5.
// Islands with contact points are checked only where SHAKE more than doubled the kinetic energy:
// the next solve's contact rows take more than the joint rows alone, and checked in every landing
// the humanoid's SHAKE was refused in 101 of 752 steps, its drops with joint friction took 9 %
// more steps to rest and failed more solves. Unchecked, a humanoid with hands 1000 times denser
// than ours had SHAKE take its kinetic energy from 1.7e4 to 2.2e5 on the ground, which the guard
// put back.
// Steps in which no body turns kCheckedTurn are not checked (the chain gains nothing with them
// unchecked); the bench ragdoll's fall pays 0.1M instructions of 204M for the others.
bool Island::keepsMoreEnergy(Real dt, const IslandContext& context) {
    Real before = 0;
    bool fast = false;
    for (const RigidBody& b : beforeShake_) {
        before += b.kineticEnergy();
        fast = fast || b.angularVelocity.norm() * dt > kCheckedTurn;
    }
    if (!fast) return false;
    if (!points_.empty()) {
        Real after = 0;
        for (const RigidBody& b : bodies_) after += b.kineticEnergy();
        if (after <= kContactShakeGain * before) return false;
    }
    writeJointRowsOnly(context);
    system_.buildResponses(rows_, bodies_, rowInertia_);
    keptEnergy_.capture(rows_, ranges_, system_);
    return keptEnergy_.keptKineticEnergy(rows_, ranges_, bodies_) > (1 + kKeptEnergySlack) * before;
}

// When the joints drifted since the velocity solve, captures its rows (rows_, responses in
// system_) for SHAKE and writes the joint rows at the moved poses for its first step; otherwise
// returns false with the joint errors measured at the poses. A resting figure has no drift: it is
// measured first, rows_ left as the velocity solve wrote them (the measure's rows are kept for
// the next step). A figure that drifted in its last step most likely drifts
// again: its rows are written at once and give the drift, the velocity solve's rows kept for the
// capture meanwhile (measuring first cost 17k instructions a step more for the bench ragdoll).
bool Island::captureDrift(const IslandContext& context) {
    if (!driftedLastStep_) {
        measureJointErrors(context);
        if (ShakeCorrection::drift(rows_, ranges_, restRows_, restRanges_) <= kShakeTolerance) return false;
        shake_.capture(rows_, ranges_, system_, limitsToHold(rows_, ranges_, restRanges_));
        writeJointRowsOnly(context);
        return true;
    }
    // writeJointRowsOnly starts rows_ and ranges_ afresh, so their old buffers can hold the
    // velocity solve's rows instead of a copy of them.
    std::swap(startRows_, rows_);
    std::swap(startRanges_, ranges_);
    writeJointRowsOnly(context);
    if (ShakeCorrection::drift(startRows_, startRanges_, rows_, ranges_) <= kShakeTolerance) {
        measureJointErrors(context);
        return false;
    }
    shake_.capture(startRows_, startRanges_, system_, limitsToHold(startRows_, startRanges_, ranges_));
    return true;
}

// Flags for ShakeCorrection::capture: the limit rows that push in the velocity solve (λ > 0), if
// the joint writes as many limit rows at the moved poses (capture checks that the rows it finds
// there turn the same way). Holding only those the move took past min(C₀, 0) measured worse
// (bench drop: 191 passes against 181; 16 ragdolls: 7e-4 J gained, ground 1.6 mm deep).
std::span<const char> Island::limitsToHold(const ConstraintRows& startRows, const std::vector<JointRowRange>& startRanges,
                                            const std::vector<JointRowRange>& moved) {
    holdLimit_.assign(startRows.size(), 0);
    const std::span<const Real> lambda = system_.solution();
    for (std::size_t k = 0; k < startRanges.size(); ++k) {
        const JointRowRange& start = startRanges[k];
        if (moved[k].limitRows != start.limitRows) continue;
        for (int r = start.equalityRows; r < start.equalityRows + start.limitRows; ++r) {
            const std::size_t i = static_cast<std::size_t>(start.first + r);
            holdLimit_[i] = lambda[i] > 0;
        }
    }
    return holdLimit_;
}

}  // namespace af
