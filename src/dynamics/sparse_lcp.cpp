#include "sparse_lcp.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace af {

namespace {

// Times the dense core may grow by the rows its answer finds wrong outside it.
constexpr int kCoreRounds = 4;
// A guess is kept when its free rows' w are within this fraction of the tolerance. What a kept
// guess leaves undone comes back about three times larger in the next step, so a larger fraction
// keeps more steps in a row before a solve (see guessHolds). Bench single / grid4, 600 steps,
// millions of instructions: 219.4 / - with 0.1, 218.8 / 5321 with 0.25, 218.5 / 5315 with 0.5,
// 218.1 / 5309 with the whole tolerance. (When a resting figure still drifted, before 72b81dc,
// a quarter was best: 573k per resting step against 654k with the whole tolerance.)
constexpr Real kHoldFraction = 1;

Real mid(Real lo, Real hi, Real v) { return std::min(hi, std::max(lo, v)); }

}  // namespace

void SparseLcpSolver::bounds(const LcpProblem& problem, std::span<const Real> x) {
    for (std::size_t i = 0; i < lo_.size(); ++i) bound(problem, x, i);
}

void SparseLcpSolver::bound(const LcpProblem& problem, std::span<const Real> x, std::size_t i) {
    const int s = source(problem, i);
    if (s >= 0) {
        const Real box = problem.mu[i] * std::abs(x[static_cast<std::size_t>(s)]);
        lo_[i] = -box;
        hi_[i] = box;
    } else {
        lo_[i] = problem.lo[i];
        hi_[i] = problem.hi[i];
    }
}

// The bodies' velocity change M⁻¹Jᵀx of the rows with use[i] (all rows if use is empty).
void SparseLcpSolver::velocityChange(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                                     std::span<const Real> x, std::span<const std::uint8_t> use) {
    std::fill(linear_.begin(), linear_.end(), Vec3::Zero());
    std::fill(angular_.begin(), angular_.end(), Vec3::Zero());
    // The sums' storage and each row's x and bodies are read once into locals: Eigen's vector
    // stores may alias anything, so the compiler read them again after every store otherwise.
    Vec3* const linear = linear_.data();
    Vec3* const angular = angular_.data();
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Real xi = x[i];
        if (xi == 0 || (!use.empty() && !use[i])) continue;
        const ConstraintRow& r = rows[i];
        const RowResponse& m = responses[i];
        const int a = r.bodyA, b = r.bodyB;
        if (a != kWorldBody) {
            linear[a] += xi * m.linearA;
            angular[a] += xi * m.angularA;
        }
        if (b != kWorldBody) {
            linear[b] += xi * m.linearB;
            angular[b] += xi * m.angularB;
        }
    }
}

// x_F = A_FF⁻¹ (b_F − A_F,fixed x_fixed) for the free rows, from the rows marked in use_.
void SparseLcpSolver::solveFree(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                                std::span<const Real> b, std::span<const Real> x, std::span<Real> out) {
    velocityChange(rows, responses, x, use_);
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (free_[i]) out[i] = b[i] - along(rows[i]);
    factor_.solve(out);
}

