// Exact solver, pattern stage: given which rows are clamped (C) and which sit at a bound, solve
// for x exactly, then check every processed row and release the ones the pattern got wrong.
//
// Untied solve: rows outside C keep their values (bounds, or held values), and
//     A_CC x_C = b_C − A_C,rest x_rest
// is one solve with the current factorisation.
//
// Tied solve (friction coupling): a friction row k at a bound is not at a constant but at
// x_k = c_k·x_q with c_k = ±mu_k·sign(x_q), where q is its normal. When q is in C, substituting
// gives
//     (A_CC + Σ_q u_q e_qᵀ) x_C = r,   u_q = Σ_{k tied to q} c_k A_C,k,
// a rank-m change of A_CC (m = normals with sliding friction rows). By Woodbury, with
// y = A_CC⁻¹ r and Z = A_CC⁻¹ [u_q], the normals' values ξ solve the small m×m system
// (I + Z_S) ξ = y_S, and then x_C = y − Z ξ. The factorisation is reused unchanged: the tied
// pattern costs m extra solves and one tiny LU, not a non-symmetric refactorisation.

#include "dynamics/lcp_internal.h"

#include <algorithm>
#include <cmath>

namespace af {

namespace {

using Slot = lcp::Slot;

// Relative size of an LU pivot of the capacitance system below which the tied system counts as
// singular (friction so strong that the normals are not determined by the pattern).
constexpr Real kLinkPivotRelative = 1e-13;


// Solves the k×k system K ξ = rhs in place (K row-major, stride k) by Gaussian elimination with
// partial pivoting. Returns false when a pivot is negligible.
bool luSolveSmall(Real* K, int k, Real* rhs, int* pivotRow) {
    Real scale = 0;
    for (int i = 0; i < k * k; ++i) {
        scale = std::max(scale, std::abs(K[i]));
    }
    for (int c = 0; c < k; ++c) {
        int best = c;
        for (int r = c + 1; r < k; ++r) {
            if (std::abs(K[r * k + c]) > std::abs(K[best * k + c])) {
                best = r;
            }
        }
        pivotRow[c] = best;
        if (!(std::abs(K[best * k + c]) > kLinkPivotRelative * scale)) {
            return false;
        }
        if (best != c) {
            std::swap_ranges(K + best * k, K + best * k + k, K + c * k);
            std::swap(rhs[best], rhs[c]);
        }
        const Real inv = 1 / K[c * k + c];
        for (int r = c + 1; r < k; ++r) {
            const Real f = K[r * k + c] * inv;
            if (f != 0) {
                for (int j = c + 1; j < k; ++j) {
                    K[r * k + j] -= f * K[c * k + j];
                }
                rhs[r] -= f * rhs[c];
            }
        }
    }
    for (int c = k - 1; c >= 0; --c) {
        Real v = rhs[c];
        for (int j = c + 1; j < k; ++j) {
            v -= K[c * k + j] * rhs[j];
        }
        rhs[c] = v / K[c * k + c];
    }
    return true;
}

}  // namespace

int LcpExactSolver::Impl::markTies(int driven, Real drivenSign) {
    int count = 0;
    for (int k = nC; k < nP; ++k) {
        tie[k] = 0;
        if (!coupled(k) || !atBound(slot[k])) {
            continue;
        }
        const int q = posOf[source[k]];
        if (q < nC || q == driven) {
            const Real v = x[q];
            const Real sign = v > 0 ? Real(1) : v < 0 ? Real(-1) : (q == driven ? drivenSign : Real(1));
            tie[k] = (slot[k] == Slot::AtLower ? Real(-1) : Real(1)) * mu[k] * sign;
            count += tie[k] != 0 ? 1 : 0;
        }
    }
    return count;
}

bool LcpExactSolver::Impl::correctForTies(Real* v) {
    const std::size_t sn = static_cast<std::size_t>(n);
    int               k = 0;
    for (int p = nC; p < nP; ++p) {
        const int q = tie[p] != 0 ? posOf[source[p]] : n;
        if (q >= nC) {
            continue;  // untied, or tied to the driven row (the caller's right-hand side has it)
        }
        if (linkColumn[q] < 0) {
            linkColumn[q] = k;
            linkSources[k] = q;
            std::fill_n(linkZ.data() + k * sn, nC, Real(0));
            ++k;
        }
        // u_q += c_p A_C,p (column p of A is row p).
        lcp::axpy(linkZ.data() + linkColumn[q] * sn, tie[p], a.data() + p * sn, nC);
    }
    if (k == 0) {
        return true;
    }
    for (int c = 0; c < k; ++c) {
        factor.solve(linkZ.data() + c * sn);
    }
    Real* K = linkK.data();
    Real* xi = scratch.data();
    for (int r = 0; r < k; ++r) {
        for (int c = 0; c < k; ++c) {
            K[r * k + c] = (r == c ? Real(1) : Real(0)) + linkZ[c * sn + linkSources[r]];
        }
        xi[r] = v[linkSources[r]];
    }
    const bool ok = luSolveSmall(K, k, xi, linkPivot.data());
    if (ok) {
        for (int c = 0; c < k; ++c) {
            lcp::axpy(v, -xi[c], linkZ.data() + c * sn, nC);
        }
    }
    for (int c = 0; c < k; ++c) {
        linkColumn[linkSources[c]] = -1;
    }
    return ok;
}

void LcpExactSolver::Impl::solvePattern(bool tieFriction) {
    // Rows at a bound sit exactly on it; sources are never coupled, so uncoupled rows first.
    for (int p = nC; p < nP; ++p) {
        if (!coupled(p) && atBound(slot[p])) {
            x[p] = slot[p] == Slot::AtLower ? lo[p] : hi[p];
        }
    }
    int nTied = 0;
    if (tieFriction && anyCoupled) {
        nTied = markTies(-1, 1);
    } else {
        std::fill(tie.begin() + nC, tie.begin() + nP, Real(0));
    }
    for (int p = nC; p < nP && anyCoupled; ++p) {
        if (!coupled(p) || !atBound(slot[p])) {
            continue;
        }
        if (tie[p] != 0) {
            x[p] = 0;  // kept out of the right-hand side; the correction accounts for it
            continue;
        }
        if (tieFriction) {
            const Real bound = couplingBound(p);
            lo[p] = -bound;
            hi[p] = bound;
        }
        x[p] = slot[p] == Slot::AtLower ? lo[p] : hi[p];
    }

    // x_C := A_CC⁻¹ (b_C − A_C,rest x_rest), using the symmetry of A to read rows.
    const std::size_t sn = static_cast<std::size_t>(n);
    for (int m = 0; m < nC; ++m) {
        x[m] = b[m] - lcp::dot(a.data() + m * sn + nC, x.data() + nC, n - nC);
    }
    factor.solve(x.data());
    if (nTied == 0) {
        return;
    }
    // When the tied system is singular the untied values stay; the check then finds friction
    // rows off their bounds, and the pass loop reports NotConverged if that never settles.
    correctForTies(x.data());
    for (int p = nC; p < nP; ++p) {
        if (tie[p] != 0) {
            const Real bound = couplingBound(p);
            lo[p] = -bound;
            hi[p] = bound;
            x[p] = tie[p] * x[posOf[source[p]]];
        }
    }
}

int LcpExactSolver::Impl::checkPattern(bool tieFriction, bool flip) {
    if (tieFriction && anyCoupled) {
        for (int p = 0; p < nP; ++p) {
            if (coupled(p) && (slot[p] == Slot::Clamped || atBound(slot[p]))) {
                const Real bound = couplingBound(p);
                lo[p] = -bound;
                hi[p] = bound;
            }
        }
    }
    const std::size_t sn = static_cast<std::size_t>(n);
    pending.clear();
    int  worst = -1;  // with `flip`: the row with the largest violation, measured in units of w
    Real worstSize = 0;
    auto note = [&](int p, Real size) {
        pending.push_back(perm[p]);
        if (size > worstSize) {
            worstSize = size;
            worst = perm[p];
        }
    };

    // Rows outside C: the sign of w must match the bound they sit on. Their A x in one product
    // (their rows of A are contiguous), cheaper than a dot product per row.
    if (nP > nC) {
        using RowMajor = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        const Eigen::Map<const RowMajor> outside(a.data() + nC * sn, nP - nC, n);
        lcp::VecMap(dw.data() + nC, nP - nC).noalias() = outside * lcp::ConstVecMap(x.data(), n);
    }
    for (int p = nC; p < nP; ++p) {
        const Slot s = slot[p];
        if (s == Slot::Failed) {
            continue;
        }
        const Real wp = dw[p] - b[p];
        w[p] = wp;
        const bool onLower = std::isfinite(lo[p]) && std::abs(x[p] - lo[p]) <= tolX(lo[p]);
        const bool onUpper = std::isfinite(hi[p]) && std::abs(x[p] - hi[p]) <= tolX(hi[p]);
        bool       bad = false;
        if (s == Slot::AtLower) {
            bad = !onLower || (wp < -tolW && !onUpper);
        } else if (s == Slot::AtUpper) {
            bad = !onUpper || (wp > tolW && !onLower);
        } else if (s == Slot::Held) {
            bad = std::abs(wp) > tolW;
        }
        if (bad) {
            note(p, atBound(s) && (s == Slot::AtLower ? onLower : onUpper) ? std::abs(wp) : kLcpInfinity);
        }
    }
    // Clamped rows have w = 0 by construction; they only have to stay inside their box.
    for (int p = 0; p < nC; ++p) {
        const Real over = std::max(lo[p] - x[p], x[p] - hi[p]);
        if (over > tolX(over > 0 && x[p] > hi[p] ? hi[p] : lo[p])) {
            note(p, over * a[p * sn + p]);
        } else {
            w[p] = 0;
        }
    }

    if (flip) {
        // One block-pivoting step on the worst row only: flipping every wrong row at once
        // overshoots badly when a row's free value is far outside its box (a sliding contact).
        if (worst >= 0 && worstSize < kLcpInfinity) {
            const int p = posOf[worst];
            if (p < nC) {
                const bool up = x[p] > hi[p];
                x[p] = up ? hi[p] : lo[p];
                removeFromClamped(p, up ? Slot::AtUpper : Slot::AtLower);
            } else {
                addToClamped(p, nullptr);
            }
            ++pivots;
        }
        return worst >= 0 && worstSize < kLcpInfinity ? static_cast<int>(pending.size()) : 0;
    }
    releaseAll(pending);
    return static_cast<int>(pending.size());
}

}  // namespace af
