#pragma once
// An island: awake bodies joined (directly or through others) by joints or contacts, solved on
// its own. The bodies are copied into contiguous local arrays (rows, joints and contact points
// renumbered to them), so that the cost of a step grows with each island's size rather than
// with the whole world's, and two figures that do not touch never share a dense system.
//
// The step of an island (island_step.cpp, SHAKE's part in island_shake.cpp, the projection in
// island_project.cpp) is the world's step after velocity integration: rows, velocity solve,
// position integration, SHAKE, position projection. Its order and reasons are those of
// af/dynamics/world.h.

#include "af/dynamics/world.h"
#include "contact_set.h"
#include "figure_blocks.h"
#include "frozen_boxes.h"
#include "joint_errors.h"
#include "lcp.h"
#include "row_pgs.h"
#include "row_source.h"
#include "row_system.h"
#include "shake.h"
#include "solver_counters.h"
#include "solver_tuning.h"
#include "sparse_lcp.h"
#include "tree_solver.h"
#include "warm_start.h"

#include <cstdint>
#include <vector>

namespace af {

// What every island of a step shares: the settings and the solvers' tuning, the extra row
// source (called on the world's bodies, see Island::writeRows) and where the islands' reports,
// counters and warm starts are gathered.
struct IslandContext {
    const WorldSettings& settings;
    const SolverTuning& tuning;
    const RowSource& extraRows;
    std::vector<RigidBody>& worldBodies;
    StepReport& report;
    SolverCounters& counters;
    const WarmStartCache& velocityWarmStart;  // the previous step's rows, all islands
    // The energy the island's position projections put into its springs (stretching one while
    // closing a joint or lifting a body out of a brush): work the guard must allow, since the
    // projection moves positions that no force moved (world_guard.cpp).
    Real& projectedSpringWork;
    // Threads for the work within the island (the figure blocks of a pile), when it is stepped
    // alone: the world's pool, or none while the islands share it out.
    WorkerPool* pool = nullptr;
};

// What the islands are gathered from. `localOf` maps every world body to its index in its own
// island, or to kOutsideIsland (resting bodies, which no row of an island touches).
inline constexpr int kOutsideIsland = -2;
struct IslandWorld {
    std::span<const RigidBody> bodies;
    const std::vector<Joint>& joints;
    std::span<const ContactPoint> points;
    std::span<const int> localOf;
};

class Island {
public:
    // Copies the bodies (ascending world indices), the joints (world indices) and the contact
    // points (indices into world.points) into the local arrays, renumbered.
    void gather(std::span<const int> bodyIds, std::span<const int> jointIds, std::span<const int> pointIds,
                const IslandWorld& world);
    // Writes the bodies and the joints' impulses back.
    void scatter(std::vector<RigidBody>& worldBodies, std::vector<Joint>& worldJoints) const;

    // The step after velocity integration (see the file comment).
    void step(Real dt, IslandContext& context);
    // The projection alone, with the contact points gathered last (settling new contacts).
    void project(IslandContext& context);
    Real maxPenetration() const { return af::maxPenetration(points_, bodies_); }

