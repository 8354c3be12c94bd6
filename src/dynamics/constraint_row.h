#pragma once
// One velocity-level constraint row, the unit every constraint type writes and the solver reads.
//
// A row couples body A and body B (an index into the island's bodies, or kWorldBody for the
// immovable world) through its Jacobian: the constraint velocity is
//     Cdot = linearA·v_A + angularA·ω_A + linearB·v_B + angularB·ω_B.
// The solver finds an impulse λ (lo ≤ λ ≤ hi) applied as Jᵀλ so that, for the velocities after
// the step, Cdot = target for a free row, Cdot ≥ target at the lower bound, Cdot ≤ target at the
// upper bound (the LCP of lcp.h with w = Cdot − target). A contact or a limit has
// lo = 0, hi = +∞; a joint row is unbounded; a friction row takes its bounds from the impulse of
// another row (frictionSource) times frictionCoefficient.
//
// `error` is the position-level violation C along the row (same sign convention as Cdot), used
// by the position correction after integration; 0 for rows that only act on velocities.

#include "af/dynamics/rigid_body.h"

#include <limits>
#include <utility>
#include <vector>

namespace af {

inline constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

struct ConstraintRow {
    int bodyA = kWorldBody;
    int bodyB = kWorldBody;
    Vec3 linearA = Vec3::Zero();
    Vec3 angularA = Vec3::Zero();
    Vec3 linearB = Vec3::Zero();
    Vec3 angularB = Vec3::Zero();
    Real target = 0;        // wanted Cdot (restitution, motors); error correction is separate
    Real error = 0;         // C, position level
    Real lo = -kInfinity;
    Real hi = kInfinity;
    int frictionSource = -1;       // row index (in the same list) whose impulse bounds this one
    Real frictionCoefficient = 0;  // bounds ±coefficient·|λ_source|
    Real cfm = 0;                  // softness: added to the diagonal of J M⁻¹ Jᵀ
};

// Rows of one step, in a vector that keeps its capacity from step to step.
class ConstraintRows {
public:
    void clear() { rows_.clear(); }
    // Appends a row and returns its index (for frictionSource).
    int add(const ConstraintRow& row) {
        rows_.push_back(row);
        return static_cast<int>(rows_.size()) - 1;
    }
    // Appends a row made in place from all of its members, in ConstraintRow's order: each is
    // written once (no temporary to copy, no default row zeroed first: a default row cost ~20 of
    // the ~155 instructions of appending a joint row). Its index is size() − 1. A compiler without
    // parenthesised aggregate initialisation (P0960: clang before 16) gets the same row made from
    // braces and moved in.
    template <class... Members>
    void appendMade(Members&&... members) {
#if defined(__cpp_aggregate_paren_init) && __cpp_aggregate_paren_init >= 201902L
        rows_.emplace_back(std::forward<Members>(members)...);
#else
        rows_.push_back(ConstraintRow{std::forward<Members>(members)...});
#endif
    }
    std::size_t size() const { return rows_.size(); }
    ConstraintRow& operator[](std::size_t i) { return rows_[i]; }
    const ConstraintRow& operator[](std::size_t i) const { return rows_[i]; }
    const std::vector<ConstraintRow>& all() const { return rows_; }

private:
    std::vector<ConstraintRow> rows_;
};

}  // namespace af