SparseLcpResult SparseLcpSolver::solve(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                                       const LcpProblem& problem, std::span<const RigidBody> bodies, std::span<Real> x,
                                       std::span<LcpRowState> states, const LcpExactSettings& settings) {
    SparseLcpResult result;
    const std::size_t n = rows.size();
    if (n == 0) {  // nothing to solve, and no velocity change
        linear_.assign(bodies.size(), Vec3::Zero());
        angular_.assign(bodies.size(), Vec3::Zero());
        return result;
    }
    if (!factor_.analyse(rows, bodies)) {
        refinable_ = false;
        result.status = LcpStatus::InvalidInput;
        return result;
    }
    lo_.resize(n);
    hi_.resize(n);
    w_.resize(n);
    rhs_.resize(n);
    next_.resize(n);
    use_.resize(n);
    linear_.resize(bodies.size());
    angular_.resize(bodies.size());

    Real bScale = 1;
    bool guessComplete = true;
    for (std::size_t i = 0; i < n; ++i) {
        bScale = std::max(bScale, std::abs(problem.b[i]));
        if (states[i] == LcpRowState::Free) continue;  // known, and what an unbounded row gets anyway
        const bool unknown = states[i] == LcpRowState::Unknown || states[i] == LcpRowState::Failed;
        guessComplete = guessComplete && !unknown;
        const bool lower = std::isfinite(problem.lo[i]) || source(problem, i) >= 0;
        const bool upper = std::isfinite(problem.hi[i]) || source(problem, i) >= 0;
        if (!lower && !upper) {
            states[i] = LcpRowState::Free;
        } else if (unknown && source(problem, i) >= 0) {
            states[i] = LcpRowState::Unknown;  // guessed below, from its normal's guess
        } else if (unknown) {
            // A new contact or limit pushes when it is closing (w = −b < 0 before any impulse).
            const bool closing = lower ? problem.b[i] > 0 : problem.b[i] < 0;
            states[i] = (lower && upper) || closing ? LcpRowState::Free : lower ? LcpRowState::AtLower : LcpRowState::AtUpper;
        }
    }
    // A new friction row sticks when its normal pushes; otherwise its box is empty. (A complete
    // guess has no new rows.)
    for (std::size_t i = 0; i < n && !guessComplete; ++i) {
        if (states[i] != LcpRowState::Unknown) continue;
        const bool normalPushes = states[static_cast<std::size_t>(source(problem, i))] == LcpRowState::Free;
        states[i] = normalPushes ? LcpRowState::Free : LcpRowState::AtLower;
    }
    const Real wTolerance = settings.tolerance * bScale;

    // A figure at rest meets the same problem as in its last step, up to rounding: the last
    // impulses are still the answer within the tolerance, and nothing needs factorising.
    if (guessComplete && guessHolds(rows, responses, problem, x, states, wTolerance, settings.tolerance)) {
        const Real gap = boundGap_;
        finish(x, states, result);
        boundGap_ = gap;  // the reference stays the last solve's
        return result;
    }
    if (guessComplete && refine(rows, responses, problem, x, states, wTolerance, settings.tolerance)) {
        result.refined = true;
        return finish(x, states, result);
    }

    // One trial, the guess's pattern. When it does not hold, the rows its check finds wrong choose
    // the core (with the sliding friction rows and their normals, see markCore), and the core's
    // pivoting starts from the guess's states; a later round's from the last core's answer. The
    // trial's switches (every wrong row at once, a friction row's state guessed from its normal's)
    // only tell markCore which rows slide then: single pivots repair the guess better than the
    // switched pattern, and a second trial solving that pattern, which this path had until the
    // seventeenth session, cost more than it spared. Bench single, 600 steps: 258.8M instructions
    // with a second trial after more than 32 wrong rows and the core started from the switches,
    // 250.2M with the core started from the guess, 249.2M without the second trial; grid4 4855M,
    // 4770M, 4757M; af-sim seeds 0-40: 3405 steps and a failed solve, then 3366 and none.
    guessStates_.assign(states.begin(), states.end());
    free_.assign(n, 2);  // neither free nor clamped: the trial factorises
    refinable_ = false;
    result.trials = 1;
    if (!solvePattern(rows, responses, problem, x, states, result)) return result;
    if (check(rows, responses, problem, x, states, wTolerance, settings.tolerance) == 0) {
        refinable_ = true;
        slidingAnswersKept_ = false;
        return finish(x, states, result);
    }
    switched_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        if (next_[i] == states[i]) continue;
        states[i] = next_[i];
        switched_[i] = 1;
    }
    // A friction row whose normal stops pushing has nothing to push with; when the normal
    // pushes again it starts sticking.
    for (std::size_t i = 0; i < n; ++i) {
        const int s = source(problem, i);
        if (s < 0) continue;
        const bool normalPushes = states[static_cast<std::size_t>(s)] == LcpRowState::Free;
        if (!normalPushes && x[static_cast<std::size_t>(s)] == 0) states[i] = LcpRowState::AtLower;
        if (normalPushes && states[i] == LcpRowState::AtLower && lo_[i] == hi_[i]) states[i] = LcpRowState::Free;
    }
    // The core, grown by the rows its answer finds wrong outside it, until it holds or is too large.
    for (int round = 0; round < kCoreRounds; ++round) {
        result.coreRounds = round + 1;
        const std::span<const LcpRowState> coreGuess = round == 0 ? std::span<const LcpRowState>(guessStates_) : states;
        const int wrong = solveCore(rows, responses, problem, x, states, coreGuess, wTolerance, settings, result);
        if (wrong == 0) return finish(x, states, result);
        if (wrong < 0) break;
        for (std::size_t i = 0; i < n; ++i)
            if (next_[i] != states[i]) {
                states[i] = next_[i];
                switched_[i] = 1;
            }
    }
    result.status = LcpStatus::NotConverged;
    return result;
}

// w of every row at x into w_, with the velocity change of x in linear_ and angular_.
void SparseLcpSolver::measureW(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                               const LcpProblem& problem, std::span<const Real> x) {
    velocityChange(rows, responses, x, {});
    for (std::size_t i = 0; i < rows.size(); ++i)
        w_[i] = along(rows[i]) + (problem.cfm.empty() ? 0 : problem.cfm[i]) * x[i] - problem.b[i];
}

