// Exact solver, pivot stage: Dantzig's method for the boxed LCP (Baraff 1994 "Fast contact
// force computation for nonpenetrating rigid bodies"; the scheme of ODE's dLCP and Doom's
// idLCP_Symmetric), driving one unprocessed row at a time to complementarity while every
// processed row stays complementary.
//
// Driving row i: w_i = (Ax − b)_i is moved towards zero by changing x_i in direction s (x_i
// decreases when w_i > 0). To keep w_C = 0 the clamped rows follow, Δx_C = −s A_CC⁻¹ A_C,i; then
// Δw_i = s·σ with σ = A_ii − A_iC A_CC⁻¹ A_Ci > 0 (a Schur complement of a positive definite
// matrix), so |w_i| shrinks monotonically whatever the pivots do. The step is the largest one
// that keeps every processed row valid; the row that limits it changes sets (one append or one
// removal of the LDLᵀ factor) and the drive goes on, until i itself is settled: w_i reaches 0
// (i joins C) or x_i reaches a bound (i stays there).
//
// Friction coupling. ODE and Doom fix a friction row's box from its normal when the row is
// reached and never look back, so their answer satisfies the bounds of normals that have
// moved on since. Here the boxes move with the normals during the drive:
//  * a friction row at a bound whose normal is clamped (or is row i) is tied to it,
//    x_k = ±mu_k·|x_q|, and moves with it; the clamped rows absorb that motion through a rank-m
//    Woodbury correction of the same factorisation (m = normals with tied rows);
//  * clamped friction rows and row i meet boxes that move at mu·sign(x_q)·Δx_q per unit step;
//  * a normal whose sign would flip ends a step (the rates change there).
// Every processed row then stays complementary with the true coupled bounds, so a drive ends in
// a valid state of the coupled problem. The tied system is not symmetric, and Δw_i/Δx_i may then
// lose its sign: a friction row may find neither side valid and flip between C and its bound in
// zero steps, or its box may close in on x_i. In those cases the drive goes on with boxes frozen
// (plain Dantzig, which always progresses) and the pattern check after the pass (and the next
// pass) repairs what that left stale.

#include "dynamics/lcp_internal.h"

#include <algorithm>
#include <cmath>

