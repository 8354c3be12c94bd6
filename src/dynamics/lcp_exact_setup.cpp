// Exact solver, setup and bookkeeping: loading a problem into pivot order (with the warm-start
// guess), keeping the permuted copy of A consistent when rows change sets, and writing results.

#include "dynamics/lcp_internal.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace af {

namespace {

using Slot = lcp::Slot;

// Below this many units of |Δw| per unit of step (relative to A's largest diagonal entry), a
// bound row's w is taken not to move: rounding noise must not trigger pivots. A row whose w does
// drift across zero this way is caught by the check after the pass.
constexpr Real kDeltaWRelative = 1e-13;

// Default pivot cap per row, Doom's idLCP limit of 32 iterations per variable.
constexpr int kDefaultPivotsPerRow = 32;

// Load order: the initial clamped set, then the guessed-at-bound rows, then the rows to pivot,
// uncoupled before coupled so that friction bounds see solved normals (ODE's order).
enum Group : int { kClampedGuess, kBoundGuess, kToPivot, kCoupledToPivot, kGroups };

Real clampReal(Real v, Real lo, Real hi) { return std::min(std::max(v, lo), hi); }

// The caller's state of a row in a slot; Unknown for a row not settled (failed or unprocessed).
LcpRowState stateOf(Slot slot) {
    switch (slot) {
        case Slot::Clamped:
        case Slot::Held: return LcpRowState::Free;
        case Slot::AtLower: return LcpRowState::AtLower;
        case Slot::AtUpper: return LcpRowState::AtUpper;
        case Slot::Failed:
        case Slot::Unprocessed: break;
    }
    return LcpRowState::Unknown;
}

// dst[q] = src[from[q]] for q < n. The gather is most of a load's cost and GCC does not unroll
// it: four entries per trip halve the loop's overhead.
void gather(Real* dst, const Real* src, const int* from, int n) {
    int q = 0;
    for (; q + 4 <= n; q += 4) {
        dst[q] = src[from[q]];
        dst[q + 1] = src[from[q + 1]];
        dst[q + 2] = src[from[q + 2]];
        dst[q + 3] = src[from[q + 3]];
    }
    for (; q < n; ++q) {
        dst[q] = src[from[q]];
    }
}

}  // namespace

void LcpExactSolver::Impl::reserve(int size) {
    if (size <= capacity) {
        return;
    }
    const std::size_t n1 = static_cast<std::size_t>(size);
    const std::size_t n2 = n1 * n1;
    a.resize(n2);
    for (std::vector<Real>* v : {&x, &b, &lo, &hi, &w, &mu, &dx, &dw, &y, &tie}) {
        v->resize(n1);
    }
    boxLo.reserve(n1);
    boxHi.reserve(n1);
    boxStates.reserve(n1);
    boxPattern.reserve(n1);
    scratch.resize(3 * n1);
    for (std::vector<int>* v : {&perm, &posOf, &source, &linkSources, &linkPivot}) {
        v->resize(n1);
    }
    linkColumn.assign(n1, -1);
    slot.resize(n1);
    frozen.assign(n1, 0);
    linkZ.resize(n2);
    linkK.resize(n2);
    failed.reserve(n1);
    pending.reserve(n1);
    factor.reserve(size);
    capacity = size;
}

