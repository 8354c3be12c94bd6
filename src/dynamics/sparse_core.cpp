// The sparse path's way out when its trial does not settle (a tumbling figure whose contacts all
// change at once, friction rows that keep swapping sides): most rows are right by then. The rows
// its check found wrong, the sliding friction rows, and the normals and friction
// rows coupled to those form a small core U; the rows outside it keep their states (free rows as
// equations F, the others at their bounds), and the core is solved as a dense boxed LCP with its
// friction coupling, on its Schur complement
//     S = A_UU − A_UF A_FF⁻¹ A_FU,     b' = b_U − (A x⁰)_U   (x⁰: the answer with the core at 0),
// by the pivoting solver, which always finishes (with the caller's settings: friction boxes
// frozen first, which settles a tumbling figure's coupled core in a few plain passes). The free
// rows then follow the core's impulses and the whole answer is checked like any trial's: the core
// is exact, the guess outside it may not be. The rows found wrong outside join the core and it is
// solved again (sparse_lcp.cpp), until the answer holds or the core is too large; then the caller
// falls back to its other solvers.
//
// Rows boxed on both sides by fixed bounds (joint friction) always join the core. The last step's
// states are no guess for them: the bound is f·|λ| of the joint's previous impulse, which changes
// as much as the joints' sticking and slipping do, and the states jump from step to step (our
// humanoid settling on the default map at ca69c12, 29 joint friction rows a step: 1.3k of 2.6k kept
// their state, 400 went from one bound to the other, with |w| up to several rad/s; none of the
// switches was a degenerate row, at its bound with w ≈ 0). And a trial that frees them all at once
// is far off: a figure whose joints all stick is one rigid body on redundant contacts, held so by
// impulses far beyond the bounds (rows freed by a trial: median 100, a quarter over 18000 times
// their bound), so a freed row pulls others past their bounds in turn. Kept outside, they were
// found wrong a few at a time, each time growing the core by a round (a factorisation, the Schur
// complement and the dense solve again): 2-4 rounds in most steps, and six cores grew too large. In
// the core the pivoting solver settles them in one round, as a rule. af-sim --solver tree: 1.51G ->
// 0.97G instructions (the same 104 steps); seeds 0-6: 4.32G -> 3.54G, 560 -> 575 steps (two seeds
// fall otherwise, with answers within the tolerance).
//
// Returns the rows the check found wrong (0: x is the answer), or −1 when the core is too large
// or could not be solved.

#include "sparse_lcp.h"

#include <Eigen/Core>

#include <algorithm>

