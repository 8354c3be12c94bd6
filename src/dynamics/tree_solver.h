#pragma once
// The fast path of the constraint solve: a figure's joint tree factorised in time linear in the
// number of bodies (Baraff 1996, docs/doom-physics.md §4.4), and every other row solved as a boxed
// LCP on the small Schur complement that the tree leaves (docs/doom-physics.md §4.5), warm-started from the
// previous solve. It gives the same impulses as the dense path (RowSystem + LcpExactSolver) on the same
// rows, up to rounding.
//
// Primary rows (docs/doom-physics.md §4.2, as a spanning forest rather than Doom's body1-has-no-parent rule):
// joints are taken in their order; a joint is primary when it has equality rows (not a spring) and joins
// two parts of the figure not yet joined, where the world (and any static body) is one part. So
// the first joint to the world roots its body's tree, and a joint that would close a loop, a
// second path to the world included, stays auxiliary with all its rows. Only the equality rows of
// primary joints are primary; limit, joint friction and contact rows (every row after the joints'
// rows) are auxiliary.
//
// Primary rows keep the CFM they carry (Doom gives them none), so the answer is the dense one.
//
// Units and frames are those of the rows (constraint_row.h): world frame, impulses
// in mass·length/s for the velocity problem, mass·length for the position problem.
//
// Use, per step:  setStructure once per figure (and when its joints change); then at every pose
// factor(rows at that pose), then solveVelocity and/or solvePosition as often as needed, then
// applyImpulses or applyDisplacements. No heap allocation once the largest row count has been
// seen (buffers keep their capacity). Not thread-safe; one solver per figure or thread.

#include "af/dynamics/rigid_body.h"
#include "constraint_row.h"
#include "joint_rows.h"
#include "lcp.h"

#include <cstdint>
#include <memory>
#include <span>

namespace af {

struct TreeSolveResult {
    LcpStatus status = LcpStatus::Solved;  ///< of the auxiliary LCP; InvalidInput for rows that do
                                           ///< not fit the structure, Unsatisfiable if a tree block
                                           ///< could not be factorised (no CFM on dependent rows)
    int  primaryRows = 0;
    int  auxiliaryRows = 0;                ///< the size of the LCP (rows left out are neither)
    int  pivots = 0;                       ///< LcpResult::pivots of the auxiliary LCP
    int  couplingPasses = 0;
    Real residual = 0;                     ///< natural residual of the auxiliary LCP (lcp.h)
    bool iterative = false;                ///< the auxiliary LCP was beyond the pivot row limit (or
                                           ///< pivoting was off) and solved by projected
                                           ///< Gauss–Seidel (its status Solved)
    bool frozenAnswer = false;             ///< NotConverged, and the auxiliary rows hold the
                                           ///< frozen-box answer (frozen_boxes.h) instead of the
                                           ///< failed solve's: impulses() is usable, its joints held
};

/// Which problems a factorisation serves. The position problem holds friction rows at 0, so a
/// factorisation for it alone leaves them (and any row with lo = hi = 0) out of the Schur
/// complement: a smaller LCP, and their λ is 0.
enum class TreeProblems { VelocityAndPosition, PositionOnly };

class TreeSolver {
public:
    explicit TreeSolver(const LcpExactSettings& settings = {});
    ~TreeSolver();
    TreeSolver(TreeSolver&&) noexcept;
    TreeSolver& operator=(TreeSolver&&) noexcept;

    void setSettings(const LcpExactSettings& settings);
    /// An auxiliary LCP of more rows than this (0: no limit) is solved by projected Gauss–Seidel
    /// on the Schur complement, warm-started, instead of by pivoting: a pivot costs O(rows²) and
    /// a few hundred contacts take thousands (a 57-body figure lying flat: seconds a step). The
    /// joints stay exact; the contacts and limits are as converged as `pgs` leaves them.
    void setPivotRowLimit(std::size_t rows, const LcpPgsSettings& pgs = {});
    /// false: every auxiliary LCP is solved as one beyond the pivot row limit, whatever its size
    /// (a caller whose pivoting of these rows failed too often; see FigureBlockSolver).
    void setPivoting(bool allowed);

