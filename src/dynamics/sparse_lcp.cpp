#include "sparse_lcp.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace af {

namespace {

// Guesses tried before the dense core takes over. A resting figure needs one, a step with a few
// new contacts or limits two. Past that the pattern is far from the guess (everything hits the
// ground at once), and block pivoting with friction coupling, whose problem is neither symmetric
// nor a P-matrix one, tends to switch rows back and forth rather than settle. On the bench
// ragdoll's first 250 steps: 2 trials 796M instructions, 3 trials 830M, 8 trials 973M (cores up
// to 96 rows).
constexpr int kMaxTrials = 2;
// A first trial that finds at most this many rows wrong goes to the core at once: switching a few
// rows together mostly upsets their neighbours (a sticking contact that must slide moves the load
// onto the corners next to it), which the core's pivoting settles at a cost that grows with its
// size, not the figure's, while a second trial refactorises everything. Many wrong rows (an
// impact) are better switched together first, keeping the core well below kMaxCore. Bench drop,
// 600 steps, with a second trial always / up to 10 wrong rows at once to the core / up to 30 /
// never: 427.5M / 401.3M / 402.6M / 407.6M instructions; grid4's first 200 steps: 9.43G /
// 8.32G / 7.05G / 7.09G. Rows with fixed boxes (joint friction) join the core anyway and are not
// counted: counted, they sent many of our humanoid's steps on the default map to a second trial,
// whose switches grew the core past kMaxCore (at ca69c12, af-sim --solver tree --seed 4: 16
// give-ups in 108 steps). af-sim --solver tree: 1.04G instructions counted, 0.97G not; seeds 0-3,
// 5 and 6: 2.69G, 2.67G.
constexpr int kCoreAfterOneTrial = 32;
// A first trial whose switched rows alone (with those the core takes anyway, see markCore) make a
// core this large gives up: the second trial only adds rows, and the core then outgrows kMaxCore
// (96, sparse_core.cpp) in the end. The caller's fallback starts from the step's guess, not from
// the trials, so its answer is the same. Bench single and grid4, 600 steps: every first trial
// past 32 wrong rows whose core already held 83 rows or more gave up after the second; the four
// that went on to a core that held had 54-81 rows after the first trial, 65-85 after the second.
constexpr std::size_t kHopelessCore = 84;
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

    guessStates_.assign(states.begin(), states.end());
    free_.assign(n, 2);  // neither free nor clamped: the first trial factorises
    refinable_ = false;
    switched_.assign(n, 0);
    for (int trial = 1; trial <= kMaxTrials; ++trial) {
        result.trials = trial;
        if (!solvePattern(rows, responses, problem, x, states, result)) return result;
        const int wrong = check(rows, responses, problem, x, states, wTolerance, settings.tolerance);
        if (wrong == 0) {
            refinable_ = true;
            slidingAnswersKept_ = false;
            return finish(x, states, result);
        }
        int wrongOutsideCore = 0;  // rows with fixed boxes join the core whatever the trials find
        for (std::size_t i = 0; i < n; ++i) {
            if (next_[i] == states[i]) continue;
            states[i] = next_[i];
            switched_[i] = 1;
            if (!fixedBox(problem, i)) ++wrongOutsideCore;
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
        if (wrongOutsideCore <= kCoreAfterOneTrial) break;
        if (trial < kMaxTrials && markCore(problem, {}) >= kHopelessCore) {
            result.status = LcpStatus::NotConverged;
            return result;
        }
    }
    // The core, grown by the rows its answer finds wrong outside it, until it holds or is too large.
    // The trials only choose the first core: its pivoting starts from the guess's states, which
    // the trials' switches (every wrong row at once, the friction rows' guessed from their
    // normals') repair worse than single pivots do; a later round's from the last core's answer.
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
    // (refine() and the trials take theirs from check()): 1.3k more of 191k.
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
