#pragma once
// Boxed mixed linear complementarity problems (LCP) with friction coupling, and two solvers:
// an exact principal-pivoting one (the reference) and projected Gauss–Seidel (the fallback).
// Pure mathematics on dense matrices: no bodies and no constraints are involved here.
//
// The problem, with the sign convention of Doom 3's idLCP (docs/doom-physics.md §4.6):
//
//     (A + diag(cfm)) x = b + w,      lo ≤ x ≤ hi,
//
// and for every row i exactly one of
//     lo_i < x_i < hi_i  and  w_i = 0     (free),
//     x_i = lo_i         and  w_i ≥ 0     (at the lower bound),
//     x_i = hi_i         and  w_i ≤ 0     (at the upper bound).
// When lo_i = hi_i the row is fixed and w_i is unrestricted. lo may be −∞ and hi +∞; a row with
// both infinite is an equality row ((Ax)_i = b_i). With A symmetric positive definite and no
// coupling this is the optimality condition of min ½xᵀAx − bᵀx over the box, so w = Ax − b is the
// gradient and the solution is unique.
//
// In a constraint solver x are the impulses (or forces) λ, A = J M⁻¹ Jᵀ, b = −(J v + bias)
// and w = J v' + bias is the resulting constraint velocity: contacts and limits have lo = 0,
// hi = +∞ (they push and the velocity may only separate); joint rows are unbounded.
//
// Friction coupling (ODE's findex, Doom's boxIndex): a row i with findex_i = j ≥ 0 ignores lo_i
// and hi_i and is bounded by the current solution of row j:
//     lo_i = −mu_i·|x_j|,   hi_i = +mu_i·|x_j|.
// Row j (the contact normal) must not be coupled itself. Doom scales its own lo_i and hi_i by
// |x_j| instead; with Doom's lo_i = −mu, hi_i = mu the two agree. The coupled problem is no
// longer a minimisation; a solution exists in the usual friction settings but need not be
// unique.
//
// CFM: rows that are redundant (two equal joint rows) or nearly so make A singular. A small
// positive constraint-force-mixing term on the diagonal (per row in the problem, and/or one value
// for all rows in the solver settings) makes A + diag(cfm) positive definite, so every pivot
// exists; Doom adds 1e-7/dt for joints, 1e-4/dt for limits and 1e-6/dt for contacts.

#include "af/types.h"

#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

