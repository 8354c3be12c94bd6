#pragma once
// Block Gauss–Seidel over the figures of one island (docs/solver.md, "Islands of many figures").
// A figure is a set of bodies joined by joints. Its rows (equality, limits, joint friction, and
// its contacts with itself and with the world) form one block, solved exactly as a figure alone
// is: the sparse path, the tree solver behind it. The rows between two figures (their contacts)
// are relaxed one at a time between the blocks, as projected Gauss–Seidel does, and each block
// sees their impulses as given ones. Every sweep ends with the blocks, so whatever the contacts
// between figures have converged to, each figure's joints hold as exactly as if it were alone.
//
// Why: a pile of figures is one island. One exact solve over all of its rows costs O(rows²) per
// pivot, and Gauss–Seidel over all of them leaves the joints open by millimetres; within a figure
// the joints are what Gauss–Seidel converges slowest on, and the tree makes them cheap to solve
// exactly.

#include "af/dynamics/joints.h"
#include "constraint_row.h"
#include "frozen_boxes.h"
#include "joint_rows.h"
#include "lcp.h"
#include "row_system.h"
#include "solver_tuning.h"
#include "sparse_lcp.h"
#include "tree_solver.h"
#include "worker_pool.h"

#include <cstdint>
#include <span>
#include <vector>

namespace af {

enum class BlockProblem { Velocity, Position };

struct BlockSolveResult {
    LcpStatus status = LcpStatus::Solved;  // NotConverged: a block's last solve found no answer
    int sweeps = 0;                        // block passes made
    int treeFallbacks = 0;                 // block solves the sparse path handed to the tree
    Real lastChange = 0;                   // the largest change of a row between figures, last sweep
    Real residual = 0;                     // natural residual of the rows between figures
};

class FigureBlockSolver {
public:
    // The figures of the island's bodies: those joined by joints (springs join nothing; a
    // spring's rows between two figures are rows between figures). Call when the bodies or
    // joints change; `bodies` decides, as for the tree solver, which bodies are static (a
    // static body's response is zero).
    void setStructure(std::span<const RigidBody> bodies, std::span<const Joint> joints);
    std::size_t figureCount() const { return figures_.size(); }
    // A block whose auxiliary rows (contacts, limits, joint friction) outnumber this has them
    // solved by projected Gauss–Seidel in its tree solver (TreeSolver::setPivotRowLimit).
    void setPivotRowLimit(std::size_t rows) { pivotRowLimit_ = rows; }