    // The rows of this step's velocity solve, for the next step's warm start.
    const WarmStartCache& velocityWarmStart() const { return velocityCache_; }

private:
    // The joint rows are those measureJointErrors kept (restRows_) if they still hold.
    // atStepStart: the bodies are at the poses the step's points were placed at (the velocity solves).
    void writeRows(IslandContext& context, bool atStepStart = false);
    // The joint rows' errors at the bodies' poses (jointErrors_, errorRanges_). With keepRows the
    // joint rows are written whole instead (restRows_, restRanges_, their errors read there) for
    // the next writeRows to take: a measure is mostly followed by rows at the same poses, a
    // projection pass's or the next step's (bench drop: of a settling step's 4 to 6 joint row
    // writes, all but SHAKE's capture and the measure between its two steps, which moves the
    // bodies again).
    void measureJointErrors(const IslandContext& context, bool keepRows = true);
    bool restRowsHold(const IslandContext& context) const;
    // largestViolation() of the rows writeRows would write now, from the last measure (at
    // the current poses) and the contact points, without writing them. Not for an extra source.
    Real measuredViolation(const IslandContext& context) const;
    // A row's target before the velocity solve, from its Cdot at the current velocities and its
    // impulse in the warm start.
    static void allowApproach(ConstraintRow& row, Real cdot, Real dt, Real previous);
    static void holdDespiteSoftness(ConstraintRow& row, Real previous);
    LcpStatus solveVelocities(IslandContext& context);
    bool solveWithTree(IslandContext& context, bool& frozen);
    bool solveSparse(const WarmStartCache& guess, IslandContext& context);
    // v += M⁻¹Jᵀλ of the velocity solve's answer.
    void applyImpulses();
    void statesFromImpulses(const IslandContext& context);
    void solveWithFrozenFriction(const LcpProblem& problem, IslandContext& context);
    // The velocity solve: rows written at the step's start, solved, impulses applied; solved
    // again with plain targets (no bounce, no softness hold) if it gained energy (gainedEnergy).
    bool solveVelocityRows(Real dt, IslandContext& context, bool firstSolve);
    // A contact row asking for a separating speed (restitution).
    static bool isBounce(const ConstraintRow& row) { return row.lo == 0 && row.frictionSource < 0 && row.target > 0; }
    struct BodyVelocities {
        std::vector<Vec3> linear, angular;
    };
    bool gainedEnergy() const;
    void rememberVelocities(BodyVelocities& into) const;
    void restoreVelocities(const BodyVelocities& from);
    void leaveOutFarPoints(Real dt, const IslandContext& context);
    bool bringBackClosingPoints(Real dt, const IslandContext& context);
    bool closeDrift(Real dt, IslandContext& context);
    bool captureDrift(const IslandContext& context);
    bool outrunsItsMove(Real dt, Real move) const;
    bool keepsMoreEnergy(Real dt, const IslandContext& context);
    // The joints' rows alone at the bodies' poses, without keys: what SHAKE reads. rows_ is whole
    // again after the next writeRows.
    void writeJointRowsOnly(const IslandContext& context);
    std::span<const char> limitsToHold(const ConstraintRows& startRows, const std::vector<JointRowRange>& startRanges,
                                       const std::vector<JointRowRange>& moved);
    // jointErrorsAtPoses: the joint errors are already measured at the bodies' current poses.
    void projectPositions(IslandContext& context, bool jointErrorsAtPoses);
    bool moveWhileImproving(Real& violation, IslandContext& context);
    bool chordStep(Real& violation, IslandContext& context);
    void writeNormalsOnly();
    Real violationAtPoses(IslandContext& context);
    LcpStatus solvePositions();
    bool solvePositionsWithTree(IslandContext& context, Real violation);
    bool putBackViolated();
    Real largestViolation() const;
    Real springEnergy(const IslandContext& context) const;
    Real liftWork(const IslandContext& context) const;
    // Beyond exactRowLimit rows of a pivoting solve: all rows for the dense solve, the rows
    // outside the joint trees' equality rows for the tree solver.
    bool large(const IslandContext& context) const {
        std::size_t pivoted = rows_.size();
        if (context.settings.solver == SolverKind::Tree)
            for (const JointRowRange& range : ranges_) pivoted -= static_cast<std::size_t>(range.equalityRows);
        return pivoted > context.settings.exactRowLimit;
    }
    // Whether the figures' blocks solve this island (figure_blocks.h): the tree solver's
    // answer for an island too large to pivot over.
    bool blocked(const IslandContext& context) const {
        return context.settings.solver == SolverKind::Tree && large(context);
    }
    // Whether PGS solves this island's velocities.
    bool iterative(const IslandContext& context) const {
        return context.settings.solver == SolverKind::Pgs || (large(context) && !blocked(context));
    }
    // stopChange: see FigureBlockSolver::solve.
    LcpStatus solveByFigures(BlockProblem problem, IslandContext& context, Real stopChange);

