// One guessed pattern of the sparse path solved exactly (the free rows' equations through the
// sparse factorisation, sliding friction rows by a small dense system), and a guess in the last
// answer's pattern refined with that answer's factors; see sparse_lcp.h.

#include "sparse_lcp.h"

#include <algorithm>
#include <cmath>

namespace af {

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
    // data() + offset, as in solveCore: no free rows, no variables, empty vectors.
    auto path = [&](std::size_t p) { return std::span<Real>(paths_.data() + p * vars, vars); };
    auto reached = [&](std::size_t p) { return std::span<std::uint8_t>(reached_.data() + p * groups, groups); };
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
    // The free rows follow the sliding rows' impulses: x_F −= A_FF⁻¹ A_Fs β = L⁻ᵀ D⁻¹ (Σ_j β_j L⁻¹a_j),
    // from the forwarded columns at hand rather than a second solve through the bodies. Bench
    // single, settling steps 26-89: solvePattern 330k -> 319k instructions a step.
    forwarded_.assign(vars, 0);
    for (std::size_t j = 0; j < k; ++j) {
        x[static_cast<std::size_t>(slidingRows_[j])] = beta_[j];
        const std::span<const Real> column = path(j);
        for (const int g : support(j))
            for (int v = factor_.firstVariable(g); v < factor_.firstVariable(g + 1); ++v)
                forwarded_[static_cast<std::size_t>(v)] += beta_[j] * column[static_cast<std::size_t>(v)];
    }
    inversePivots_.resize(vars);
    factor_.inversePivots(inversePivots_);
    for (std::size_t v = 0; v < vars; ++v) forwarded_[v] *= inversePivots_[v];
    factor_.solveForwarded(forwarded_, rhs_);
    for (std::size_t i = 0; i < n; ++i)
        if (free_[i]) x[i] -= rhs_[i];
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
// the residual. The refined x must pass the trial's check, and its free rows w = 0 within the
// tolerance; if it does not, the trial follows. It follows guessHolds on the same x, whose w_ it
// updates for the rows it puts back on their bounds (a resting figure's one or two sliding rows,
// by rounding) instead of evaluating every row again.
bool SparseLcpSolver::refine(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                             const LcpProblem& problem, std::span<Real> x, std::span<const LcpRowState> states,
                             Real wTolerance, Real tolerance) {
    const std::size_t n = rows.size();
    if (!refinable_ || !factor_.structureKept() || free_.size() != n) return false;
    // The rows at a bound, normals before the friction rows they bound (and each list in row
    // order): only they are put back on their bounds below. A resting figure has a few of its
    // rows there, and two passes over all of them were about 5k of its 74k instructions per solve.
    std::size_t k = 0;
    boundRows_.clear();
    boundFriction_.clear();
    for (std::size_t i = 0; i < n; ++i) {
        if (free_[i] != (states[i] == LcpRowState::Free ? 1 : 0)) return false;
        if (free_[i]) continue;
        (source(problem, i) >= 0 ? boundFriction_ : boundRows_).push_back(static_cast<int>(i));
        if (!sliding(problem, states, i)) continue;
        if (k == slidingRows_.size() || slidingRows_[k] != static_cast<int>(i)) return false;
        ++k;
    }
    if (k != slidingRows_.size()) return false;
    boundRows_.insert(boundRows_.end(), boundFriction_.begin(), boundFriction_.end());
    correction_.assign(n, 0);
    bool moved = false;
    for (const int row : boundRows_) {
        const std::size_t i = static_cast<std::size_t>(row);
        const Real before = x[i];
        if (sliding(problem, states, i))
            x[i] = slidingSlope(problem, states, i) * x[static_cast<std::size_t>(source(problem, i))];
        else
            x[i] = boundValue(problem, x, states, i);
        correction_[i] = x[i] - before;
        moved = moved || correction_[i] != 0;
    }
    if (moved) {
        // w_ += (A + CFM) Δx, on the rows that share a body with a moved one.
        velocityChange(rows, responses, correction_, {});
        touched_.assign(linear_.size(), 0);
        for (const int row : boundRows_) {
            const std::size_t i = static_cast<std::size_t>(row);
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
