// The position projection of an island's step (island_step.cpp): moving positions only, so that
// what the step leaves violated is removed without adding energy.

#include "island.h"

#include <algorithm>
#include <cmath>

namespace af {

namespace {

// See projectPositions. 4 was one too few: af-sim --seed 15 lands with its forearm turning 85 rad/s,
// SHAKE is refused and the projection starts from 4.4 units of drift; its fourth pass lowered the
// largest violation at no halving down to 1/16 (3.535 -> 3.549) and the projection gave up with the
// joints 4.9 units open for a step. A fifth halving (1/32) lowers it (3.479), and the passes
// after it close the joints (6.5e-11 over the drop).
constexpr int kProjectionHalvings = 5;
// Below it a pass's leftover is chord-stepped (see chordStep). The chord's answer differs from the
// full pass's by about the leftover times the move: from 3e-6 bench single cost 204.7M (against
// 205.7M from here), but the tree's poses strayed 1e-9 from the dense solve's over a nudged
// humanoid's step, and from 1e-4 the steps, slower to converge, cost more than the passes spared.
constexpr Real kChordViolation = 3e-7;
// A move the full linear answer asks for that does not lower the violation is next cut so that no
// body turns more than this (radians), then halved: a turn's linearisation is good to about a
// radian, and a light torso whipped between heavy hands asked for a move 70 times too large
// (largest violation 4.9 -> 336 units, 5.8 after five halvings; the joints then stayed open for
// steps). Cutting every move to 0.5 rad at once changed which landings failed a solve; with 2 rad
// af-soak's seed 6951 (a humanoid of mass ratios up to 1:284) opened by 6.0 units, at 1 rad 0.63.
constexpr Real kTrustedTurn = 1.0;

}  // namespace

// Whatever remains (joint errors older than the step, limit and contact penetration, drift
// SHAKE refused) is removed by moving positions only, so correcting it never adds energy. Each
// pass solves the linearised problem J M⁻¹ Jᵀ Δ = −C and moves along it as far as that reduces
// the largest violation (moveWhileImproving: the whole move, or one cut to kTrustedTurn and
// halved up to kProjectionHalvings times): with large errors,
// or rows that nearly contradict each other (a limb pinned between another figure and its own
// joint), the full linear move can overshoot and tear joints open instead of closing them.
//
// The violation is measured without writing the rows (unless an extra source adds rows of its
// own), before the first pass and after every move: most steps need no pass, and the last pass
// of a step leaves a violation below the tolerance, whose rows would go unread (bench drop:
// 275.6M -> 274.1M instructions, the same answers). A figure that projected in its last step
// and has moved since (SHAKE) most likely projects again: its rows are written at once, and
// their largest violation is the measured one's bits.
void Island::projectPositions(IslandContext& context, bool jointErrorsAtPoses) {
    const int passes = context.counters.projectionPasses;
    const Real springEnergyBefore = springEnergy(context);
    const bool springs =
        std::any_of(joints_.begin(), joints_.end(), [](const Joint& j) { return j.type == ConstraintType::Spring; });
    if (springs) projectionStart_.assign(bodies_.begin(), bodies_.end());
    bool rowsAtPoses = context.extraRows || (!jointErrorsAtPoses && projectedLastStep_);
    Real violation = 0;
    if (rowsAtPoses) {
        writeNormalsOnly();
        writeRows(context);
        violation = largestViolation();
    } else {
        violation = jointErrorsAtPoses ? measuredViolation(context) : violationAtPoses(context);
    }
    bool factored = false;  // the tree's factors are those of this projection's last full pass
    for (int pass = 0; pass < context.settings.positionIterations && violation > context.settings.positionTolerance; ++pass) {
        if (factored && violation < kChordViolation && chordStep(violation, context)) {
            ++context.counters.projectionPasses;
            continue;
        }
        factored = false;
        if (!rowsAtPoses) {
            if (!nearPointsOnly_) writeNormalsOnly();
            writeRows(context);
        }
        rowsAtPoses = static_cast<bool>(context.extraRows);
        ++context.counters.projectionPasses;
        holdFrictionAtZero(rows_, ranges_);
        system_.buildResponses(rows_, bodies_, rowInertia_);
        shiftsOfSolution_ = false;
        if (blocked(context)) {
            system_.setPositionRhs(rows_);
            positionCache_.recall(rowKeys_, system_.states(), system_.solution());
            // The contacts between figures are iterated to a share of the violation the pass
            // removes (each pass then removes most of what is left), not to the tolerance at once.
            const Real stopChange =
                std::max(context.settings.positionTolerance, context.tuning.blocks.positionShare * violation);
            if (solveByFigures(BlockProblem::Position, context, stopChange) != LcpStatus::Solved)
                ++context.report.failures;
            positionCache_.remember(rowKeys_, system_.states(), system_.solution());
        } else if (large(context)) {
            system_.setPositionRhs(rows_);
            std::span<Real> x = system_.solution();
            positionCache_.recall(rowKeys_, system_.states(), x);
            rowPgs_.solve(rows_, system_, bodies_.size(), x, context.tuning.pgs);
            positionCache_.remember(rowKeys_, system_.states(), x);
        } else if (solvePositionsWithTree(context, violation)) {
            factored = !context.extraRows;
        } else {
            system_.buildMatrix(rows_);
            system_.setPositionRhs(rows_);
            if (solvePositions() != LcpStatus::Solved) ++context.report.failures;
        }
        if (!moveWhileImproving(violation, context)) break;
    }
    projectedLastStep_ = context.counters.projectionPasses != passes;
    nearPointsOnly_ = false;
    if (!projectedLastStep_) return;
    const Real stored = springEnergy(context) - springEnergyBefore;
    if (springs && violation > context.settings.positionTolerance && stored > liftWork(context)) {
        std::copy(projectionStart_.begin(), projectionStart_.end(), bodies_.begin());
        return;
    }
    context.projectedSpringWork += std::max(Real(0), stored);
}

// What lifting each body as far as the projection moved it (from projectionStart_) would cost
// against gravity: the most an unfinished projection may store in springs. One that ends above
// the tolerance has found no pose where the island's rows hold (a lamp started inside a brush
// that its spring's world anchor holds it in); stretching a spring on that search stores energy
// that comes back as motion nothing paid for (af-soak seed 7937: two passes lowered the largest
// violation 23.5 -> 15.8 and took the spring 13 -> 9.0e5, which flung the lamp at 3.4e5 the
// next step, 15 times what the start and gravity could supply). Beyond this bound the moves are
// undone: the figure stays where the step left it, and the rest test reports it stuck. A
// projection that closes what it was given is not bound: closing a joint must stretch the
// spring that pulls it open, whatever that stores.
Real Island::liftWork(const IslandContext& context) const {
    const Real g = context.settings.gravity.norm();
    Real work = 0;
    for (std::size_t k = 0; k < bodies_.size(); ++k)
        work += bodies_[k].mass() * g * (bodies_[k].position - projectionStart_[k].position).norm();
    return work;
}

// The energy of the island's springs at the bodies' poses, by the law the substep applies (capped,
// see applySpringForces).
Real Island::springEnergy(const IslandContext& context) const {
    const Real substep = context.settings.timeStep / std::max(1, context.settings.substeps);
    Real energy = 0;
    for (const Joint& j : joints_)
        if (j.type == ConstraintType::Spring) energy += springPotentialEnergy(j, bodies_, substep);
    return energy;
}

// The position problem holds contact friction rows at 0 (holdFrictionAtZero): their λ is 0 and
// they move nothing, so the projection's writeRows leaves them out, through nearPoints_ (the
// points' copies without friction write their normal rows alone, under the same keys). Writing,
// responses, the tree's classification and the moves skipped them for nothing: bench drop,
// 45 points and 90 friction rows in a settling step's pass.
void Island::writeNormalsOnly() {
    nearPoints_.assign(points_.begin(), points_.end());
    for (ContactPoint& p : nearPoints_) p.friction = 0;
    nearPointsOnly_ = true;
}

// The largest violation at the bodies' poses. With an extra source the rows are written (its
// rows come only with them) and stay for the next pass.
Real Island::violationAtPoses(IslandContext& context) {
    if (context.extraRows) {
        writeRows(context);
        return largestViolation();
    }
    measureJointErrors(context);
    return measuredViolation(context);
}

// A pass on the last full pass's rows and factors with the errors measured at the moved poses (a
// chord step): after a pass the violation left is a small leftover of the linearisation, and the
// rows a move that small away differ from these by about as little, so the answer converges
// linearly at a rate of about the move's relative size, one or two steps from 1e-6 to the
// tolerance, without writing the rows, their responses or refactoring (bench single: a chord
// step ~80k instructions, mostly the LCP's solve and the re-measure). The joint errors are those
// violationAtPoses measured (the rows writeRows would write), the contact rows' those of their
// points. False, with the bodies where they were, when the rows at the poses are not these (a
// limit row came or went), the tree fails, a row left out of the LCP would be violated, or the
// move does not lower the largest violation: a full pass follows.
bool Island::chordStep(Real& violation, IslandContext& context) {
    // The last measure's errors: the kept rows' (measureJointErrors with keepRows) or the bare errors.
    const std::vector<JointRowRange>& measuredRanges = restRowsHeld_ ? restRanges_ : errorRanges_;
    if (measuredRanges.size() != ranges_.size()) return false;
    for (std::size_t k = 0; k < ranges_.size(); ++k) {
        const JointRowRange& a = ranges_[k];
        const JointRowRange& b = measuredRanges[k];
        if (a.first != b.first || a.equalityRows != b.equalityRows || a.limitRows != b.limitRows ||
            a.frictionRows != b.frictionRows)
            return false;
    }
    const std::span<const ContactPoint> points = nearPointsOnly_ ? nearPoints_ : points_;
    const std::size_t jointRows = restRowsHeld_ ? restRows_.size() : jointErrors_.size();
    if (rows_.size() != jointRows + points.size()) return false;
    for (std::size_t i = 0; i < jointRows; ++i) rows_[i].error = restRowsHeld_ ? restRows_[i].error : jointErrors_[i].error;
    for (std::size_t k = 0; k < points.size(); ++k) {
        if (points[k].friction > 0) return false;
        rows_[jointRows + k].error = context.settings.contact.slop - currentDepth(points[k], bodies_);
    }
    if (tree_.solvePositionImpulses(rows_).status != LcpStatus::Solved || putBackViolated()) return false;
    const std::span<const Real> lambda = tree_.impulses();
    std::copy(lambda.begin(), lambda.end(), system_.solution().begin());
    statesFromImpulses(context);
    positionCache_.remember(rowKeys_, system_.states(), system_.solution());
    shiftsOfSolution_ = true;
    return moveWhileImproving(violation, context);
}

// Applies the solved displacements, whole or cut (kTrustedTurn, then halved) until the largest
// violation drops below `violation`;
// on success updates `violation`, otherwise puts the bodies back and returns false. Without an
// extra source the rows stay those of the poses before the move.
bool Island::moveWhileImproving(Real& violation, IslandContext& context) {
    beforeProjection_.assign(bodies_.begin(), bodies_.end());
    if (!shiftsOfSolution_) {
        shiftLinear_.resize(bodies_.size());
        shiftAngular_.resize(bodies_.size());
        accumulateResponses(rows_.all(), system_.responses(), system_.solution(), shiftLinear_, shiftAngular_);
    }
    Real turn = 0;
    for (const Vec3& w : shiftAngular_) turn = std::max(turn, w.norm());
    Real scale = 1;
    for (int attempt = 0; attempt <= kProjectionHalvings; ++attempt, scale = std::min(scale / 2, kTrustedTurn / turn)) {
        for (std::size_t k = 0; k < bodies_.size(); ++k)
            displaceBody(bodies_[k], scale * shiftLinear_[k], scale * shiftAngular_[k]);
        const Real after = violationAtPoses(context);
        if (after < violation) {
            violation = after;
            return true;
        }
        std::copy(beforeProjection_.begin(), beforeProjection_.end(), bodies_.begin());
    }
    if (context.extraRows) writeRows(context);
    return false;
}

// Equality rows violate by |C|, one-sided rows (lo = 0: limits, contacts) only when C < 0.
Real Island::largestViolation() const {
    Real worst = 0;
    for (std::size_t i = 0; i < rows_.size(); ++i) {
        const ConstraintRow& r = rows_[i];
        if (r.frictionSource >= 0 || (r.lo == 0 && r.hi == 0)) continue;
        worst = std::max(worst, r.lo == 0 ? -r.error : std::abs(r.error));
    }
    return worst;
}

// Warm-started from the pattern of the last position solve (the previous pass, or the previous
// step's last pass): resting contacts and limits keep their pattern from pass to pass.
LcpStatus Island::solvePositions() {
    std::span<LcpRowState> states = system_.states();
    std::span<Real> x = system_.solution();
    positionCache_.recall(rowKeys_, states, x);
    const LcpStatus status = exactPosition_.solve(system_.problem(), x, states).status;
    if (status != LcpStatus::Solved) {
        // As for velocities: a failed pivoting solve's displacements may be far from any
        // solution, and moving bodies by them can tear a figure apart. PGS's are bounded.
        positionCache_.recall(rowKeys_, states, x);
        pgs_.solve(system_.problem(), x);
    }
    positionCache_.remember(rowKeys_, states, x);
    return status;
}

// The tree solver's position answer, as the dense one's would be (see solveWithTree). It
// factorises the rows without friction rows, which the position problem holds at 0, so its
// auxiliary LCP holds only the contact normals and limits; the sparse path, which velocities
// try first, carries the held friction rows through its factorisations and trials and cost
// twice as much here (bench drop, 193 passes: 102M against 56M instructions, same answers).
// False when the tree cannot serve these rows (the fallback is counted) or is not the chosen
// solver.
//
// One-sided rows (contacts, limits) apart by more than `violation`, the largest violation the
// pass removes, are left out of the LCP first (held at 0, which the tree leaves out of its
// Schur complement): many of a figure's speculative contacts are far apart next to the move,
// which is of the size of the violation (bench drop: about half of them in a first pass, most in
// the passes after it; the projection's instructions 82M -> 60M). The answer stands when none of
// them is violated by the linear move (C + JΔ ≥ 0): it is then the whole problem's, those rows at
// 0 with w ≥ 0. Rows that would be violated are put back and the problem solved again.
bool Island::solvePositionsWithTree(IslandContext& context, Real violation) {
    if (context.settings.solver != SolverKind::Tree) return false;
    if (!treeReady_) {
        tree_.setStructure(bodies_, joints_);
        treeReady_ = true;
    }
    leftOut_.clear();
    for (std::size_t i = 0; i < rows_.size(); ++i) {
        ConstraintRow& r = rows_[i];
        if (r.lo != 0 || !(r.hi > 0) || r.error <= violation) continue;
        leftOut_.push_back({i, r.hi});
        r.hi = 0;
    }
    bool solved = true;
    do {
        tree_.factor(rows_, ranges_, bodies_, TreeProblems::PositionOnly, rowKeys_);
        solved = tree_.solvePositionImpulses(rows_).status == LcpStatus::Solved;
    } while (solved && putBackViolated());
    for (const HeldRow& held : leftOut_) rows_[held.row].hi = held.hi;
    if (!solved) {
        ++context.counters.treeFallbacks;
        return false;
    }
    const std::span<const Real> lambda = tree_.impulses();
    std::copy(lambda.begin(), lambda.end(), system_.solution().begin());
    statesFromImpulses(context);
    positionCache_.remember(rowKeys_, system_.states(), system_.solution());
    shiftsOfSolution_ = true;
    return true;
}

// The rows left out that the tree's answer would violate (w = C + J M⁻¹Jᵀλ < 0, through the
// responses in system_) get their bounds back; returns whether there were any. The move M⁻¹Jᵀλ
// it sums is the one moveWhileImproving first tries, bit for bit (same rows, same order).
bool Island::putBackViolated() {
    shiftLinear_.resize(bodies_.size());
    shiftAngular_.resize(bodies_.size());
    accumulateResponses(rows_.all(), system_.responses(), tree_.impulses(), shiftLinear_, shiftAngular_);
    const auto violated = [&](const HeldRow& held) {
        ConstraintRow& r = rows_[held.row];
        if (r.error + rowAlong(r, shiftLinear_, shiftAngular_) >= 0) return false;
        r.hi = held.hi;
        return true;
    };
    const std::size_t before = leftOut_.size();
    leftOut_.erase(std::remove_if(leftOut_.begin(), leftOut_.end(), violated), leftOut_.end());
    return leftOut_.size() != before;
}

}  // namespace af