namespace af {

namespace {

// A larger core's dense pivoting costs more than the caller's own fallback. The bench ragdoll's
// first 250 steps (two trials first, frozen boxes in the core): 805M instructions and 11 fallbacks
// with cores up to 64 rows, 796M and 4 up to 96, 843M and 1 up to 128. Since the core starts from
// the guess (one trial), grid4's 600 steps: 4757M and 17 fallbacks up to 96, 4742M and 7 up to
// 128, 4725M and 1 up to 192; but with 192 af-sim --seed 24 went another way and counted a failed
// solve (seeds 0-40 with 128: the same drops, but for one step more in seed 28).
constexpr std::size_t kMaxCore = 128;

}  // namespace

// Marks in inCore_ the rows switched by the trial (and the rounds), those with fixed boxes and the
// sliding friction rows, each with its normal and the normal's friction rows; returns how many.
std::size_t SparseLcpSolver::markCore(const LcpProblem& problem, std::span<const LcpRowState> states) {
    const std::size_t n = switched_.size();
    inCore_.assign(switched_.begin(), switched_.end());
    for (std::size_t i = 0; i < n; ++i)
        if (sliding(problem, states, i) || fixedBox(problem, i)) inCore_[i] = 1;
    for (std::size_t i = 0; i < n; ++i)  // a friction row's normal, then every friction row of a normal
        if (source(problem, i) >= 0 && inCore_[i]) inCore_[static_cast<std::size_t>(source(problem, i))] = 1;
    for (std::size_t i = 0; i < n; ++i)
        if (source(problem, i) >= 0 && inCore_[static_cast<std::size_t>(source(problem, i))]) inCore_[i] = 1;
    return static_cast<std::size_t>(std::count(inCore_.begin(), inCore_.end(), std::uint8_t{1}));
}

int SparseLcpSolver::solveCore(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                               const LcpProblem& problem, std::span<Real> x, std::span<LcpRowState> states,
                               std::span<const LcpRowState> coreGuess, Real wTolerance, const LcpExactSettings& settings,
                               SparseLcpResult& result) {
    const std::size_t n = rows.size();
    markCore(problem, states);
    lastCore_.swap(core_);
    lastCoreIndex_.swap(coreIndex_);
    core_.clear();
    coreIndex_.assign(n, -1);
    for (std::size_t i = 0; i < n; ++i)
        if (inCore_[i]) {
            coreIndex_[i] = static_cast<int>(core_.size());
            core_.push_back(static_cast<int>(i));
        }
    const std::size_t m = core_.size();
    if (m == 0 || m > kMaxCore) return -1;
    result.coreRows = static_cast<int>(m);

    // Outside the core: free rows factorised, the others at their bounds (a friction row outside
    // the core has its normal outside too, at a bound: its box is known). Normals first.
    coreX_.resize(m);
    coreStates_.resize(m);
    for (std::size_t u = 0; u < m; ++u) {
        const std::size_t row = static_cast<std::size_t>(core_[u]);
        coreX_[u] = x[row];
        coreStates_[u] = coreGuess[row];
    }
    // free_ holds the rows factor_ was last factorised with (a trial's, or the last round's): a
    // core that frees none of them (its rows were all at bounds in the trial, or a round grown
    // only by rows at bounds) keeps that factorisation, as solvePattern does.
    bool freeSetChanged = false;
    for (std::size_t pass = 0; pass < 2; ++pass)
        for (std::size_t i = 0; i < n; ++i) {
            const int s = source(problem, i);
            if ((s >= 0) != (pass == 1)) continue;
            const std::uint8_t isFree = !inCore_[i] && states[i] == LcpRowState::Free ? 1 : 0;
            freeSetChanged = freeSetChanged || free_[i] != isFree;
            free_[i] = isFree;
            use_[i] = !inCore_[i] && clamped(states[i]) ? 1 : 0;
            if (inCore_[i]) x[i] = 0;
            if (!use_[i]) continue;
            const Real box = s >= 0 ? problem.mu[i] * std::abs(x[static_cast<std::size_t>(s)]) : 0;
            const Real lo = s >= 0 ? -box : problem.lo[i], hi = s >= 0 ? box : problem.hi[i];
            x[i] = states[i] == LcpRowState::AtLower ? lo : hi;
        }
    if (freeSetChanged) {
        ++result.factorisations;
        if (!factor_.factor(rows, responses, problem.cfm, free_)) return -1;
    }
    solveFree(rows, responses, problem.b, x, x);

    // b' through the bodies; S = A_UU − Wᵀ D⁻¹ W with W = L⁻¹ A_FU, the core rows' columns
    // forward-solved (sparse: each touches only its path to the root).
    velocityChange(rows, responses, x, {});
    coreB_.resize(m);
    for (std::size_t u = 0; u < m; ++u) coreB_[u] = problem.b[static_cast<std::size_t>(core_[u])] - along(rows[static_cast<std::size_t>(core_[u])]);
    const std::size_t vars = static_cast<std::size_t>(factor_.variables());
    const std::size_t groups = static_cast<std::size_t>(factor_.groups());
    // A round that kept the last round's factorisation (it grew by rows at bounds only) has the
    // last round's paths and Schur entries for the rows both cores share, bit for bit: they depend
    // on the factorisation and the two rows alone. Bench single, 600 steps: 4 such rounds (one at
    // step 35, 66 rows), 215.55M -> 214.89M instructions.
    const bool reuse = result.coreRounds > 1 && !freeSetChanged;
    const std::size_t lastM = lastCore_.size();
    auto lastIndex = [&](std::size_t u) { return reuse ? lastCoreIndex_[static_cast<std::size_t>(core_[u])] : -1; };
    lastPaths_.swap(paths_);
    lastPathStart_.swap(pathStart_);
    lastCoreA_.swap(coreA_);
    paths_.resize(m * vars);
    reached_.resize(m * groups);
    pathStart_.resize(m);
    for (std::size_t u = 0; u < m; ++u) {
        if (const int last = lastIndex(u); last >= 0) {
            std::copy_n(lastPaths_.data() + static_cast<std::size_t>(last) * vars, vars, paths_.data() + u * vars);
            pathStart_[u] = lastPathStart_[static_cast<std::size_t>(last)];
            continue;
        }
        // data() + offset: with no free rows outside the core (a lone box whose every point is
        // in it) the factorisation has no variables, and element access on the empty vectors
        // would be undefined.
        const std::span<Real> path(paths_.data() + u * vars, vars);
        const std::span<std::uint8_t> reached(reached_.data() + u * groups, groups);
        factor_.column(core_[u], rows, responses, path, reached);
        factor_.forward(path, reached);
        std::size_t g = 0;
        while (g < groups && !reached[g]) ++g;
        pathStart_[u] = g < groups ? factor_.firstVariable(static_cast<int>(g)) : static_cast<int>(vars);
    }
    inversePivots_.resize(vars);
    factor_.inversePivots(inversePivots_);
    scaledPaths_.resize(m * vars);
    using Matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
    using Vector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
    const Eigen::Map<const Matrix> w(paths_.data(), static_cast<Eigen::Index>(vars), static_cast<Eigen::Index>(m));
    Eigen::Map<Matrix> scaled(scaledPaths_.data(), static_cast<Eigen::Index>(vars), static_cast<Eigen::Index>(m));
    scaled.noalias() = Eigen::Map<const Vector>(inversePivots_.data(), static_cast<Eigen::Index>(vars)).asDiagonal() * w;
    // One dot product per entry of the lower half, mirrored (S is symmetric): cheaper here than a
    // general matrix product (the bench drop's first 250 steps: 652M instructions against 667M),
    // and it never needs blocking buffers, which Eigen takes from the heap once they outgrow its
    // stack limit. Two paths overlap only from where the later of them starts.
    coreA_.resize(m * m);
    for (std::size_t v = 0; v < m; ++v) {
        const std::size_t column = static_cast<std::size_t>(core_[v]);
        const int lastV = lastIndex(v);
        for (std::size_t u = v; u < m; ++u) {
            if (const int lastU = lastIndex(u); lastV >= 0 && lastU >= 0) {
                coreA_[v * m + u] = coreA_[u * m + v] =
                    lastCoreA_[static_cast<std::size_t>(lastV) * lastM + static_cast<std::size_t>(lastU)];
                continue;
            }
            const Eigen::Index start = std::max(pathStart_[u], pathStart_[v]);
            const Eigen::Index length = static_cast<Eigen::Index>(vars) - start;
            const Real entry = rowCoupling(rows[static_cast<std::size_t>(core_[u])], rows[column], responses[column]) -
                               w.col(static_cast<Eigen::Index>(u)).segment(start, length).dot(
                                   scaled.col(static_cast<Eigen::Index>(v)).segment(start, length));
            coreA_[v * m + u] = entry;
            coreA_[u * m + v] = entry;
        }
    }
    coreLo_.resize(m);
    coreHi_.resize(m);
    coreFindex_.resize(m);
    coreMu_.resize(m);
    coreCfm_.resize(m);
    for (std::size_t u = 0; u < m; ++u) {
        const std::size_t row = static_cast<std::size_t>(core_[u]);
        const int s = source(problem, row);
        coreFindex_[u] = s >= 0 ? coreIndex_[static_cast<std::size_t>(s)] : -1;
        coreMu_[u] = s >= 0 ? problem.mu[row] : 0;
        coreLo_[u] = s >= 0 ? -kLcpInfinity : problem.lo[row];
        coreHi_[u] = s >= 0 ? kLcpInfinity : problem.hi[row];
        coreCfm_[u] = problem.cfm.empty() ? 0 : problem.cfm[row];
    }
    LcpProblem core;
    core.size = static_cast<int>(m);
    core.a = coreA_;
    core.b = coreB_;
    core.lo = coreLo_;
    core.hi = coreHi_;
    core.findex = coreFindex_;
    core.mu = coreMu_;
    core.cfm = coreCfm_;
    // The answer is checked with every row below: the solver's own residual, a product with the
    // whole core matrix, would tell nothing more.
    LcpExactSettings coreSettings = settings;
    coreSettings.computeResidual = false;
    coreSolver_.setSettings(coreSettings);
    if (coreSolver_.solve(core, coreX_, coreStates_).status != LcpStatus::Solved) return -1;

    // The free rows follow: x_F −= A_FF⁻¹ A_FU x_U = L⁻ᵀ (D⁻¹ W x_U), from the scaled paths at
    // hand rather than a solve of A_FU x_U through the bodies. Bench single, settling steps
    // 26-89: solveCore 642k -> 627k instructions a step.
    for (std::size_t u = 0; u < m; ++u) {
        const std::size_t row = static_cast<std::size_t>(core_[u]);
        x[row] = coreX_[u];
        states[row] = coreStates_[u];
    }
    forwarded_.resize(vars);
    Eigen::Map<Vector>(forwarded_.data(), static_cast<Eigen::Index>(vars)).noalias() =
        scaled * Eigen::Map<const Vector>(coreX_.data(), static_cast<Eigen::Index>(m));
    factor_.solveForwarded(forwarded_, rhs_);
    for (std::size_t i = 0; i < n; ++i)
        if (free_[i]) x[i] -= rhs_[i];
    return check(rows, responses, problem, x, states, wTolerance, settings.tolerance);
}

}  // namespace af