void LcpExactSolver::Impl::load(const LcpProblem& problem, std::span<const LcpRowState> warm) {
    n = problem.size;
    reserve(n);
    const bool hasCoupling = !problem.findex.empty();

    // Sort rows into their groups, stably (original order within a group keeps runs repeatable).
    int   counts[kGroups] = {};
    int*  group = linkPivot.data();  // scratch: linkPivot is not in use while loading
    for (int r = 0; r < n; ++r) {
        const bool        isCoupled = hasCoupling && problem.findex[r] >= 0;
        const Real        l = problem.lo[r];
        const Real        h = problem.hi[r];
        const LcpRowState guess = warm.empty() ? LcpRowState::Unknown : warm[r];
        int               g = isCoupled ? kCoupledToPivot : kToPivot;
        if (!isCoupled && l == -kLcpInfinity && h == kLcpInfinity) {
            g = kClampedGuess;
        } else if (guess == LcpRowState::Free && (isCoupled || l < h)) {
            g = kClampedGuess;
        } else if ((guess == LcpRowState::AtLower && (isCoupled || l > -kLcpInfinity)) ||
                   (guess == LcpRowState::AtUpper && (isCoupled || h < kLcpInfinity))) {
            g = kBoundGuess;
        }
        group[r] = g;
        ++counts[g];
    }
    int start[kGroups];
    for (int g = 0, sum = 0; g < kGroups; ++g) {
        start[g] = sum;
        sum += counts[g];
    }
    for (int r = 0; r < n; ++r) {
        const int p = start[group[r]]++;
        perm[p] = r;
        posOf[r] = p;
    }

    // Per-position data. Coupled bounds are unknown until their normal is solved: [0, 0] for now.
    Real bInf = 0;
    Real aMax = 0;
    anyCoupled = false;
    for (int p = 0; p < n; ++p) {
        const int r = perm[p];
        b[p] = problem.b[r];
        bInf = std::max(bInf, std::abs(b[p]));
        source[p] = hasCoupling ? problem.findex[r] : -1;
        mu[p] = hasCoupling && source[p] >= 0 ? problem.mu[r] : 0;
        anyCoupled = anyCoupled || source[p] >= 0;
        lo[p] = source[p] >= 0 ? 0 : problem.lo[r];
        hi[p] = source[p] >= 0 ? 0 : problem.hi[r];
        w[p] = 0;
        const LcpRowState guess = warm.empty() ? LcpRowState::Unknown : warm[r];
        if (p < counts[kClampedGuess]) {
            slot[p] = Slot::Clamped;
            x[p] = 0;
        } else if (p < counts[kClampedGuess] + counts[kBoundGuess]) {
            slot[p] = guess == LcpRowState::AtLower ? Slot::AtLower : Slot::AtUpper;
            x[p] = slot[p] == Slot::AtLower ? lo[p] : hi[p];
        } else {
            slot[p] = Slot::Unprocessed;
            x[p] = clampReal(0, lo[p], hi[p]);
        }

        // Row p of the permuted matrix, with CFM on the diagonal.
        Real* dst = a.data() + static_cast<std::size_t>(p) * n;
        gather(dst, problem.a.data() + static_cast<std::size_t>(r) * n, perm.data(), n);
        dst[p] += settings.cfm + (problem.cfm.empty() ? Real(0) : problem.cfm[r]);
        aMax = std::max(aMax, dst[p]);
    }

    tolW = settings.tolerance * std::max(Real(1), bInf);
    tolRel = settings.tolerance;
    minPivotRel = settings.pivotTolerance;
    deltaW = kDeltaWRelative * std::max(aMax, std::numeric_limits<Real>::min());
    pivots = 0;
    maxPivots = settings.maxPivots > 0 ? settings.maxPivots : kDefaultPivotsPerRow * n;
    pivotLimitHit = false;
    order = 0;
    failed.clear();

    factor.reset(n);
    nC = 0;
    nP = counts[kClampedGuess] + counts[kBoundGuess];
    buildInitialFactor(counts[kClampedGuess]);
}

void LcpExactSolver::Impl::rebox(std::span<const Real> newLo, std::span<const Real> newHi) {
    for (int p = 0; p < n; ++p) {
        lo[p] = newLo[perm[p]];
        hi[p] = newHi[perm[p]];
    }
    pivots = 0;
    pivotLimitHit = false;
    order = 0;
    failed.clear();
}

void LcpExactSolver::Impl::buildInitialFactor(int nCandidates) {
    // A candidate that depends on those before it cannot be factorised: it moves behind the
    // candidates and is held at its start value; the check after the first solve decides whether
    // it is consistent (w = 0) or must be pivoted.
    int end = nCandidates;
    int p = 0;
    while (p < end) {
        const Real* row = a.data() + static_cast<std::size_t>(p) * n;
        if (factor.append(row, row[p], minPivotRel * std::max(row[p], Real(0)), scratch.data())) {
            slot[p] = Slot::Clamped;
            ++p;
        } else {
            swapPositions(p, end - 1);
            --end;
            slot[end] = Slot::Held;
            x[end] = clampReal(0, lo[end], hi[end]);
        }
    }
    nC = end;
}

void LcpExactSolver::Impl::swapPositions(int p, int q) {
    if (p == q) {
        return;
    }
    const std::size_t sn = static_cast<std::size_t>(n);
    if (!matrixDeferred) {
        std::swap_ranges(a.begin() + p * sn, a.begin() + (p + 1) * sn, a.begin() + q * sn);
        for (std::size_t r = 0; r < sn; ++r) {
            std::swap(a[r * sn + p], a[r * sn + q]);
        }
    }
    std::swap(x[p], x[q]);
    std::swap(b[p], b[q]);
    std::swap(lo[p], lo[q]);
    std::swap(hi[p], hi[q]);
    std::swap(w[p], w[q]);
    std::swap(mu[p], mu[q]);
    std::swap(source[p], source[q]);
    std::swap(slot[p], slot[q]);
    std::swap(frozen[p], frozen[q]);
    std::swap(perm[p], perm[q]);
    posOf[perm[p]] = p;
    posOf[perm[q]] = q;
}

