#pragma once
// The dense system of one island's constraint rows: A = J M⁻¹ Jᵀ + diag(cfm), and applying
// impulses (or position displacements) Jᵀλ through M⁻¹. Workspace buffers keep their capacity
// from step to step, so a step allocates nothing once the figure's row count has been seen.

#include "af/dynamics/rigid_body.h"
#include "constraint_row.h"
#include "joint_rows.h"
#include "lcp.h"

#include <array>
#include <span>
#include <vector>

namespace af {

// M⁻¹ Jᵀ of one row, per side: the velocity change of each body per unit impulse.
struct RowResponse {
    Vec3 linearA, angularA, linearB, angularB;
};

// Adds λ_i times row i's response to the per-body sums (sized to the bodies, zeroed first): the
// velocity change, or the move, that the impulses λ cause.
void accumulateResponses(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                         std::span<const Real> lambda, std::vector<Vec3>& linear, std::vector<Vec3>& angular);

// The position problem's bounds: friction rows (joint friction, and rows boxed by another row)
// act on velocities only, so they are held at 0 and uncoupled.
void holdFrictionAtZero(ConstraintRows& rows, std::span<const JointRowRange> ranges);

// The row states of impulses x (one per row): a row at a bound (a friction row's box from its
// source's impulse) is there, within `tolerance` relative; any other is free. What a solver that
// keeps no states of its own (the tree, PGS) leaves the next solve's guess.
void statesFromImpulses(const ConstraintRows& rows, std::span<const Real> x, std::span<LcpRowState> states,
                        Real tolerance);
// The same for an LCP's rows, by its bounds and friction coupling (findex, mu).
void statesFromImpulses(const LcpProblem& problem, std::span<const Real> x, std::span<LcpRowState> states,
                        Real tolerance);

// Cdot of a row at the bodies' current velocities.
inline Real rowVelocity(const ConstraintRow& r, std::span<const RigidBody> bodies) {
    Real cdot = 0;
    if (r.bodyA != kWorldBody) {
        const RigidBody& a = bodies[static_cast<std::size_t>(r.bodyA)];
        cdot += r.linearA.dot(a.linearVelocity) + r.angularA.dot(a.angularVelocity);
    }
    if (r.bodyB != kWorldBody) {
        const RigidBody& b = bodies[static_cast<std::size_t>(r.bodyB)];
        cdot += r.linearB.dot(b.linearVelocity) + r.angularB.dot(b.angularVelocity);
    }
    return cdot;
}

// J of a row times per-body vectors: the velocity change or the move they hold for its bodies.
inline Real rowAlong(const ConstraintRow& r, std::span<const Vec3> linear, std::span<const Vec3> angular) {
    Real v = 0;
    if (r.bodyA != kWorldBody)
        v += r.linearA.dot(linear[static_cast<std::size_t>(r.bodyA)]) + r.angularA.dot(angular[static_cast<std::size_t>(r.bodyA)]);
    if (r.bodyB != kWorldBody)
        v += r.linearB.dot(linear[static_cast<std::size_t>(r.bodyB)]) + r.angularB.dot(angular[static_cast<std::size_t>(r.bodyB)]);
    return v;
}

// A_ij without CFM: row i's velocity per unit impulse of row j (response mj), through the bodies
// the two rows share.
inline Real rowCoupling(const ConstraintRow& ri, const ConstraintRow& rj, const RowResponse& mj) {
    Real v = 0;
    if (ri.bodyA != kWorldBody) {
        if (ri.bodyA == rj.bodyA) v += ri.linearA.dot(mj.linearA) + ri.angularA.dot(mj.angularA);
        if (ri.bodyA == rj.bodyB) v += ri.linearA.dot(mj.linearB) + ri.angularA.dot(mj.angularB);
    }
    if (ri.bodyB != kWorldBody) {
        if (ri.bodyB == rj.bodyA) v += ri.linearB.dot(mj.linearA) + ri.angularB.dot(mj.angularA);
        if (ri.bodyB == rj.bodyB) v += ri.linearB.dot(mj.linearB) + ri.angularB.dot(mj.angularB);
    }
    return v;
}

// Moves a body by a small displacement: its centre by `linear`, its orientation turned by the
// rotation vector `angular`.
void displaceBody(RigidBody& body, const Vec3& linear, const Vec3& angular);

class RowSystem {
public:
    // Fills A, lo, hi, findex, mu and cfm from `rows` at the bodies' current inertia; b is left
    // to the caller (velocity or position level). Rows with include[i] false are left out.
    void build(const ConstraintRows& rows, std::span<const RigidBody> bodies);
    // build in two parts: the responses, bounds and sizes (all that applying impulses needs,
    // O(rows)), then A (O(rows²)), which only the dense solvers read.
    void buildResponses(const ConstraintRows& rows, std::span<const RigidBody> bodies);
    // The same with each body's RigidBody::inverseInertiaWorld given (at the same poses: those
    // the rows were written with).
    void buildResponses(const ConstraintRows& rows, std::span<const RigidBody> bodies,
                        std::span<const Mat3> inverseInertiaWorld);
    void buildMatrix(const ConstraintRows& rows);