namespace af {

/// +∞, for unbounded sides of a row.
inline constexpr Real kLcpInfinity = std::numeric_limits<Real>::infinity();

/// One boxed mixed LCP, as views of caller-owned contiguous arrays (nothing is copied or kept).
/// All spans with per-row data hold `size` entries, or are empty where that is allowed.
struct LcpProblem {
    int                   size = 0;  ///< n, the number of rows
    std::span<const Real> a;         ///< n×n symmetric positive semi-definite, row i at a[i·n …]
    std::span<const Real> b;         ///< right-hand side
    std::span<const Real> lo;        ///< lower bounds (may be −∞); ignored on coupled rows
    std::span<const Real> hi;        ///< upper bounds (may be +∞), lo ≤ hi; ignored on coupled rows
    std::span<const int>  findex;    ///< bound source per row, −1 for none; empty: no coupling
    std::span<const Real> mu;        ///< friction coefficient (≥ 0) of coupled rows; empty if findex is
    std::span<const Real> cfm;       ///< per-row CFM (≥ 0) added to A's diagonal; empty: none
};

/// Where a row ended up; also the warm-start guess for the next solve.
enum class LcpRowState : std::uint8_t {
    Unknown,  ///< no guess (warm-start input only)
    Free,     ///< lo < x < hi, w = 0 (in the factorised set)
    AtLower,  ///< x = lo, w ≥ 0
    AtUpper,  ///< x = hi, w ≤ 0
    Failed,   ///< could not be satisfied; see LcpResult::failedRows
};

enum class LcpStatus : std::uint8_t {
    Solved,         ///< every row complementary within the tolerance
    Unsatisfiable,  ///< some rows had no solution (inconsistent redundant rows without CFM, or an
                    ///< unbounded row that no motion can satisfy); the others are solved
    NotConverged,   ///< friction coupling did not settle within maxCouplingPasses
    PivotLimit,     ///< the pivot cap was reached; unprocessed rows are listed as failed
    InvalidInput,   ///< sizes, bounds (lo > hi, NaN), findex or mu/cfm values are malformed
};

/// Human-readable name of a status, for logs.
const char* toString(LcpStatus status);

struct LcpResult {
    LcpStatus status = LcpStatus::Solved;
    int       pivots = 0;          ///< changes of the factorised set after its initial build
    int       couplingPasses = 0;  ///< rounds of solve-then-check; 1 for a warm start that held
    Real      residual = 0;        ///< max_i |x_i − mid(lo_i, hi_i, x_i − w_i)| (natural residual,
                                   ///< coupled bounds from the returned x); 0 iff complementary
    std::span<const int> failedRows;  ///< original row indices; valid until the solver's next call
};

/// Settings of the exact solver (plain data, as every settings struct is).
struct LcpExactSettings {
    /// Added to every diagonal entry on top of LcpProblem::cfm. Zero by default: the problem is
    /// solved as given. Set it when rows may be redundant and the caller gives no per-row CFM.
    Real cfm = 0;
    /// Relative zero of the solver: |w| ≤ tolerance·max(1, ‖b‖∞) counts as w = 0, and x within
    /// tolerance·max(1, |bound|) of a bound counts as at it. Results satisfy complementarity to
    /// about this level (more loosely when A is ill-conditioned).
    Real tolerance = 1e-11;
    /// A new pivot d of the factorisation with d ≤ pivotTolerance·A_ii means the row depends on
    /// the rows already factorised. With CFM > 0 this does not happen.
    Real pivotTolerance = 1e-12;
    /// Pivot cap: at most this many changes of the factorised set per solve; 0 means 32·n
    /// (Doom's 32 iterations per row). Reaching it ends the solve with status PivotLimit.
    int maxPivots = 0;
    /// Cap on the solve-check-pivot passes that settle friction coupling (see below).
    int maxCouplingPasses = 16;
    /// Compute LcpResult::residual against the original problem (one extra n×n product).
    bool computeResidual = true;
    /// A coupled problem solved with a warm start whose guess does not hold in the first pass
    /// may freeze the friction boxes at that pass's normals and iterate them to a fixed point, at
    /// most this many plain boxed solves; see solve(). 0 (the default): never. World sets it: a
    /// tumbling figure's coupled drives cost far more than a few plain solves.
    int frictionBoxPasses = 0;
};

/// Exact solver: Dantzig / principal pivoting on the boxed LCP with an incrementally updated
/// LDLᵀ factorisation of the free set, as Baraff's and ODE's dLCP and Doom's idLCP_Symmetric do.
///
/// * Unbounded rows are factorised first; the bounded rows are then driven one at a time to
///   complementarity, each pivot adding or removing one row of the factorisation in O(n²)
///   (never a refactorisation).
/// * Friction coupling: coupled rows are processed after the others (ODE's order), but unlike
///   ODE and Doom their boxes are not frozen at the normals of that moment: while a row is
///   driven, friction rows at a bound stay tied to their normals (x_k = ±mu_k·|x_j|, a rank-k
///   Woodbury correction of the same factorisation, k = sliding contacts) and free friction rows
///   meet boxes that move with the normals. Each pass ends with an exact solve of the whole
///   pattern with those ties and a check of every row against the bounds of the final x; rows
///   that fail are pivoted again, for at most maxCouplingPasses passes. The answer therefore
///   satisfies the coupled bounds of its own x. The coupled problem need not have a unique
///   solution, or any when friction is very strong; a problem that does not settle is reported
///   as NotConverged (on random dense test problems with mu ≤ 1.2, about 1 in 10⁴).
/// * Warm start: pass the row states of a previous solve in ioStates; the solver factorises that
///   pattern directly and only pivots the rows the guess got wrong. Solving the same problem
///   again from its own states takes zero pivots. A coupled problem that does not settle from
///   the guess is tried once more from cold, for a few passes (a guess can lead into a cycle).
/// * Failures are reported, never hidden: see LcpStatus and LcpResult::failedRows.
///
/// No heap allocation happens inside solve() once reserve(n) has been called for n ≥ the problem
/// size (solve() reserves on demand otherwise). Not thread-safe; use one solver per thread.
class LcpExactSolver {
public:
    explicit LcpExactSolver(const LcpExactSettings& settings = {});
    ~LcpExactSolver();
    LcpExactSolver(LcpExactSolver&&) noexcept;
    LcpExactSolver& operator=(LcpExactSolver&&) noexcept;

