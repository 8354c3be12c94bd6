#pragma once
// Private parts of the LCP solvers: the incremental LDLᵀ factorisation and the exact solver's
// workspace. The stages of the exact solver live in separate files:
//   lcp_factor.cpp        LDLᵀ append / remove / solve
//   lcp_exact_setup.cpp   loading a problem into pivot order, warm start, swaps, results
//   lcp_exact_pattern.cpp exact solve of a given active pattern (with friction ties) and its check
//   lcp_exact_pivot.cpp   the Dantzig driving loop
//   lcp_exact.cpp         the passes that tie these together
// Everything here works in "positions": the rows of the permuted copy of A. Positions
// [0, nC) form the clamped (free, factorised) set C, [nC, nP) the processed rows that are not
// factorised (at a bound, or held), and [nP, n) the rows not processed yet.

#include "lcp.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace af::lcp {

// For workspaces whose every cell is written before it is read (here A in pivot order, L, the link
// columns; the sparse solver's forwarded columns and dense core), so growing them need not zero
// them. Zeroing was most of the cost of the step where a solver first met a larger problem (bench
// single step 34: 0.69M of 6.8M instructions, when the tree solver's pivoting solver first grew to
// its auxiliary rows).
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = UninitialisedAllocator<U>;
    };
    UninitialisedAllocator() = default;
    template <class U>
    UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};
using Workspace = std::vector<Real, UninitialisedAllocator<Real>>;

using VecMap = Eigen::Map<Eigen::Matrix<Real, Eigen::Dynamic, 1>>;
using ConstVecMap = Eigen::Map<const Eigen::Matrix<Real, Eigen::Dynamic, 1>>;

// Eigen's vectorised kernels on raw contiguous arrays (with -ffp-contract=off and no fast-math
// the compiler would not vectorise a plain reduction loop).
inline Real dot(const Real* u, const Real* v, int n) {
    return n > 0 ? ConstVecMap(u, n).dot(ConstVecMap(v, n)) : Real(0);
}
inline void axpy(Real* y, Real alpha, const Real* x, int n) {
    if (n > 0) {
        VecMap(y, n) += alpha * ConstVecMap(x, n);
    }
}

/// LDLᵀ factorisation of a symmetric positive definite matrix that grows and shrinks by one
/// row at a time: L unit lower triangular, stored row-major with a fixed stride so every kernel
/// reads contiguous rows; D diagonal.
class Ldlt {
public:
    void reserve(int n);
    void reset(int stride);  ///< empty factor; rows of up to `stride` entries

    int size() const { return size_; }
    const Real* row(int r) const { return l_.data() + static_cast<std::size_t>(r) * stride_; }
    Real pivot(int r) const { return d_[r]; }

    void forward(Real* v) const;   ///< v := L⁻¹ v (first size() entries)
    void backward(Real* v) const;  ///< v := L⁻ᵀ v
    void scale(Real* v) const;     ///< v := D⁻¹ v
    void solve(Real* v) const;     ///< v := (L D Lᵀ)⁻¹ v

    /// Appends the row whose off-diagonal part a (size() entries) was already forward-solved,
    /// y = L⁻¹ a. Refuses (returns false, factor unchanged) when the new pivot
    /// d = diag − yᵀD⁻¹y is not above minPivot: the row depends on the factorised ones.
    bool appendForwardSolved(const Real* y, Real diag, Real minPivot);
    /// Same from the plain row a; `scratch` holds size() entries.
    bool append(const Real* a, Real diag, Real minPivot, Real* scratch);
    /// Deletes row and column p: the trailing block gets the rank-one update that row p carried
    /// (stable: the update is positive). O((size−p)·size). `scratch` holds 3·size() entries.
    void remove(int p, Real* scratch);

private:
    Real* rowMut(int r) { return l_.data() + static_cast<std::size_t>(r) * stride_; }

    Workspace         l_;
    std::vector<Real> d_, invD_;
    int stride_ = 0;
    int size_ = 0;
};

/// State of one position in the exact solver.
enum class Slot : std::uint8_t {
    Clamped,      ///< in C: free, w = 0, in the factorisation
    AtLower,      ///< x = lo, w ≥ 0
    AtUpper,      ///< x = hi, w ≤ 0
    Held,         ///< w = 0 at an interior x, but dependent on C (singular pivot), so not in C
    Failed,       ///< given up; reported
    Unprocessed,  ///< not driven yet; x is some value inside the box
};

inline bool atBound(Slot s) { return s == Slot::AtLower || s == Slot::AtUpper; }

}  // namespace af::lcp

namespace af {

struct LcpExactSolver::Impl {
    using Slot = lcp::Slot;

    LcpExactSettings settings;
    int              capacity = 0;

    // The frozen-box phase of a coupled problem (lcp_exact.cpp): its bounds and row states.
    std::vector<Real>        boxLo, boxHi;
    std::vector<LcpRowState> boxStates, boxPattern;