// How far from a bound row i's x may be and still count as at it.
Real SparseLcpSolver::xTolerance(std::size_t i, Real tolerance) const {
    return tolerance * std::max({Real(1), std::isfinite(lo_[i]) ? std::abs(lo_[i]) : 0, std::isfinite(hi_[i]) ? std::abs(hi_[i]) : 0});
}

// Whether x, as given, is an answer with these states: every row complementary within the
// tolerance (free rows with w = 0, within kHoldFraction of it, inside their box; the others on
// their bound with w pointing away from it). A sliding friction row is as close to its box as
// the last solve left it (its impulse and its normal's come from two solves, and redundant
// contacts make A ill-conditioned: about 1e-9 on the resting bench ragdoll), so rows at a bound
// may be off it by twice that. Leaves w_ as check() does, and the bounds when the guess holds.
bool SparseLcpSolver::guessHolds(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                                 const LcpProblem& problem, std::span<const Real> x, std::span<const LcpRowState> states,
                                 Real wTolerance, Real tolerance) {
    measureW(rows, responses, problem, x);
    // What a kept guess leaves undone comes back about three times larger in the next step, and a
    // single solve settles only that step: the next keeps its guess and the one after refuses it,
    // every other step whatever kHoldFraction is (bench ragdoll, a soft joint row: 1.6e-12 kept,
    // 4.8e-12 refused). The step after a refusal solves too, which settles the figure to rounding
    // (3e-14), and the guess then holds for several steps: bench single 224.6M -> 218.8M
    // instructions, grid4 5472M -> 5321M (with a quarter of the tolerance).
    if (std::exchange(guessRefused_, false)) return false;
    const auto holds = [&](std::size_t i) {
        const Real atBound = xTolerance(i, tolerance), gap = std::max(atBound, 2 * boundGap_);
        return states[i] == LcpRowState::Free
                   ? std::abs(w_[i]) <= kHoldFraction * wTolerance && x[i] >= lo_[i] - atBound && x[i] <= hi_[i] + atBound
               : states[i] == LcpRowState::AtLower
                   ? std::abs(x[i] - lo_[i]) <= gap && (lo_[i] == hi_[i] || w_[i] >= -wTolerance)
                   : std::abs(x[i] - hi_[i]) <= gap && (lo_[i] == hi_[i] || w_[i] <= wTolerance);
    };
    // Whether every row holds does not depend on the order they are asked in. A resting figure's
    // guess fails step after step at the same row, far down the list: asked first, it saves the
    // bench ragdoll 1.2k of its 205k instructions per step. Its bounds alone are needed for that
    // (refine() and the trial take theirs from check()): 1.3k more of 191k.
    if (lastMiss_ < rows.size()) {
        bound(problem, x, lastMiss_);
        if (!holds(lastMiss_)) {
            guessRefused_ = true;
            return false;
        }
    }
    bounds(problem, x);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (holds(i)) continue;
        lastMiss_ = i;
        guessRefused_ = true;
        return false;
    }
    return true;
}

// w of every row at x, the bounds at x, and the state each row wants (next_); returns how many
// rows are in the wrong state.
int SparseLcpSolver::check(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                           const LcpProblem& problem, std::span<const Real> x, std::span<const LcpRowState> states,
                           Real wTolerance, Real tolerance) {
    measureW(rows, responses, problem, x);
    int wrong = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        bound(problem, x, i);
        LcpRowState want = states[i];
        if (states[i] == LcpRowState::Free) {
            const Real atBound = xTolerance(i, tolerance);
            if (x[i] < lo_[i] - atBound) want = LcpRowState::AtLower;
            if (x[i] > hi_[i] + atBound) want = LcpRowState::AtUpper;
        } else if (states[i] == LcpRowState::AtLower && lo_[i] != hi_[i] && w_[i] < -wTolerance) {
            want = LcpRowState::Free;
        } else if (states[i] == LcpRowState::AtUpper && lo_[i] != hi_[i] && w_[i] > wTolerance) {
            want = LcpRowState::Free;
        }
        next_[i] = want;
        if (want != states[i]) ++wrong;
    }
    return wrong;
}

// The natural residual of the answer, from the w and bounds check() left, and how far its rows at
// a bound are off it (boundGap_, for guessHolds).
SparseLcpResult& SparseLcpSolver::finish(std::span<const Real> x, std::span<const LcpRowState> states,
                                         SparseLcpResult& result) {
    boundGap_ = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        result.residual = std::max(result.residual, std::abs(x[i] - mid(lo_[i], hi_[i], x[i] - w_[i])));
        if (states[i] == LcpRowState::AtLower) boundGap_ = std::max(boundGap_, std::abs(x[i] - lo_[i]));
        if (states[i] == LcpRowState::AtUpper) boundGap_ = std::max(boundGap_, std::abs(x[i] - hi_[i]));
    }
    return result;
}

}  // namespace af