    std::vector<int> bodyIds_;
    std::vector<int> jointIds_;
    std::vector<RigidBody> bodies_;
    std::vector<Joint> joints_;
    std::vector<ContactPoint> points_;
    // The points the velocity solve writes rows for, and those it leaves out (see
    // leaveOutFarPoints) with where their pA and pB are, which the solves do not move;
    // writeRows takes nearPoints_ instead of points_ while nearPointsOnly_. A far point is named
    // by its place in points_, not copied (resting bench ragdoll, 34 far points a step:
    // leaveOutFarPoints 7.2k -> 6.1k instructions, bringBackClosingPoints 3.3k -> 3.5k). The
    // projection puts its frictionless copies of points_ there (writeNormalsOnly).
    struct FarPoint {
        std::size_t point;  // in points_
        Vec3 onA, onB;
        Real gap = 0;  // slop + n·(pA − pB)
        bool staysApart = false;  // the last bringBackClosingPoints bounded its closing below gap
    };
    struct BodySpeed {
        Real linear, angular;  // |v|, |ω|
    };
    std::vector<BodySpeed> bodySpeeds_;  // scratch of bringBackClosingPoints
    std::vector<ContactPoint> nearPoints_;
    std::vector<FarPoint> farPoints_;
    bool nearPointsOnly_ = false;
    // The bodies moved only by the step's integration since the last bringBackClosingPoints: the
    // far points that stay apart are still apart (see measuredViolation).
    bool farPointsApart_ = false;
    BodyVelocities velocitiesAtStart_;      // of the step, while far points are left out (bringBackClosingPoints)
    BodyVelocities velocitiesBeforeSolve_;  // see gainedEnergy
    bool plainTargets_ = false;  // a solve of this step gained energy: its solves have plain targets
    std::span<const int> localOf_;
    bool treeReady_ = false;  // the tree's structure is that of joints_ (same bodies, same joints)

    ConstraintRows rows_;
    std::vector<std::uint64_t> rowKeys_;
    std::vector<JointRowRange> ranges_;
    ConstraintRows extra_;  // scratch: rows of the extra source, world numbering
    std::vector<int> extraIndex_;
    std::vector<RowError> jointErrors_;
    std::vector<JointRowRange> errorRanges_;
    // The bodies' world inverse inertias rows_ were written with (in system_ or restInertia_):
    // valid until the next writeRows, measureJointErrors or buildResponses.
    std::span<const Mat3> rowInertia_;
    std::vector<Mat3> rowRotations_;  // scratch of writeJointRowsOnly and measureJointErrors: rotation()s
    // Joint rows measureJointErrors kept, and what they were written from.
    struct RestPose {
        Vec3 position;
        Quat orientation;
        Real inverseMass;
        Mat3 inverseInertia;
    };
    ConstraintRows restRows_;
    std::vector<JointRowRange> restRanges_;
    std::vector<Mat3> restInertia_, restRotations_;
    std::vector<RestPose> restPoses_;
    std::vector<Real> restImpulses_;
    JointRowSettings restSettings_;
    bool restRowsHeld_ = false;
    bool restedLastStep_ = false;  // the last step neither moved by SHAKE nor projected
    bool projectedLastStep_ = false;  // the last projection made a pass (see projectPositions)
    RowSystem system_;
    LcpExactSolver exact_;
    LcpExactSolver exactPosition_;
    TreeSolver tree_;
    SparseLcpSolver sparse_;
    bool sparseAnswered_ = false;  // the sparse path found this velocity solve's answer
    LcpPgsSolver pgs_;
    RowPgs rowPgs_;
    FigureBlockSolver blocks_;
    bool blocksReady_ = false;  // blocks_'s structure is that of joints_
    ShakeCorrection shake_;
    ShakeCorrection keptEnergy_;  // projects velocities onto the joints at the moved poses
    bool driftedLastStep_ = false;  // SHAKE had a drift to close in the last step
    // The velocity solve's rows, kept for SHAKE's capture while the joint rows are written at the
    // moved poses (see closeDrift).
    ConstraintRows startRows_;
    std::vector<JointRowRange> startRanges_;
    std::vector<RigidBody> beforeShake_;
    std::vector<char> holdLimit_;  // see limitsToHold
    std::vector<RigidBody> beforeProjection_;
    std::vector<RigidBody> projectionStart_;  // the bodies as projectPositions found them (with springs)
    // Rows solvePositionsWithTree leaves out of its LCP, with their upper bounds.
    struct HeldRow {
        std::size_t row;
        Real hi;
    };
    std::vector<HeldRow> leftOut_;
    std::vector<Vec3> shiftLinear_, shiftAngular_;
    bool shiftsOfSolution_ = false;  // the shifts are M⁻¹Jᵀ of this pass's system_.solution()
    WarmStartCache velocityCache_;
    WarmStartCache positionCache_;  // the last position pass of this island (this step or before)
    FrozenBoxFallback frozenBoxes_;
    bool settingsSet_ = false;
};

}  // namespace af
