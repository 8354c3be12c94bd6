#pragma once
// The sweeps both projected Gauss–Seidel solvers share (lcp_pgs.cpp on the dense matrix,
// row_pgs.cpp on the rows): each row in turn gets x_i − ω·w_i/A_ii, clamped into its box right
// away; rows with invDiagonal 0 stay put. Stops after a sweep that changes no x_i by more than
// tolerance·max(1, ‖x‖∞), or after maxIterations sweeps (status NotConverged).

#include "lcp.h"

#include <algorithm>
#include <cmath>
#include <span>

namespace af {

// bounds(i, lo, hi) gives row i's box at the current x; w(i) its current w_i = (Ax − b)_i;
// moved(i, change) is told every change of x_i before the next row is visited.
template <class Bounds, class W, class Moved>
void pgsSweeps(std::span<Real> x, std::span<const Real> invDiagonal, const LcpPgsSettings& settings,
               Bounds&& bounds, W&& w, Moved&& moved, LcpPgsResult& result) {
    result.status = LcpStatus::NotConverged;
    for (int it = 1; it <= settings.maxIterations; ++it) {
        Real maxChange = 0;
        Real maxAbs = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const Real inv = invDiagonal[i];
            if (inv == 0) continue;
            Real lo, hi;
            const Real wi = w(i);
            bounds(i, lo, hi);
            const Real next = std::clamp(x[i] - settings.sor * wi * inv, lo, hi);
            const Real change = next - x[i];
            x[i] = next;
            if (change != 0) moved(i, change);
            maxChange = std::max(maxChange, std::abs(change));
            maxAbs = std::max(maxAbs, std::abs(next));
        }
        result.iterations = it;
        result.lastChange = maxChange;
        if (maxChange <= settings.tolerance * std::max(Real(1), maxAbs)) {
            result.status = LcpStatus::Solved;
            return;
        }
    }
}

}  // namespace af