    /// Chooses the primary joints and orders the tree. `bodies` decides which bodies are static
    /// (inverseMass 0, treated as the world); joints' body indices refer to it. Throws
    /// std::invalid_argument for a body index out of range.
    void setStructure(std::span<const RigidBody> bodies, std::span<const Joint> joints);
    /// Whether joint k's equality rows are primary.
    bool isPrimary(int joint) const;
    /// Forgets the row states of the last solves, so the next ones start cold (after a teleport,
    /// or to measure).
    void resetWarmStart();

    /// Factorises the primary rows and forms the Schur complement of the others at the bodies'
    /// current poses. `ranges[k]` says where joint k's rows are in `rows` (writeJointRows); rows
    /// outside every range (contacts) are auxiliary. Keeps no reference to its arguments. Rows
    /// that do not fit the structure (a primary joint without 1 to 6 equality rows, or whose rows
    /// couple other bodies) make the solves return InvalidInput until the next factor().
    /// `rowKeys`, when given (one per row), name the rows for the warm start, as World's keys
    /// do (unique, stable while the row exists; see World's warm start); otherwise a row is
    /// known by its joint and place, or by its place after the joints' rows.
    void factor(const ConstraintRows& rows, std::span<const JointRowRange> ranges, std::span<const RigidBody> bodies,
                TreeProblems problems = TreeProblems::VelocityAndPosition,
                std::span<const std::uint64_t> rowKeys = {});

    /// The solves take the rows given to factor() (their targets, errors and bounds are read
    /// here, the rest was read there).
    ///
    /// The velocity problem of the factorised rows: b_i = target_i − Cdot_i (current velocities),
    /// bounds and friction coupling as the rows give them. InvalidInput after a PositionOnly
    /// factorisation. Each problem's LCP starts from the row states its last solve ended with,
    /// matched by identity (joint k's limit row q, its friction row q, the q-th row after the
    /// joints' rows) and bodies; rows without a match start unknown.
    TreeSolveResult solveVelocity(const ConstraintRows& rows, std::span<const RigidBody> bodies);
    /// The same, the auxiliary LCP started from a guess per row (in the rows' order; Unknown
    /// where there is none) instead of the last solve's states: a caller that solves most steps
    /// by another path has a fresher guess than this solver's last solve, which may be many
    /// steps old.
    TreeSolveResult solveVelocity(const ConstraintRows& rows, std::span<const RigidBody> bodies,
                                  std::span<const LcpRowState> guessStates, std::span<const Real> guessImpulses);
    /// The position problem: b_i = −error_i; friction rows (coupled rows and joint friction rows)
    /// are held at 0.
    TreeSolveResult solvePosition(const ConstraintRows& rows);
    /// The same for a caller that moves the bodies itself from impulses(): applyImpulses and
    /// applyDisplacements move nothing after it (the sums per body they read are not made).
    TreeSolveResult solvePositionImpulses(const ConstraintRows& rows);

    /// The primary rows alone factorised at the bodies' poses, for primaryResponse and
    /// addPrimaryImpulses (the solves above need factor() again after it).
    void factorPrimary(const ConstraintRows& rows, std::span<const JointRowRange> ranges,
                       std::span<const RigidBody> bodies);
    /// After factorPrimary: every body's velocity change per unit impulse along (linear,
    /// angular) on `body` with the primary rows holding (the articulated response, H⁻¹ of the
    /// impulse), written per body into the outputs. False when not factorised.
    bool primaryResponse(int body, const Vec3& linear, const Vec3& angular, std::span<Vec3> linearOut,
                         std::span<Vec3> angularOut);
    /// After factorPrimary: adds to rowImpulses (one per row given to it) the primary rows'
    /// impulses that hold them while the impulses Jᵀλ summed per body (linear, angular) act.
    void addPrimaryImpulses(std::span<const Vec3> linear, std::span<const Vec3> angular, std::span<Real> rowImpulses);

    /// λ of every row of the last solve, in the rows' order.
    std::span<const Real> impulses() const;
    /// v += M⁻¹ Jᵀ λ for the last solve's λ (rows as given to factor).
    void applyImpulses(std::span<RigidBody> bodies) const;
    /// Positions moved by M⁻¹ Jᵀ λ (centre by the linear part, orientation turned by the angular).
    void applyDisplacements(std::span<RigidBody> bodies) const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace af