    // The problem in position order. a is n×n with stride n and CFM already on its diagonal.
    int                  n = 0;
    lcp::Workspace       a;
    std::vector<Real>    x, b, lo, hi, w, mu;
    std::vector<int>     perm;    // position → original row
    std::vector<int>     posOf;   // original row → position
    std::vector<int>     source;  // position → original row of the bound source, or −1
    bool                 anyCoupled = false;  // some source ≥ 0: the coupling loops have work
    std::vector<Slot>    slot;
    std::vector<std::uint8_t> frozen;  // position → box frozen for the current drive
    lcp::Ldlt            factor;  // of a[C][C]
    bool                 matrixDeferred = false;  // swaps and rotations leave a to releaseAll
    int                  nC = 0;
    int                  nP = 0;

    // Scratch, all of size capacity (or capacity² where noted).
    std::vector<Real> dx, dw, y, scratch;  // scratch: 3·capacity
    std::vector<Real> tie;                 // per position: c_k of a tied friction row, else 0
    std::vector<int>  linkColumn;          // per position: column of a linked source, or −1
    std::vector<int>  linkSources;         // positions of linked sources
    lcp::Workspace    linkZ;               // capacity²: one solved column per linked source (releaseAll: A)
    lcp::Workspace    linkK;               // capacity²: the small capacitance system
    std::vector<int>  linkPivot;
    std::vector<int>  failed;              // original rows, reported in LcpResult
    std::vector<int>  pending;             // original rows found wrong by checkPattern

    // Per-solve numbers.
    int  pivots = 0;
    int  maxPivots = 0;
    bool pivotLimitHit = false;
    Real tolW = 0;       // |w| at or below this is zero
    Real tolRel = 0;     // relative tolerance for x against bounds
    Real minPivotRel = 0;
    Real deltaW = 0;     // |Δw| per unit step below this is rounding noise
    std::uint64_t order = 0;  // state of the drive-order shuffle (reset per solve: deterministic)

    // lcp_exact_setup.cpp
    void reserve(int n);
    void load(const LcpProblem& problem, std::span<const LcpRowState> warm);
    void buildInitialFactor(int nCandidates);
    // New bounds (in original row order) for a loaded problem without coupling; the pattern,
    // its factorisation and the pivot order stay, the per-solve counts start again.
    void rebox(std::span<const Real> newLo, std::span<const Real> newHi);
    void swapPositions(int p, int q);
    void removeFromClamped(int p, Slot to);  // factor removal + rotation to position nC
    bool addToClamped(int p, const Real* forwardSolved);  // swap p to nC and append; false: singular
    void release(int p);                    // processed → unprocessed, keeping x in its box
    void releaseAll(std::span<const int> rows);  // release(posOf[row]) for each original row in turn
    // The current impulses and pattern as a guess in original row order (unprocessed rows: Unknown).
    void saveGuess(std::span<Real> outX, std::span<LcpRowState> outStates) const;
    void finish(const LcpProblem& problem, std::span<Real> outX, std::span<LcpRowState> ioStates,
                LcpResult& result, LcpStatus status);

    bool coupled(int p) const { return source[p] >= 0; }
    Real tolX(Real bound) const { return tolRel * std::max(Real(1), std::abs(bound)); }
    Real couplingBound(int p) const { return mu[p] * std::abs(x[posOf[source[p]]]); }  // mu·|x_source|

    // lcp_exact.cpp: solve-check-pivot passes from the loaded state until a pattern holds.
    // Returns false, before any pivoting, when stopIfFirstFails and the first pass's check fails;
    // otherwise true, with the status and the passes taken.
    bool settle(bool stopIfFirstFails, LcpStatus& status, int& passes);

    // lcp_exact_pattern.cpp
    void solvePattern(bool tieFriction);
    // Checks every processed row against the current x and returns how many are wrong. Those
    // are released (made unprocessed, to be pivoted again); or, with `flip`, only the worst one
    // changes sides (a clamped row out of its box goes to that bound, a bound row with the wrong
    // w into C: a single principal pivot, cheap when a warm start is nearly right), and 0 is
    // returned when no row can be flipped that way.
    int  checkPattern(bool tieFriction, bool flip);
    // Friction rows at a bound whose normal q is clamped (or is row `driven`) are tied to it:
    // x_k = c_k·x_q with c_k = ±mu_k·sign(x_q) (drivenSign stands for the sign of a driven
    // normal at 0). Fills tie[nC, nP); returns how many rows are tied.
    int  markTies(int driven, Real drivenSign);
    // v holds A_CC⁻¹ r; turns it into the solution of the clamped rows' equations with the tied
    // rows following their normals (Woodbury, see lcp_exact_pattern.cpp). False: singular.
    bool correctForTies(Real* v);

    // lcp_exact_pivot.cpp
    void pivotUnprocessed(int pass);  // the pass number picks the order of the drives

private:
    bool driveRow(int i);  // false when the pivot cap stopped it
    Real direction(int i, Real s, bool& ioUntied, bool& outForwardKept);  // fills dx; returns Δw_i
};

}  // namespace af