    /// Sizes the workspace for problems of up to n rows.
    void reserve(int n);

    const LcpExactSettings& settings() const;
    void                    setSettings(const LcpExactSettings& settings);

    /// Solves `problem` into outX (size n). ioStates is empty (cold start, states not returned)
    /// or holds n entries: on input the warm-start guess (Unknown where there is none), on output
    /// the final state of every row. outX is not read: the impulses follow from the states
    /// (frictionBoxPasses freezes the boxes at the normals of the first pass's answer).
    LcpResult solve(const LcpProblem& problem, std::span<Real> outX,
                    std::span<LcpRowState> ioStates = {});

    struct Impl;

private:
    LcpResult solveWithFrozenBoxes(const LcpProblem& problem, std::span<Real> x, std::span<LcpRowState> ioStates);

    std::unique_ptr<Impl> impl_;
};

/// Settings of projected Gauss–Seidel.
struct LcpPgsSettings {
    int  maxIterations = 100;  ///< sweeps over all rows
    /// Stop when a sweep changes no x_i by more than tolerance·max(1, ‖x‖∞).
    Real tolerance = 1e-10;
    Real sor = 1;              ///< successive over-relaxation factor ω, 0 < ω < 2
    Real cfm = 0;              ///< added to every diagonal entry, as LcpExactSettings::cfm
    bool computeResidual = true;
};

struct LcpPgsResult {
    LcpStatus status = LcpStatus::Solved;  ///< Solved, NotConverged (ran out of sweeps) or InvalidInput
    int       iterations = 0;              ///< sweeps done
    Real      lastChange = 0;              ///< max |Δx_i| of the last sweep
    Real      residual = 0;                ///< as LcpResult::residual
};

/// Projected Gauss–Seidel: rows are relaxed in order, each clamped to its box right after its
/// update; a coupled row is clamped to ±mu·|x_j| with the value x_j has at that moment. Rows
/// with a non-positive diagonal are left unchanged. Converges for positive definite A (ω in
/// (0, 2)), linearly, slowly when A is ill-conditioned.
class LcpPgsSolver {
public:
    explicit LcpPgsSolver(const LcpPgsSettings& settings = {});

    void reserve(int n);

    const LcpPgsSettings& settings() const { return settings_; }
    void                  setSettings(const LcpPgsSettings& settings) { settings_ = settings; }

    /// ioX (size n) holds the warm start on input (zeros for a cold start; it is clamped into
    /// the box first) and the solution on output.
    LcpPgsResult solve(const LcpProblem& problem, std::span<Real> ioX);

private:
    LcpPgsSettings    settings_;
    std::vector<Real> invDiagonal_;
};

/// Checks sizes and values of a problem (the solvers call this first). Returns false and names
/// the first problem found in outMessage (a static string) when the problem is malformed.
bool lcpValidate(const LcpProblem& problem, const char** outMessage = nullptr);

/// Natural residual max_i |x_i − mid(lo_i, hi_i, x_i − w_i)| with w = (A + diag(cfm + extraCfm))x − b
/// and coupled bounds taken from x. Zero exactly at a solution. O(n²), no allocation.
Real lcpResidual(const LcpProblem& problem, std::span<const Real> x, Real extraCfm = 0);

}  // namespace af