void LcpExactSolver::Impl::removeFromClamped(int p, Slot to) {
    factor.remove(p, scratch.data());
    // The factor's rows below p moved up by one; rotate positions [p, nC) to match, which puts
    // the removed row at nC − 1, the first position after the shrunk clamped set.
    const std::size_t sn = static_cast<std::size_t>(n);
    if (p + 1 < nC && !matrixDeferred) {
        // Rotation by one as a saved entry and a memmove: std::rotate's generic cycle of swaps
        // cost more than the factor's own update.
        const std::size_t moved = static_cast<std::size_t>(nC - p - 1);
        Real* const       rowP = a.data() + p * sn;
        std::copy_n(rowP, sn, scratch.data());
        std::memmove(rowP, rowP + sn, sizeof(Real) * moved * sn);
        std::copy_n(scratch.data(), sn, a.data() + (nC - 1) * sn);
        // Locals: the memmove call would make the compiler reload nC and a's storage per row.
        Real* const       rows = a.data();
        const std::size_t first = static_cast<std::size_t>(p);
        const std::size_t last = static_cast<std::size_t>(nC - 1);
        for (std::size_t r = 0; r < sn; ++r) {
            Real* const row = rows + r * sn;
            const Real  entry = row[first];
            std::memmove(row + first, row + first + 1, sizeof(Real) * moved);
            row[last] = entry;
        }
    }
    if (p + 1 < nC) {
        auto rot = [&](auto& v) { std::rotate(v.begin() + p, v.begin() + p + 1, v.begin() + nC); };
        rot(x);
        rot(b);
        rot(lo);
        rot(hi);
        rot(w);
        rot(mu);
        rot(source);
        rot(slot);
        rot(frozen);
        rot(perm);
        for (int q = p; q < nC; ++q) {
            posOf[perm[q]] = q;
        }
    }
    --nC;
    slot[nC] = to;
}

bool LcpExactSolver::Impl::addToClamped(int p, const Real* forwardSolved) {
    swapPositions(p, nC);
    const Real* row = a.data() + static_cast<std::size_t>(nC) * n;
    const Real  diag = row[nC];
    const Real  minPivot = minPivotRel * std::max(diag, Real(0));
    const bool  ok = forwardSolved ? factor.appendForwardSolved(forwardSolved, diag, minPivot)
                                   : factor.append(row, diag, minPivot, scratch.data());
    w[nC] = 0;
    if (!ok) {
        slot[nC] = Slot::Held;
        return false;
    }
    slot[nC] = Slot::Clamped;
    ++nC;
    return true;
}

void LcpExactSolver::Impl::release(int p) {
    if (p < nC) {
        x[p] = std::min(std::max(x[p], lo[p]), hi[p]);
        removeFromClamped(p, Slot::Unprocessed);
        ++pivots;
        p = nC;
    }
    swapPositions(p, nP - 1);
    --nP;
    slot[nP] = Slot::Unprocessed;
}

void LcpExactSolver::Impl::releaseAll(std::span<const int> rows) {
    // Each release moves a row and a column of A, a clamped one a block of them; when more than
    // a quarter of the rows go, one gather of A into the final order costs less than all those
    // moves (measured on bench single: an eighth or a sixteenth gained less, a half lost).
    const bool batch = rows.size() * 4 > static_cast<std::size_t>(n);
    int* const oldPos = linkPivot.data();  // scratch: no tied solve is under way
    if (batch) {
        std::copy_n(posOf.data(), n, oldPos);
        matrixDeferred = true;
    }
    for (const int row : rows) {
        release(posOf[row]);
    }
    if (!batch) {
        return;
    }
    matrixDeferred = false;
    int* const from = linkSources.data();  // position → position before the releases
    for (int p = 0; p < n; ++p) {
        from[p] = oldPos[perm[p]];
    }
    const std::size_t sn = static_cast<std::size_t>(n);
    for (int p = 0; p < n; ++p) {
        gather(linkZ.data() + p * sn, a.data() + static_cast<std::size_t>(from[p]) * sn, from, n);
    }
    a.swap(linkZ);  // linkZ is scratch of the same size
}

void LcpExactSolver::Impl::saveGuess(std::span<Real> outX, std::span<LcpRowState> outStates) const {
    for (int p = 0; p < n; ++p) {
        const int r = perm[p];
        outX[r] = x[p];
        outStates[r] = stateOf(slot[p]);
    }
}

void LcpExactSolver::Impl::finish(const LcpProblem& problem, std::span<Real> outX,
                                  std::span<LcpRowState> ioStates, LcpResult& result,
                                  LcpStatus status) {
    failed.clear();
    for (int p = 0; p < n; ++p) {
        const int r = perm[p];
        outX[r] = x[p];
        LcpRowState state = stateOf(slot[p]);
        if (state == LcpRowState::Unknown) {
            state = LcpRowState::Failed;
            failed.push_back(r);
        }
        if (!ioStates.empty()) {
            ioStates[r] = state;
        }
    }
    std::sort(failed.begin(), failed.end());
    if (status == LcpStatus::Solved && !failed.empty()) {
        status = LcpStatus::Unsatisfiable;
    }
    result.status = status;
    result.pivots = pivots;
    result.failedRows = std::span<const int>(failed.data(), failed.size());
    result.residual = settings.computeResidual ? lcpResidual(problem, outX, settings.cfm) : 0;
}

}  // namespace af
