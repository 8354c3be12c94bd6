#pragma once
// Projected Gauss–Seidel on the rows themselves (sequential impulses): the LcpPgsSolver's
// iteration, with A = J M⁻¹ Jᵀ + diag(cfm) never formed. The impulses act through per-body
// accumulators Δv = Σ M⁻¹ Jᵀ λ, so a row's w_i = J_i·Δv + cfm_i λ_i − b_i costs O(1) and a sweep
// O(rows): what large islands need, where the dense matrix alone would cost O(rows²).
//
// Same problem, bounds, coupling, order, relaxation and stopping rule as LcpPgsSolver (lcp.h);
// the two agree up to rounding.

#include "lcp.h"
#include "row_system.h"

#include <span>
#include <vector>

namespace af {

class RowPgs {
public:
    // Solves the problem of `system` (its bounds, coupling, CFM and b, without its matrix: see
    // RowSystem::buildResponses) for the rows it was built from. ioX holds the warm start on
    // input (clamped into the boxes first) and the answer on output.
    LcpPgsResult solve(const ConstraintRows& rows, const RowSystem& system, std::size_t bodyCount,
                       std::span<Real> ioX, const LcpPgsSettings& settings);

private:
    std::vector<Real> invDiagonal_;
    std::vector<Vec3> linear_, angular_;  // per body: Δv and Δω of the current impulses
};

}  // namespace af