    // Solves the problem in `system` (responses built, b set; for Position, b = −error and the
    // friction rows held at 0) for `rows`, whose joint rows `ranges` gives in the joints' order
    // of setStructure. system.solution() and states() carry the warm start in and the answer
    // out (states as statesFromImpulses gives them). `keys` name the rows (warm_start.h). The
    // sweeps stop when one changes no row between figures by more than stopChange in its own
    // units (velocity, or length for Position), or after tuning.blocks.maxSweeps.
    // With a pool, the blocks of a sweep are solved on its threads: a block reads the impulses
    // between figures, which no block writes, and writes only its own figure's state, so the
    // answer is the same bits on any number of threads.
    BlockSolveResult solve(BlockProblem problem, const ConstraintRows& rows, std::span<const JointRowRange> ranges,
                           std::span<const std::uint64_t> keys, RowSystem& system, std::span<const RigidBody> bodies,
                           const SolverTuning& tuning, Real stopChange, WorkerPool* pool = nullptr);

private:
    struct Figure {
        std::vector<int> bodies;  // island indices, ascending
        std::vector<int> joints;  // island indices
        std::vector<Joint> localJoints;
        // This solve's block: the figure's rows in the island's order, renumbered.
        std::vector<std::size_t> rows;  // island indices
        ConstraintRows localRows;
        std::vector<JointRowRange> ranges;
        std::vector<std::uint64_t> keys;
        std::vector<RowResponse> responses;
        std::vector<RigidBody> localBodies;
        std::vector<Real> islandB, b, lo, hi, mu, cfm, x, lastX;
        std::vector<int> findex;
        std::vector<LcpRowState> states;
        SparseLcpSolver sparse;
        TreeSolver tree;
        RowSystem system;  // the block's dense system, for solveDense alone
        bool treeReady = false;
        bool pushed = false;  // an impulse between figures changed since the block's last solve
        bool failed = false;  // the block's last solve found no answer (solveDense's fallback stands)
        // Pivots of this solve's failed pivoting solves of the block (tree and dense). Past the
        // budget (SolverTuning::Blocks::pivotsPerRow), the block's later sweeps relax the
        // tree's auxiliary rows instead: a failed pivoting solve costs thousands of pivots, and
        // the next sweep's nearly equal block often fails again.
        long failedPivots = 0;
        bool factored = false;  // the tree holds this solve's factor(): later sweeps reuse it
        int treeFallbacks = 0;  // this solve's block solves the sparse path handed to the tree
        // solveDense's solvers, and scratch per body of the figure (the velocity change of the
        // block's answer, the impulses between figures on it).
        LcpExactSolver exact;
        LcpPgsSolver pgs;
        FrozenBoxFallback frozenBoxes;
        std::vector<Vec3> linearChange, angularChange;
    };
    void gatherBlocks(const ConstraintRows& rows, std::span<const JointRowRange> ranges,
                      std::span<const std::uint64_t> keys, RowSystem& system, std::span<const RigidBody> bodies);
    bool solveBlock(BlockProblem problem, Figure& figure, const ConstraintRows& rows, std::span<const RigidBody> bodies,
                    const SolverTuning& tuning);
    void forEachFigure(WorkerPool* pool, std::span<const std::size_t> which, const std::function<void(Figure&)>& task);
    TreeSolveResult solveByTree(BlockProblem problem, Figure& figure, std::span<const RigidBody> bodies,
                                const SolverTuning& tuning);
    LcpResult solveDense(Figure& figure, const SolverTuning& tuning);
    bool mayPivot(const Figure& figure, const SolverTuning& tuning) const;
    Real relaxBetween(const ConstraintRows& rows, const RowSystem& system, std::span<Real> x);
    Real respond(std::size_t k, const ConstraintRows& rows, const LcpProblem& p);
    void pushBetween(std::size_t k, const ConstraintRows& rows, const LcpProblem& p, Real impulse);
    Real boundOf(const LcpProblem& problem, std::span<const Real> x, std::size_t i, Real& lo) const;

    std::vector<Figure> figures_;
    std::size_t pivotRowLimit_ = 0;
    std::vector<int> figureOf_;  // per island body
    std::vector<int> localOf_;   // per island body, its index in its figure
    std::vector<int> rowFigure_;  // per row of this solve: its figure, or −1 between figures
    std::vector<int> localRow_;   // per row: its index in its block
    std::vector<std::size_t> between_;  // the rows between figures
    // Per row between figures (in between_'s order): where its sides' articulated responses are
    // in responseLinear_/Angular_ (one entry per body of the side's figure), and 1/(J H⁻¹ Jᵀ + cfm).
    struct BetweenResponse {
        bool known = false;
        int offsetA = 0, offsetB = 0;
        Real invDiagonal = 0;
    };
    std::vector<BetweenResponse> responses_;
    std::vector<Vec3> responseLinear_, responseAngular_;
    // Per island body: the velocity change (or move) of the blocks' impulses and of those
    // between figures.
    std::vector<Vec3> blockLinear_, blockAngular_, betweenLinear_, betweenAngular_;
    std::vector<Vec3> impulseLinear_, impulseAngular_;  // per island body: Jᵀλ of the rows between figures
    std::vector<std::size_t> sweepFigures_;             // the figures a sweep solves
};

}  // namespace af
