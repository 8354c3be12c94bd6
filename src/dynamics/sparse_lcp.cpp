#include "sparse_lcp.h"

#include <algorithm>
#include <cmath>

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
// Times the dense core may grow by the rows its answer finds wrong outside it.
constexpr int kCoreRounds = 4;
// A guess is kept when its free rows' w are within this fraction of the tolerance. What a kept
// guess leaves undone comes back several times larger in the next step (measured on the resting
// bench ragdoll: a joint row 8e-12 off became 9e-11 off), so a kept guess is usually followed by
// a solve. Resting bench ragdoll, instructions per step: 654k with the whole tolerance, 573k with
// a quarter (about half the steps keep their guess), 725k with 3%.
constexpr Real kHoldFraction = 0.25;

Real mid(Real lo, Real hi, Real v) { return std::min(hi, std::max(lo, v)); }

bool clamped(LcpRowState s) { return s == LcpRowState::AtLower || s == LcpRowState::AtUpper; }

}  // namespace

int SparseLcpSolver::source(const LcpProblem& problem, std::size_t i) const {
    return problem.findex.empty() ? -1 : problem.findex[i];
}

bool SparseLcpSolver::sliding(const LcpProblem& problem, std::span<const LcpRowState> states, std::size_t i) const {
    const int s = source(problem, i);
    return s >= 0 && clamped(states[i]) && states[static_cast<std::size_t>(s)] == LcpRowState::Free;
}

void SparseLcpSolver::bounds(const LcpProblem& problem, std::span<const Real> x) {
    for (std::size_t i = 0; i < lo_.size(); ++i) {
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
}

// The bodies' velocity change M⁻¹Jᵀx of the rows with use[i] (all rows if use is empty).
void SparseLcpSolver::velocityChange(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                                     std::span<const Real> x, std::span<const std::uint8_t> use) {
    std::fill(linear_.begin(), linear_.end(), Vec3::Zero());
    std::fill(angular_.begin(), angular_.end(), Vec3::Zero());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (x[i] == 0 || (!use.empty() && !use[i])) continue;
        const ConstraintRow& r = rows[i];
        const RowResponse& m = responses[i];
        if (r.bodyA != kWorldBody) {
            linear_[static_cast<std::size_t>(r.bodyA)] += x[i] * m.linearA;
            angular_[static_cast<std::size_t>(r.bodyA)] += x[i] * m.angularA;
        }
        if (r.bodyB != kWorldBody) {
            linear_[static_cast<std::size_t>(r.bodyB)] += x[i] * m.linearB;
            angular_[static_cast<std::size_t>(r.bodyB)] += x[i] * m.angularB;
        }
    }
}