    // b_i = target_i − Cdot_i(current velocities): the velocity problem.
    void setVelocityRhs(const ConstraintRows& rows, std::span<const RigidBody> bodies);
    // The same, each row's target first changed by retarget(row, Cdot_i, x_i), x_i its impulse
    // in solution() (the warm start), in the same pass.
    template <class Retarget>
    void setVelocityRhs(ConstraintRows& rows, std::span<const RigidBody> bodies, Retarget&& retarget) {
        for (std::size_t i = 0; i < rows.size(); ++i) {
            ConstraintRow& row = rows[i];
            const Real cdot = rowVelocity(row, bodies);
            retarget(row, cdot, x_[i]);
            b_[i] = row.target - cdot;
        }
    }
    // b_i = −error_i: the position problem (J Δq = −C).
    void setPositionRhs(const ConstraintRows& rows);

    LcpProblem problem() const;
    std::span<Real> solution() { return x_; }
    std::span<LcpRowState> states() { return states_; }

    // v += M⁻¹ Jᵀ λ for every row's λ in solution().
    void applyImpulses(const ConstraintRows& rows, std::span<RigidBody> bodies);
    // x += M⁻¹ Jᵀ λ (linear), orientation turned by I⁻¹ Jᵀ λ (angular), with the rows' bodies as
    // buildResponses saw them, so the caller may rewrite its rows in between (the projection
    // moves, rewrites them to measure, and moves again) without keeping a copy of the rows.
    void applyDisplacements(std::span<RigidBody> bodies);

    const RowResponse& response(std::size_t row) const { return response_[row]; }
    std::span<const RowResponse> responses() const { return std::span(response_).first(static_cast<std::size_t>(n_)); }

    // Each body's RigidBody::inverseInertiaWorld at its current pose, computed once per body, for
    // writing or reading many rows at one pose. Valid until the next call of this or of build
    // or buildResponses (which compute it for their own bodies).
    std::span<const Mat3> inverseInertiasWorld(std::span<const RigidBody> bodies);
    // The same with each body's rotation() given, indexed as bodies.
    std::span<const Mat3> inverseInertiasWorld(std::span<const RigidBody> bodies, std::span<const Mat3> rotations);

private:
    int n_ = 0;
    std::vector<RowResponse> response_;
    std::vector<Real> a_, b_, lo_, hi_, mu_, cfm_, x_;
    std::vector<int> findex_;
    std::vector<LcpRowState> states_;
    std::vector<Vec3> linearShift_, angularShift_;
    std::vector<Mat3> inverseInertia_;
    std::vector<std::array<int, 2>> rowBodies_;  // per row: bodyA, bodyB at buildResponses
};

}  // namespace af