namespace af {

namespace {

using Slot = lcp::Slot;


// A clamped row whose Δx per unit step is below this is taken not to move (rounding noise).
// If it does creep over its bound, the check after the pass releases it.
constexpr Real kDeltaX = 1e-13;

// Zero-length steps in a row after which a drive stops tying friction rows (see driveRow).
constexpr int kMaxZeroStepsTied = 4;

enum class Event { None, ReachZero, ReachBound, ClampedHitsBound, BoundRowFrees, SourceCrossesZero };

}  // namespace

void LcpExactSolver::Impl::pivotUnprocessed(int pass) {
    while (nP < n) {
        if (pivotLimitHit) {
            for (int p = nP; p < n; ++p) {
                slot[p] = Slot::Failed;
            }
            nP = n;
            return;
        }
        // Order of the drives: as loaded on the first pass, backwards on the second, then
        // shuffled by a fixed rule; a pass that left rows wrong is not repeated the same way.
        if (pass == 2) {
            swapPositions(nP, n - 1);
        } else if (pass > 2) {
            order = order * 6364136223846793005ull + 1442695040888963407ull;
            swapPositions(nP, nP + static_cast<int>((order >> 33) % static_cast<std::uint64_t>(n - nP)));
        }
        if (!driveRow(nP)) {
            pivotLimitHit = true;
        }
    }
}

Real LcpExactSolver::Impl::direction(int i, Real s, bool& untied, bool& forwardKept) {
    const std::size_t sn = static_cast<std::size_t>(n);
    const Real*       ai = a.data() + i * sn;
    int               nTied = 0;
    if (untied) {
        std::fill(tie.begin() + nC, tie.begin() + nP, Real(0));
    } else {
        nTied = markTies(i, s);
        for (int k = nC; k < nP; ++k) {
            if (tie[k] != 0 && frozen[k]) {
                tie[k] = 0;
                --nTied;
            }
        }
    }
    std::fill(dx.begin() + nC, dx.begin() + nP, Real(0));
    dx[i] = s;
    if (nTied == 0) {
        // Plain Dantzig: y = L⁻¹ A_C,i is kept, it is the forward solve that appending i needs,
        // and σ comes from it without cancellation.
        std::copy_n(ai, nC, y.data());
        factor.forward(y.data());
        std::copy_n(y.data(), nC, dx.data());
        factor.scale(dx.data());
        const Real sigma = ai[i] - lcp::dot(y.data(), dx.data(), nC);
        factor.backward(dx.data());
        if (nC > 0) {
            lcp::VecMap(dx.data(), nC) *= -s;
        }
        forwardKept = true;
        return s * sigma;
    }
    // Tied friction rows move with their normals, Δx_k = c_k Δx_q; the clamped rows must absorb
    // that too: (A_CC + Σ u_q e_qᵀ) Δx_C = −s (A_C,i + Σ_{k tied to i} c_k A_C,k).
    forwardKept = false;
    for (int m = 0; m < nC; ++m) {
        dx[m] = -s * ai[m];
    }
    for (int k = nC; k < nP; ++k) {
        if (tie[k] != 0 && posOf[source[k]] == i) {
            lcp::axpy(dx.data(), -s * tie[k], a.data() + k * sn, nC);
        }
    }
    factor.solve(dx.data());
    if (!correctForTies(dx.data())) {
        untied = true;  // the tied system is singular here: carry on as plain Dantzig
        return direction(i, s, untied, forwardKept);
    }
    for (int k = nC; k < nP; ++k) {
        if (tie[k] != 0) {
            dx[k] = tie[k] * dx[posOf[source[k]]];
        }
    }
    return lcp::dot(ai, dx.data(), nP + 1);
}

bool LcpExactSolver::Impl::driveRow(int i) {
    const std::size_t sn = static_cast<std::size_t>(n);
    const Real*       ai = a.data() + i * sn;
    const Real        aii = ai[i];

    auto refreshBound = [&](int p) {
        if (coupled(p)) {
            const Real bound = couplingBound(p);
            lo[p] = -bound;
            hi[p] = bound;
        }
    };
    refreshBound(i);
    x[i] = std::min(std::max(x[i], lo[i]), hi[i]);
    Real wi = lcp::dot(ai, x.data(), n) - b[i];
    // Tied friction makes the drive's matrix non-symmetric, and then a friction row can find
    // neither side valid (free, it leaves its moving box; at its bound, its w turns wrong) and
    // flip between them with zero steps. After a few zero steps that row's box is frozen where
    // it is (as ODE freezes all of them) for the rest of the drive; if zero steps go on, the whole
    // drive continues untied, plain Dantzig on a positive definite matrix, which progresses.
    // The pattern check after the pass re-ties whatever was frozen.
    bool untied = !anyCoupled;  // without coupling, plain Dantzig from the start
    bool frozenBox = false;  // also row i's own box, once it overtook x_i (see ReachBound)
    int  zeroSteps = 0;
    if (anyCoupled) {
        std::fill_n(frozen.begin(), n, std::uint8_t(0));
    }

    for (;;) {
        const bool atLo = x[i] <= lo[i];
        const bool atHi = x[i] >= hi[i];
        if ((atLo && wi >= -tolW) || (atHi && wi <= tolW)) {
            slot[i] = (atLo && wi >= -tolW) ? Slot::AtLower : Slot::AtUpper;
            w[i] = wi;
            ++nP;
            return true;
        }
        if (!atLo && !atHi && std::abs(wi) <= tolW) {
            addToClamped(i, nullptr);
            ++pivots;
            ++nP;
            return true;
        }
        if (pivots >= maxPivots) {
            slot[i] = Slot::Failed;
            w[i] = wi;
            ++nP;
            return false;
        }
        // A friction row shut at [0, 0] by a zero normal may sit on either side; let it sit on
        // the side its w allows, so that it is valid when the normal opens its box.
        for (int k = nC; k < nP && anyCoupled; ++k) {
            if (coupled(k) && atBound(slot[k]) && lo[k] == hi[k]) {
                slot[k] = w[k] >= 0 ? Slot::AtLower : Slot::AtUpper;
            }
        }

        const Real s = wi > 0 ? Real(-1) : Real(1);
        bool       forwardKept = false;
        const Real dwi = direction(i, s, untied, forwardKept);
        const int  span = forwardKept ? nC : nP + 1;  // dx is zero on untied rows outside C
        // Δw of the rows at a bound, except where any w is valid: fixed uncoupled rows, and
        // friction rows shut at [0, 0] by a normal that stays put.
        for (int k = nC; k < nP; ++k) {
            bool moving = atBound(slot[k]) && lo[k] < hi[k];
            if (coupled(k) && atBound(slot[k]) && !untied && !frozen[k]) {
                const int q = posOf[source[k]];
                moving = lo[k] < hi[k] || ((q < nC || q == i) && mu[k] > 0);
            }
            dw[k] = moving ? lcp::dot(a.data() + k * sn, dx.data(), span) +
                                 (forwardKept ? s * a[k * sn + i] : Real(0))
                           : Real(0);
        }

        // How fast a row's box moves: the normal q changes at dx[q], so the bound mu·|x_q| of a
        // friction row changes at mu·sign(x_q)·dx[q] (dx holds s at i).
        auto boundRate = [&](int p) {
            if (!coupled(p) || frozen[p] || (untied && (p != i || frozenBox))) {
                return Real(0);
            }
            const int  q = posOf[source[p]];
            const Real rq = q < nC || q == i ? dx[q] : Real(0);
            const Real sign = x[q] > 0 ? Real(1) : x[q] < 0 ? Real(-1) : (rq >= 0 ? Real(1) : Real(-1));
            return mu[p] * sign * rq;
        };
        // Step at which row p, moving at rp, meets its (moving) box; +∞ if never.
        auto timeToBound = [&](int p, Real rp, bool& upper) {
            const Real br = boundRate(p);
            const Real closeUp = rp - br;   // the gap hi − x shrinks at this speed
            const Real closeLo = -rp - br;  // the gap x − lo shrinks at this speed
            Real       t = kLcpInfinity;
            if (closeUp > kDeltaX) {
                t = (hi[p] - x[p]) / closeUp;
                upper = true;
            }
            if (closeLo > kDeltaX) {
                const Real tl = (x[p] - lo[p]) / closeLo;
                if (tl < t) {
                    t = tl;
                    upper = false;
                }
            }
            return t;
        };

        // Ratio test. Settling i wins ties: it ends the drive without touching the factor.
        Real  t = kLcpInfinity;
        Event event = Event::None;
        int   which = -1;
        bool  upper = false;
        if (s * dwi > minPivotRel * std::max(aii, Real(0))) {
            t = std::abs(wi) / (s * dwi);
            event = Event::ReachZero;
        }
        bool       iUpper = s > 0;
        const Real toBound = timeToBound(i, s, iUpper);
        if (toBound <= t) {
            t = toBound;
            event = Event::ReachBound;
        }
        for (int m = 0; m < nC; ++m) {
            bool       up = false;
            const Real tm = timeToBound(m, dx[m], up);
            if (tm < t) {
                t = tm;
                event = Event::ClampedHitsBound;
                which = m;
                upper = up;
            }
        }
        for (int k = nC; k < nP; ++k) {
            const Real d = dw[k];
            const bool closing = (slot[k] == Slot::AtLower && d < -deltaW) ||
                                 (slot[k] == Slot::AtUpper && d > deltaW);
            if (closing) {
                const Real tk = -w[k] / d;
                if (tk < t) {
                    t = tk;
                    event = Event::BoundRowFrees;
                    which = k;
                }
            }
        }
        // A normal whose sign would flip changes how its friction bounds move: stop there and
        // look again (a contact normal, bounded below by 0, hits its bound first instead).
        for (int p = 0; p <= nP && anyCoupled; ++p) {
            const bool inPlay = p == i || (!untied && (p < nC || (p < nP && tie[p] != 0)));
            if (!inPlay || !coupled(p) || frozen[p]) {
                continue;
            }
            const int  q = posOf[source[p]];
            const Real rq = q < nC || q == i ? dx[q] : Real(0);
            if ((x[q] > 0 && rq < -kDeltaX) || (x[q] < 0 && rq > kDeltaX)) {
                const Real tq = -x[q] / rq;
                if (tq < t) {
                    t = tq;
                    event = Event::SourceCrossesZero;
                    which = q;
                }
            }
        }
        if (!(t < kLcpInfinity)) {
            // Nothing limits the step: row i is unbounded in that direction and no motion of the
            // others can zero its w (a dependent, inconsistent row, or runaway friction).
            slot[i] = Slot::Failed;
            w[i] = wi;
            ++nP;
            return true;
        }
        t = std::max(t, Real(0));
        zeroSteps = t > 0 ? 0 : zeroSteps + 1;
        // After too many zero steps: freeze the box of the friction row that keeps flipping
        // (kept as an original row number: positions move in the step), else untie everything.
        int freezeRow = -1;
        if (zeroSteps > kMaxZeroStepsTied) {
            zeroSteps = 0;
            if (which >= 0 && coupled(which) && !frozen[which]) {
                freezeRow = perm[which];
            } else {
                untied = true;
            }
        }

        // Step. Tied rows and every moving box are recomputed from the normals afterwards, so
        // that they stay exactly on their bounds.
        lcp::axpy(x.data(), t, dx.data(), nC);
        x[i] += t * s;
        for (int k = nC; k < nP; ++k) {
            w[k] += t * dw[k];
        }
        wi += t * dwi;
        if (event == Event::SourceCrossesZero) {
            x[which] = 0;
        }
        if (!untied) {
            for (int p = 0; p < nC; ++p) {
                if (!frozen[p]) {
                    refreshBound(p);
                }
            }
        }
        if (!frozenBox) {
            refreshBound(i);
        }
        if (!forwardKept) {
            for (int k = nC; k < nP; ++k) {
                if (tie[k] != 0) {
                    refreshBound(k);
                    x[k] = slot[k] == Slot::AtLower ? lo[k] : hi[k];
                }
            }
        }

        switch (event) {
            case Event::ReachZero:
                addToClamped(i, forwardKept ? y.data() : nullptr);
                ++pivots;
                ++nP;
                return true;
            case Event::ReachBound:
                x[i] = iUpper ? hi[i] : lo[i];
                if (iUpper != (s > 0)) {
                    // The box closed in on x_i faster than x_i moves (its normal shrinks as it
                    // grows): at that bound w_i has the wrong sign. Freeze the boxes and go on.
                    untied = true;
                    frozenBox = true;
                    ++pivots;
                    break;
                }
                slot[i] = iUpper ? Slot::AtUpper : Slot::AtLower;
                w[i] = wi;
                ++nP;
                return true;
            case Event::ClampedHitsBound:
                x[which] = upper ? hi[which] : lo[which];
                removeFromClamped(which, upper ? Slot::AtUpper : Slot::AtLower);
                w[nC] = 0;
                ++pivots;
                break;
            case Event::BoundRowFrees:
                w[which] = 0;
                addToClamped(which, nullptr);
                ++pivots;
                break;
            case Event::SourceCrossesZero:
                ++pivots;  // no set change, but it counts against the cap like one
                break;
            case Event::None: break;
        }
        if (freezeRow >= 0) {
            frozen[posOf[freezeRow]] = 1;
        }
    }
}

}  // namespace af