// J of the row times the velocity change held in linear_ and angular_.
Real SparseLcpSolver::along(const ConstraintRow& r) const {
    Real v = 0;
    if (r.bodyA != kWorldBody)
        v += r.linearA.dot(linear_[static_cast<std::size_t>(r.bodyA)]) + r.angularA.dot(angular_[static_cast<std::size_t>(r.bodyA)]);
    if (r.bodyB != kWorldBody)
        v += r.linearB.dot(linear_[static_cast<std::size_t>(r.bodyB)]) + r.angularB.dot(angular_[static_cast<std::size_t>(r.bodyB)]);
    return v;
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
    // A new friction row sticks when its normal pushes; otherwise its box is empty.
    for (std::size_t i = 0; i < n; ++i) {
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
    }
    // The core, grown by the rows its answer finds wrong outside it, until it holds or is too large.
    for (int round = 0; round < kCoreRounds; ++round) {
        result.coreRounds = round + 1;
        const int wrong = solveCore(rows, responses, problem, x, states, wTolerance, settings, result);
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

// w of every row at x and the bounds at x, into w_, lo_ and hi_.
void SparseLcpSolver::evaluate(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                               const LcpProblem& problem, std::span<const Real> x) {
    velocityChange(rows, responses, x, {});
    for (std::size_t i = 0; i < rows.size(); ++i)
        w_[i] = along(rows[i]) + (problem.cfm.empty() ? 0 : problem.cfm[i]) * x[i] - problem.b[i];
    bounds(problem, x);
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
// may be off it by twice that. Leaves w_ and the bounds as check() does.
bool SparseLcpSolver::guessHolds(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                                 const LcpProblem& problem, std::span<const Real> x, std::span<const LcpRowState> states,
                                 Real wTolerance, Real tolerance) {
    evaluate(rows, responses, problem, x);
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
    // bench ragdoll 1.2k of its 205k instructions per step.
    if (lastMiss_ < rows.size() && !holds(lastMiss_)) return false;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (holds(i)) continue;
        lastMiss_ = i;
        return false;
    }
    return true;
}

// w of every row at x, the bounds at x, and the state each row wants (next_); returns how many
// rows are in the wrong state.
int SparseLcpSolver::check(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                           const LcpProblem& problem, std::span<const Real> x, std::span<const LcpRowState> states,
                           Real wTolerance, Real tolerance) {
    evaluate(rows, responses, problem, x);
    int wrong = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Real atBound = xTolerance(i, tolerance);
        LcpRowState want = states[i];
        if (states[i] == LcpRowState::Free) {
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

// Solves one pattern exactly. Rows at a bound take it (a friction row's box from its normal's
// impulse when the normal is itself at a bound); the free rows' equations are solved with the
// sparse factorisation. A friction row at its box while its normal is free (sliding) has
// λ_k = σ_k μ_k λ_n(k), which couples it to the solve: with x0 the free rows' answer for λ_k = 0
// and g_k their answer to a unit λ_k, the sliding impulses β solve the small system
//     β_k = σ_k μ_k (x0_n(k) + Σ_j g_j,n(k) β_j),
// one sparse solve per sliding row and a dense solve of their number.
bool SparseLcpSolver::solvePattern(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                                   const LcpProblem& problem, std::span<Real> x, std::span<const LcpRowState> states,
                                   SparseLcpResult& result) {
    const std::size_t n = rows.size();
    bool freeSetChanged = false;
    slidingRows_.clear();
    for (std::size_t pass = 0; pass < 2; ++pass)  // normals before the friction rows they bound
        for (std::size_t i = 0; i < n; ++i) {
            const bool coupled = source(problem, i) >= 0;
            if (coupled != (pass == 1)) continue;
            const std::uint8_t isFree = states[i] == LcpRowState::Free ? 1 : 0;
            freeSetChanged = freeSetChanged || free_[i] != isFree;
            free_[i] = isFree;
            use_[i] = clamped(states[i]) ? 1 : 0;
            if (sliding(problem, states, i)) {
                slidingRows_.push_back(static_cast<int>(i));
                use_[i] = 0;
                continue;
            }
            if (clamped(states[i])) x[i] = boundValue(problem, x, states, i);
        }
    if (freeSetChanged) {
        ++result.factorisations;
        if (!factor_.factor(rows, responses, problem.cfm, free_)) {
            result.status = LcpStatus::Unsatisfiable;
            return false;
        }
    }
    solveFree(rows, responses, problem.b, x, x);
    const std::size_t k = slidingRows_.size();
    if (k == 0) return true;

    // G_ij = g_j at row i's normal = −e_nᵀ A_FF⁻¹ a_j = −(L⁻¹e_n)ᵀ D⁻¹ (L⁻¹a_j), a_j the sliding
    // row's column of A: both forward solves touch only the elimination tree's paths from the
    // rows' groups to its root.
    const std::size_t vars = static_cast<std::size_t>(factor_.variables());
    const std::size_t groups = static_cast<std::size_t>(factor_.groups());
    paths_.resize(2 * k * vars);
    reached_.resize(2 * k * groups);
    auto path = [&](std::size_t p) { return std::span<Real>(&paths_[p * vars], vars); };
    auto reached = [&](std::size_t p) { return std::span<std::uint8_t>(&reached_[p * groups], groups); };
    supports_.clear();
    supportStart_.assign(1, 0);
    for (std::size_t j = 0; j < 2 * k; ++j) {
        const std::size_t row = static_cast<std::size_t>(slidingRows_[j % k]);
        if (j < k) {
            factor_.column(static_cast<int>(row), rows, responses, path(j), reached(j));
        } else {
            factor_.unit(source(problem, row), path(j), reached(j));
        }
        factor_.forward(path(j), reached(j));
        factor_.support(reached(j), supports_);
        supportStart_.push_back(static_cast<int>(supports_.size()));
    }
    auto support = [&](std::size_t p) {
        return std::span<const int>(supports_.data() + supportStart_[p], static_cast<std::size_t>(supportStart_[p + 1] - supportStart_[p]));
    };
    // (I − D G) β = D x0_n with D = diag(σ μ).
    small_.assign(k * k, 0);
    beta_.resize(k);
    for (std::size_t i = 0; i < k; ++i) {
        const std::size_t row = static_cast<std::size_t>(slidingRows_[i]);
        const Real d = slidingSlope(problem, states, row);
        for (std::size_t j = 0; j < k; ++j)
            small_[i * k + j] = (i == j ? 1 : 0) + d * factor_.scaledDot(path(k + i), support(k + i), path(j), support(j));
        beta_[i] = d * x[static_cast<std::size_t>(source(problem, row))];
    }
    if (!solveSmall(k)) {
        result.status = LcpStatus::Unsatisfiable;
        return false;
    }
    // The free rows again, the sliding rows' impulses now among the known ones.
    for (std::size_t j = 0; j < k; ++j) {
        x[static_cast<std::size_t>(slidingRows_[j])] = beta_[j];
        use_[static_cast<std::size_t>(slidingRows_[j])] = 1;
    }
    solveFree(rows, responses, problem.b, x, x);
    ++result.couplingSolves;
    return true;
}

// Gaussian elimination with partial pivoting of small_ (k×k) against beta_, in place. small_
// keeps the LU factors (the multipliers below the diagonal, rows in pivot order) and
// smallPivots_ the row each column's pivot came from, for solveSmallAgain.
bool SparseLcpSolver::solveSmall(std::size_t k) {
    smallPivots_.resize(k);
    for (std::size_t c = 0; c < k; ++c) {
        std::size_t pivot = c;
        for (std::size_t r = c + 1; r < k; ++r)
            if (std::abs(small_[r * k + c]) > std::abs(small_[pivot * k + c])) pivot = r;
        smallPivots_[c] = static_cast<int>(pivot);
        if (!(std::abs(small_[pivot * k + c]) > 1e-12)) return false;
        if (pivot != c) {
            for (std::size_t j = 0; j < k; ++j) std::swap(small_[c * k + j], small_[pivot * k + j]);
            std::swap(beta_[c], beta_[pivot]);
        }
        for (std::size_t r = c + 1; r < k; ++r) {
            const Real f = small_[r * k + c] / small_[c * k + c];
            small_[r * k + c] = f;
            if (f == 0) continue;
            for (std::size_t j = c + 1; j < k; ++j) small_[r * k + j] -= f * small_[c * k + j];
            beta_[r] -= f * beta_[c];
        }
    }
    for (std::size_t c = k; c-- > 0;) {
        for (std::size_t j = c + 1; j < k; ++j) beta_[c] -= small_[c * k + j] * beta_[j];
        beta_[c] /= small_[c * k + c];
    }
    return true;
}

// beta_ ← small⁻¹ beta_ with the factors solveSmall left: the row swaps, then L (unit lower),
// then U.
void SparseLcpSolver::solveSmallAgain(std::size_t k) {
    for (std::size_t c = 0; c < k; ++c) std::swap(beta_[c], beta_[static_cast<std::size_t>(smallPivots_[c])]);
    for (std::size_t c = 0; c < k; ++c)
        for (std::size_t r = c + 1; r < k; ++r) beta_[r] -= small_[r * k + c] * beta_[c];
    for (std::size_t c = k; c-- > 0;) {
        for (std::size_t j = c + 1; j < k; ++j) beta_[c] -= small_[c * k + j] * beta_[j];
        beta_[c] /= small_[c * k + c];
    }
}

// Where a row at a bound sits: its bound, a friction row's box from its normal's impulse in x.
Real SparseLcpSolver::boundValue(const LcpProblem& problem, std::span<const Real> x, std::span<const LcpRowState> states,
                                 std::size_t i) const {
    const int s = source(problem, i);
    if (s < 0) return states[i] == LcpRowState::AtLower ? problem.lo[i] : problem.hi[i];
    const Real box = problem.mu[i] * std::abs(x[static_cast<std::size_t>(s)]);
    return states[i] == LcpRowState::AtLower ? -box : box;
}

// A sliding friction row's impulse per unit of its (pushing) normal's: ±μ.
Real SparseLcpSolver::slidingSlope(const LcpProblem& problem, std::span<const LcpRowState> states, std::size_t i) const {
    return (states[i] == LcpRowState::AtLower ? -1 : 1) * problem.mu[i];
}

// A guess in the pattern of the last answer a trial found (a resting figure's, a step later) is
// refined with that answer's factorisation instead of a new one. The rows have barely moved, so
// A_FF is the factorised one to within the poses' change: with r_F the free rows' residual at x
// (rows at a bound on it, sliding rows at ±μ times their normals), one step
//     δ_F = A_FF⁻¹ (r_F − A_Fs δ_s),   δ_s = ±μ δ_n(s)
// (the sliding rows' coupling by the kept LU of the small system of solvePattern, whose equations
// are the same with δ0 = A_FF⁻¹ r_F for x0) leaves an error of the order of that change times
// the residual. The refined x must pass the trials' check, and its free rows w = 0 within the
// tolerance; if it does not, the trials follow. It follows guessHolds on the same x, whose w_ it
// updates for the rows it puts back on their bounds (a resting figure's one or two sliding rows,
// by rounding) instead of evaluating every row again.
bool SparseLcpSolver::refine(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                             const LcpProblem& problem, std::span<Real> x, std::span<const LcpRowState> states,
                             Real wTolerance, Real tolerance) {
    const std::size_t n = rows.size();
    if (!refinable_ || !factor_.structureKept() || free_.size() != n) return false;
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (free_[i] != (states[i] == LcpRowState::Free ? 1 : 0)) return false;
        if (!sliding(problem, states, i)) continue;
        if (k == slidingRows_.size() || slidingRows_[k] != static_cast<int>(i)) return false;
        ++k;
    }
    if (k != slidingRows_.size()) return false;
    correction_.assign(n, 0);
    bool moved = false;
    for (std::size_t pass = 0; pass < 2; ++pass)  // normals before the friction rows they bound
        for (std::size_t i = 0; i < n; ++i) {
            if ((source(problem, i) >= 0) != (pass == 1)) continue;
            const Real before = x[i];
            if (sliding(problem, states, i))
                x[i] = slidingSlope(problem, states, i) * x[static_cast<std::size_t>(source(problem, i))];
            else if (clamped(states[i]))
                x[i] = boundValue(problem, x, states, i);
            correction_[i] = x[i] - before;
            moved = moved || correction_[i] != 0;
        }
    if (moved) {
        // w_ += (A + CFM) Δx, on the rows that share a body with a moved one.
        velocityChange(rows, responses, correction_, {});
        touched_.assign(linear_.size(), 0);
        for (std::size_t i = 0; i < n; ++i) {
            if (correction_[i] == 0) continue;
            if (rows[i].bodyA != kWorldBody) touched_[static_cast<std::size_t>(rows[i].bodyA)] = 1;
            if (rows[i].bodyB != kWorldBody) touched_[static_cast<std::size_t>(rows[i].bodyB)] = 1;
        }
        for (std::size_t i = 0; i < n; ++i) {
            const ConstraintRow& r = rows[i];
            const bool near = (r.bodyA != kWorldBody && touched_[static_cast<std::size_t>(r.bodyA)]) ||
                              (r.bodyB != kWorldBody && touched_[static_cast<std::size_t>(r.bodyB)]);
            if (near) w_[i] += along(r) + (problem.cfm.empty() ? 0 : problem.cfm[i]) * correction_[i];
        }
    }
    for (std::size_t i = 0; i < n; ++i) rhs_[i] = free_[i] ? -w_[i] : 0;
    factor_.solve(rhs_);
    if (k > 0) {
        for (std::size_t j = 0; j < k; ++j) {
            const std::size_t row = static_cast<std::size_t>(slidingRows_[j]);
            beta_[j] = slidingSlope(problem, states, row) * rhs_[static_cast<std::size_t>(source(problem, row))];
        }
        solveSmallAgain(k);
        // The free rows' answer to a unit impulse of each sliding row, −A_FF⁻¹ A_F,s, is kept
        // with the factorisation: a resting figure refines with it step after step, and then
        // follows its sliding rows without a solve.
        if (!slidingAnswersKept_) {
            slidingAnswers_.assign(k * n, 0);
            zeros_.assign(n, 0);
            for (std::size_t j = 0; j < k; ++j) {
                const std::size_t row = static_cast<std::size_t>(slidingRows_[j]);
                std::fill(correction_.begin(), correction_.end(), 0);
                std::fill(use_.begin(), use_.end(), 0);
                correction_[row] = 1;
                use_[row] = 1;
                solveFree(rows, responses, zeros_, correction_, std::span<Real>(&slidingAnswers_[j * n], n));
            }
            slidingAnswersKept_ = true;
        }
        for (std::size_t j = 0; j < k; ++j) {
            x[static_cast<std::size_t>(slidingRows_[j])] += beta_[j];
            const Real* answer = &slidingAnswers_[j * n];
            for (std::size_t i = 0; i < n; ++i)
                if (free_[i]) rhs_[i] += beta_[j] * answer[i];
        }
    }
    for (std::size_t i = 0; i < n; ++i)
        if (free_[i]) x[i] += rhs_[i];
    // Unlike a trial's, the free rows' equations hold only as far as the refinement got.
    if (check(rows, responses, problem, x, states, wTolerance, tolerance) != 0) return false;
    for (std::size_t i = 0; i < n; ++i)
        if (free_[i] && !(std::abs(w_[i]) <= wTolerance)) return false;
    return true;
}

}  // namespace af
