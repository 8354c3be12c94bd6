// Block Gauss–Seidel over an island's figures; see figure_blocks.h.

#include "figure_blocks.h"

#include "disjoint_sets.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <utility>

namespace af {

namespace {

int localBody(int body, std::span<const int> localOf) {
    return body == kWorldBody ? kWorldBody : localOf[static_cast<std::size_t>(body)];
}

}  // namespace

void FigureBlockSolver::setStructure(std::span<const RigidBody> bodies, std::span<const Joint> joints) {
    const std::size_t n = bodies.size();
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    for (const Joint& j : joints)
        if (j.type != ConstraintType::Spring && j.bodyA != kWorldBody && j.bodyB != kWorldBody)
            joinSets(parent, j.bodyA, j.bodyB);
    figures_.clear();
    figureOf_.assign(n, -1);
    localOf_.assign(n, -1);
    std::vector<int> figureOfRoot(n, -1);
    for (std::size_t b = 0; b < n; ++b) {
        int& f = figureOfRoot[static_cast<std::size_t>(findRoot(parent, static_cast<int>(b)))];
        if (f < 0) {
            f = static_cast<int>(figures_.size());
            figures_.emplace_back();
        }
        figureOf_[b] = f;
        localOf_[b] = static_cast<int>(figures_[static_cast<std::size_t>(f)].bodies.size());
        figures_[static_cast<std::size_t>(f)].bodies.push_back(static_cast<int>(b));
    }
    for (std::size_t k = 0; k < joints.size(); ++k) {
        const Joint& j = joints[k];
        const int a = j.bodyA != kWorldBody ? figureOf_[static_cast<std::size_t>(j.bodyA)] : -1;
        const int b = j.bodyB != kWorldBody ? figureOf_[static_cast<std::size_t>(j.bodyB)] : -1;
        if ((a >= 0 && b >= 0 && a != b) || (a < 0 && b < 0)) continue;  // a spring between two figures
        Figure& figure = figures_[static_cast<std::size_t>(a >= 0 ? a : b)];
        figure.joints.push_back(static_cast<int>(k));
        Joint local = j;
        local.bodyA = localBody(j.bodyA, localOf_);
        local.bodyB = localBody(j.bodyB, localOf_);
        figure.localJoints.push_back(std::move(local));
    }
}

// Each row goes to the block of its bodies' figure, or between figures; a row boxed by a row of
// another block goes between figures too, where every impulse is at hand.
void FigureBlockSolver::gatherBlocks(const ConstraintRows& rows, std::span<const JointRowRange> ranges,
                                     std::span<const std::uint64_t> keys, RowSystem& system,
                                     std::span<const RigidBody> bodies) {
    const LcpProblem p = system.problem();
    const bool coupled = !p.findex.empty();
    const std::span<const Real> x = system.solution();
    const std::span<const LcpRowState> states = system.states();
    const std::size_t n = rows.size();
    rowFigure_.assign(n, -1);
    localRow_.assign(n, -1);
    between_.clear();
    for (Figure& f : figures_) {
        f.rows.clear();
        f.localRows.clear();
        f.keys.clear();
        f.responses.clear();
        f.islandB.clear();
        f.lo.clear();
        f.hi.clear();
        f.mu.clear();
        f.cfm.clear();
        f.x.clear();
        f.findex.clear();
        f.states.clear();
        f.failed = false;
    }
    for (std::size_t i = 0; i < n; ++i) {
        const ConstraintRow& r = rows[i];
        const int a = r.bodyA != kWorldBody ? figureOf_[static_cast<std::size_t>(r.bodyA)] : -1;
        const int b = r.bodyB != kWorldBody ? figureOf_[static_cast<std::size_t>(r.bodyB)] : -1;
        int f = a < 0 ? b : (b < 0 || b == a) ? a : -1;
        if (f >= 0 && r.frictionSource >= 0 && rowFigure_[static_cast<std::size_t>(r.frictionSource)] != f) f = -1;
        rowFigure_[i] = f;
        if (f < 0) {
            between_.push_back(i);
            continue;
        }
        Figure& figure = figures_[static_cast<std::size_t>(f)];
        localRow_[i] = static_cast<int>(figure.rows.size());
        figure.rows.push_back(i);
        ConstraintRow local = r;
        local.bodyA = localBody(r.bodyA, localOf_);
        local.bodyB = localBody(r.bodyB, localOf_);
        if (r.frictionSource >= 0) local.frictionSource = localRow_[static_cast<std::size_t>(r.frictionSource)];
        figure.localRows.add(local);
        figure.keys.push_back(keys[i]);
        figure.responses.push_back(system.response(i));
        figure.islandB.push_back(p.b[i]);
        figure.lo.push_back(p.lo[i]);
        figure.hi.push_back(p.hi[i]);
        figure.cfm.push_back(p.cfm.empty() ? Real(0) : p.cfm[i]);
        if (coupled) {
            figure.mu.push_back(p.mu[i]);
            figure.findex.push_back(p.findex[i] >= 0 ? localRow_[static_cast<std::size_t>(p.findex[i])] : -1);
        }
        figure.x.push_back(x[i]);
        figure.states.push_back(states[i]);
    }
    for (Figure& figure : figures_) {
        figure.ranges.clear();
        for (const int k : figure.joints) {
            JointRowRange range = ranges[static_cast<std::size_t>(k)];
            // The joint's rows are contiguous in the island's rows and all in this block.
            range.first = static_cast<int>(std::lower_bound(figure.rows.begin(), figure.rows.end(),
                                                            static_cast<std::size_t>(range.first)) -
                                           figure.rows.begin());
            figure.ranges.push_back(range);
        }
        figure.b.resize(figure.rows.size());
        figure.localBodies.clear();
        for (const int b : figure.bodies) figure.localBodies.push_back(bodies[static_cast<std::size_t>(b)]);
    }
}

BlockSolveResult FigureBlockSolver::solve(BlockProblem problem, const ConstraintRows& rows,
                                          std::span<const JointRowRange> ranges, std::span<const std::uint64_t> keys,
                                          RowSystem& system, std::span<const RigidBody> bodies,
                                          const SolverTuning& tuning, Real stopChange, WorkerPool* pool) {
    BlockSolveResult result;
    gatherBlocks(rows, ranges, keys, system, bodies);
    const std::size_t bodyCount = bodies.size();
    blockLinear_.assign(bodyCount, Vec3::Zero());
    blockAngular_.assign(bodyCount, Vec3::Zero());
    betweenLinear_.assign(bodyCount, Vec3::Zero());
    betweenAngular_.assign(bodyCount, Vec3::Zero());

    // Each figure's primary rows factorised, for the articulated responses of the rows between
    // figures (computed when a row first pushes); those rows start from their warm start,
    // clamped into their boxes.
    sweepFigures_.resize(figures_.size());
    std::iota(sweepFigures_.begin(), sweepFigures_.end(), std::size_t{0});
    forEachFigure(pool, sweepFigures_, [](Figure& figure) {
        if (!figure.treeReady) {
            figure.tree.setStructure(figure.localBodies, figure.localJoints);
            figure.treeReady = true;
        }
        figure.failedPivots = 0;
        figure.factored = false;
        figure.treeFallbacks = 0;
        figure.tree.factorPrimary(figure.localRows, figure.ranges, figure.localBodies);
    });
    const LcpProblem p = system.problem();
    const std::span<Real> x = system.solution();
    responseLinear_.clear();
    responseAngular_.clear();
    responses_.assign(between_.size(), BetweenResponse{});
    for (std::size_t k = 0; k < between_.size(); ++k) {
        const std::size_t i = between_[k];
        Real lo = 0;
        const Real hi = boundOf(p, x, i, lo);
        x[i] = std::clamp(x[i], lo, hi);
        if (x[i] != 0) pushBetween(k, rows, p, x[i]);
    }

    const int maxSweeps = std::max(1, tuning.blocks.maxSweeps);
    for (;;) {
        ++result.sweeps;
        // A block whose rows between figures did not change since its last solve keeps its answer.
        sweepFigures_.clear();
        for (std::size_t f = 0; f < figures_.size(); ++f)
            if (!figures_[f].rows.empty() && (result.sweeps == 1 || figures_[f].pushed)) sweepFigures_.push_back(f);
        forEachFigure(pool, sweepFigures_, [&](Figure& figure) {
            figure.failed = !solveBlock(problem, figure, rows, bodies, tuning);
            // A failed block is tried again in the next sweep, from the frozen answer's pattern.
            figure.pushed = figure.failed;
        });
        if (between_.empty() || result.sweeps >= maxSweeps) break;
        result.lastChange = relaxBetween(rows, system, x);
        if (result.lastChange <= stopChange) break;
    }

    // A block relaxed after its pivoting failed is answered by a fallback: the solve counts as failed.
    for (const Figure& figure : figures_) {
        if (figure.failed || !mayPivot(figure, tuning)) result.status = LcpStatus::NotConverged;
        result.treeFallbacks += figure.treeFallbacks;
    }

    // The primary rows' share of the impulses between figures (their responses held the joints
    // through it) joins the blocks' answers: the island applies M⁻¹Jᵀλ of every row.
    impulseLinear_.assign(bodyCount, Vec3::Zero());
    impulseAngular_.assign(bodyCount, Vec3::Zero());
    for (const std::size_t i : between_) {
        const ConstraintRow& r = rows[i];
        if (x[i] == 0) continue;
        if (r.bodyA != kWorldBody) {
            impulseLinear_[static_cast<std::size_t>(r.bodyA)] += x[i] * r.linearA;
            impulseAngular_[static_cast<std::size_t>(r.bodyA)] += x[i] * r.angularA;
        }
        if (r.bodyB != kWorldBody) {
            impulseLinear_[static_cast<std::size_t>(r.bodyB)] += x[i] * r.linearB;
            impulseAngular_[static_cast<std::size_t>(r.bodyB)] += x[i] * r.angularB;
        }
    }
    for (Figure& figure : figures_) {
        figure.linearChange.resize(figure.bodies.size());
        figure.angularChange.resize(figure.bodies.size());
        for (std::size_t l = 0; l < figure.bodies.size(); ++l) {
            figure.linearChange[l] = impulseLinear_[static_cast<std::size_t>(figure.bodies[l])];
            figure.angularChange[l] = impulseAngular_[static_cast<std::size_t>(figure.bodies[l])];
        }
        figure.tree.addPrimaryImpulses(figure.linearChange, figure.angularChange, figure.x);
        for (std::size_t k = 0; k < figure.rows.size(); ++k) x[figure.rows[k]] = figure.x[k];
    }
    for (const std::size_t i : between_) {
        Real lo = 0;
        const Real hi = boundOf(p, x, i, lo);
        const ConstraintRow& r = rows[i];
        const Real w = rowAlong(r, blockLinear_, blockAngular_) + rowAlong(r, betweenLinear_, betweenAngular_) +
                       (p.cfm.empty() ? Real(0) : p.cfm[i]) * x[i] - p.b[i];
        result.residual = std::max(result.residual, std::abs(x[i] - std::clamp(x[i] - w, lo, hi)));
    }
    statesFromImpulses(rows, x, system.states(), tuning.exact.tolerance);
    return result;
}

// Runs task on each figure of `which`, on the pool's threads when there is one: a share of the
// figures a thread, not a figure a task (a block's solve takes a few microseconds, and a
// figure's data then stays with one thread through the sweeps while its share is unchanged).
void FigureBlockSolver::forEachFigure(WorkerPool* pool, std::span<const std::size_t> which,
                                      const std::function<void(Figure&)>& task) {
    if (pool && which.size() > 1) {
        const std::size_t parts = std::min<std::size_t>(which.size(), static_cast<std::size_t>(pool->threads()));
        pool->run(parts, [&](std::size_t part) {
            for (std::size_t k = part; k < which.size(); k += parts) task(figures_[which[k]]);
        });
        return;
    }
    for (const std::size_t f : which) task(figures_[f]);
}

// The block of one figure with the impulses between figures as given: its b less what they
// change of its rows' velocities (or errors). The sparse path first, as for a figure alone,
// then the tree solver, then the dense one; false when none solves it (solveDense's fallback
// answer stands). Once its failed pivoting in this solve has spent the block's pivot budget,
// the later sweeps go straight to the tree with its auxiliary rows relaxed
// (TreeSolver::setPivoting): the joints stay exact, and the block costs sweeps of its Schur
// complement instead of thousands of pivots again.
bool FigureBlockSolver::solveBlock(BlockProblem problem, Figure& figure, const ConstraintRows& rows,
                                   std::span<const RigidBody> bodies, const SolverTuning& tuning) {
    const std::size_t n = figure.rows.size();
    for (std::size_t k = 0; k < n; ++k)
        figure.b[k] = figure.islandB[k] - rowAlong(rows[figure.rows[k]], betweenLinear_, betweenAngular_);
    figure.lastX.assign(figure.x.begin(), figure.x.end());
    if (mayPivot(figure, tuning)) {
        const LcpProblem p{static_cast<int>(n), {}, figure.b, figure.lo, figure.hi, figure.findex, figure.mu, figure.cfm};
        const SparseLcpResult sparse = figure.sparse.solve(figure.localRows.all(), figure.responses, p,
                                                           figure.localBodies, figure.x, figure.states, tuning.exact);
        if (sparse.status == LcpStatus::Solved) {
            const std::span<const Vec3> linear = figure.sparse.answerLinearChange();
            const std::span<const Vec3> angular = figure.sparse.answerAngularChange();
            for (std::size_t l = 0; l < figure.bodies.size(); ++l) {
                blockLinear_[static_cast<std::size_t>(figure.bodies[l])] = linear[l];
                blockAngular_[static_cast<std::size_t>(figure.bodies[l])] = angular[l];
            }
            return true;
        }
        ++figure.treeFallbacks;
    }

    TreeSolveResult tree = solveByTree(problem, figure, bodies, tuning);
    if (tree.status != LcpStatus::Solved) figure.failedPivots += tree.pivots;
    // As for a figure alone (Island::solveWithTree): a large block keeps the tree's frozen-box
    // answer rather than pivoting over all its rows.
    if (tree.status == LcpStatus::Solved || (tree.frozenAnswer && n > tuning.denseRescueRows)) {
        const std::span<const Real> lambda = figure.tree.impulses();
        std::copy(lambda.begin(), lambda.end(), figure.x.begin());
    } else {
        const LcpResult dense = solveDense(figure, tuning);
        tree.status = dense.status;
        if (dense.status != LcpStatus::Solved) figure.failedPivots += dense.pivots;
    }
    statesFromImpulses(figure.localRows, figure.x, figure.states, tuning.exact.tolerance);
    figure.linearChange.assign(figure.bodies.size(), Vec3::Zero());
    figure.angularChange.assign(figure.bodies.size(), Vec3::Zero());
    accumulateResponses(figure.localRows.all(), figure.responses, figure.x, figure.linearChange, figure.angularChange);
    for (std::size_t l = 0; l < figure.bodies.size(); ++l) {
        blockLinear_[static_cast<std::size_t>(figure.bodies[l])] = figure.linearChange[l];
        blockAngular_[static_cast<std::size_t>(figure.bodies[l])] = figure.angularChange[l];
    }
    return tree.status == LcpStatus::Solved;
}

// The block by the tree solver, from the block's last answer. The tree reads b from the
// bodies' velocities (target − Cdot) or from the rows' errors (−error): those are set to what
// the rows between figures make of them.
TreeSolveResult FigureBlockSolver::solveByTree(BlockProblem problem, Figure& figure, std::span<const RigidBody> bodies,
                                               const SolverTuning& tuning) {
    if (!figure.treeReady) {
        figure.tree.setStructure(figure.localBodies, figure.localJoints);
        figure.treeReady = true;
    }
    LcpPgsSettings pgs = tuning.pgs;
    pgs.maxIterations = tuning.blocks.relaxedSweeps;
    figure.tree.setPivotRowLimit(pivotRowLimit_, pgs);
    figure.tree.setPivoting(mayPivot(figure, tuning));
    std::copy(figure.lastX.begin(), figure.lastX.end(), figure.x.begin());
    if (problem == BlockProblem::Velocity) {
        for (std::size_t l = 0; l < figure.bodies.size(); ++l) {
            const std::size_t b = static_cast<std::size_t>(figure.bodies[l]);
            figure.localBodies[l].linearVelocity = bodies[b].linearVelocity + betweenLinear_[b];
            figure.localBodies[l].angularVelocity = bodies[b].angularVelocity + betweenAngular_[b];
        }
        if (!figure.factored)
            figure.tree.factor(figure.localRows, figure.ranges, figure.localBodies, TreeProblems::VelocityAndPosition,
                               figure.keys);
        figure.factored = true;
        statesFromImpulses(figure.localRows, figure.x, figure.states, tuning.exact.tolerance);
        return figure.tree.solveVelocity(figure.localRows, figure.localBodies, figure.states, figure.x);
    }
    for (std::size_t k = 0; k < figure.rows.size(); ++k)
        figure.localRows[k].error = -figure.b[k];
    if (!figure.factored)
        figure.tree.factor(figure.localRows, figure.ranges, figure.localBodies, TreeProblems::PositionOnly, figure.keys);
    figure.factored = true;
    return figure.tree.solvePositionImpulses(figure.localRows);
}

// Whether the block's failed pivoting in this solve is still within its budget.
bool FigureBlockSolver::mayPivot(const Figure& figure, const SolverTuning& tuning) const {
    return figure.failedPivots < static_cast<long>(tuning.blocks.pivotsPerRow) * static_cast<long>(figure.rows.size());
}

// A block neither the sparse path nor the tree solved goes to the dense pivoting solve, as a
// figure alone does (Island::solveVelocities); if that fails too, never its answer: the
// frozen-box answer (frozen_boxes.h), PGS started from the block's last answer. Returns the
// dense solve's result.
LcpResult FigureBlockSolver::solveDense(Figure& figure, const SolverTuning& tuning) {
    std::copy(figure.lastX.begin(), figure.lastX.end(), figure.x.begin());
    figure.system.build(figure.localRows, figure.localBodies);
    LcpProblem problem = figure.system.problem();
    problem.b = figure.b;
    problem.lo = figure.lo;
    problem.hi = figure.hi;
    problem.findex = figure.findex;
    problem.mu = figure.mu;
    problem.cfm = figure.cfm;
    figure.exact.setSettings(tuning.exact);
    const LcpResult result = figure.exact.solve(problem, figure.x, figure.states);
    if (result.status == LcpStatus::Solved) return result;
    std::copy(figure.lastX.begin(), figure.lastX.end(), figure.x.begin());
    figure.pgs.setSettings(tuning.pgs);
    figure.frozenBoxes.solve(problem, figure.x, figure.states, figure.exact, figure.pgs);
    return result;
}

// One Gauss–Seidel sweep over the rows between figures, with the blocks' velocity changes as
// they are; returns the largest change of an impulse. A row at 0 that its box keeps there
// (a contact apart, a friction row of a normal that does not push) is passed over without its
// response: most rows between the figures of a pile are speculative contacts apart.
Real FigureBlockSolver::relaxBetween(const ConstraintRows& rows, const RowSystem& system, std::span<Real> x) {
    const LcpProblem p = system.problem();
    Real largest = 0;
    for (std::size_t k = 0; k < between_.size(); ++k) {
        const std::size_t i = between_[k];
        const ConstraintRow& r = rows[i];
        Real lo = 0;
        const Real hi = boundOf(p, x, i, lo);
        const Real w = rowAlong(r, blockLinear_, blockAngular_) + rowAlong(r, betweenLinear_, betweenAngular_) +
                       (p.cfm.empty() ? Real(0) : p.cfm[i]) * x[i] - p.b[i];
        if (x[i] == 0 && (lo == hi || (lo == 0 && w >= 0))) continue;
        const Real invDiagonal = respond(k, rows, p);
        const Real next = std::clamp(x[i] - w * invDiagonal, lo, hi);
        const Real change = next - x[i];
        if (change == 0) continue;
        x[i] = next;
        largest = std::max(largest, std::abs(change) / invDiagonal);
        pushBetween(k, rows, p, change);
    }
    return largest;
}

// The articulated response of between-row k (each side through its figure's primary rows, so
// that an impulse moves the whole figure as its joints let it), computed once per solve; returns
// 1 / (J H⁻¹ Jᵀ + cfm), 0 for a row no impulse can move.
Real FigureBlockSolver::respond(std::size_t k, const ConstraintRows& rows, const LcpProblem& p) {
    BetweenResponse& response = responses_[k];
    if (response.known) return response.invDiagonal;
    const std::size_t i = between_[k];
    const ConstraintRow& r = rows[i];
    Real diagonal = p.cfm.empty() ? Real(0) : p.cfm[i];
    const auto side = [&](int body, const Vec3& linear, const Vec3& angular, int& offset) {
        if (body == kWorldBody) return;
        Figure& figure = figures_[static_cast<std::size_t>(figureOf_[static_cast<std::size_t>(body)])];
        const std::size_t count = figure.bodies.size();
        offset = static_cast<int>(responseLinear_.size());
        responseLinear_.resize(responseLinear_.size() + count);
        responseAngular_.resize(responseAngular_.size() + count);
        const std::span<Vec3> outLinear = std::span(responseLinear_).subspan(static_cast<std::size_t>(offset), count);
        const std::span<Vec3> outAngular = std::span(responseAngular_).subspan(static_cast<std::size_t>(offset), count);
        figure.tree.primaryResponse(localOf_[static_cast<std::size_t>(body)], linear, angular, outLinear, outAngular);
    };
    side(r.bodyA, r.linearA, r.angularA, response.offsetA);
    side(r.bodyB, r.linearB, r.angularB, response.offsetB);
    // J H⁻¹ Jᵀ: the row's velocity per unit impulse, through both responses (a row with both
    // bodies in one figure, boxed by a row between figures, sees each side's response at both).
    const auto velocityAt = [&](int body, const Vec3& linear, const Vec3& angular) {
        if (body == kWorldBody) return Real(0);
        Real v = 0;
        const int figure = figureOf_[static_cast<std::size_t>(body)];
        const std::size_t local = static_cast<std::size_t>(localOf_[static_cast<std::size_t>(body)]);
        for (const auto& [from, offset] : {std::pair{r.bodyA, response.offsetA}, std::pair{r.bodyB, response.offsetB}}) {
            if (from == kWorldBody || figureOf_[static_cast<std::size_t>(from)] != figure) continue;
            v += linear.dot(responseLinear_[static_cast<std::size_t>(offset) + local]) +
                 angular.dot(responseAngular_[static_cast<std::size_t>(offset) + local]);
        }
        return v;
    };
    diagonal += velocityAt(r.bodyA, r.linearA, r.angularA) + velocityAt(r.bodyB, r.linearB, r.angularB);
    response.invDiagonal = diagonal > 0 ? 1 / diagonal : 0;
    response.known = true;
    return response.invDiagonal;
}

// Adds `impulse` along between-row k to the velocity changes of every body of its figures.
void FigureBlockSolver::pushBetween(std::size_t k, const ConstraintRows& rows, const LcpProblem& p, Real impulse) {
    respond(k, rows, p);
    const BetweenResponse& response = responses_[k];
    const ConstraintRow& r = rows[between_[k]];
    for (const auto& [body, offset] : {std::pair{r.bodyA, response.offsetA}, std::pair{r.bodyB, response.offsetB}}) {
        if (body == kWorldBody) continue;
        Figure& figure = figures_[static_cast<std::size_t>(figureOf_[static_cast<std::size_t>(body)])];
        figure.pushed = true;
        const Vec3* linear = responseLinear_.data() + offset;
        const Vec3* angular = responseAngular_.data() + offset;
        for (std::size_t l = 0; l < figure.bodies.size(); ++l) {
            const std::size_t b = static_cast<std::size_t>(figure.bodies[l]);
            betweenLinear_[b] += impulse * linear[l];
            betweenAngular_[b] += impulse * angular[l];
        }
    }
}

// Row i's upper bound, and its lower one in lo: a friction row's box from its source's impulse.
Real FigureBlockSolver::boundOf(const LcpProblem& p, std::span<const Real> x, std::size_t i, Real& lo) const {
    if (!p.findex.empty() && p.findex[i] >= 0) {
        const Real box = p.mu[i] * std::abs(x[static_cast<std::size_t>(p.findex[i])]);
        lo = -box;
        return box;
    }
    lo = p.lo[i];
    return p.hi[i];
}

}  // namespace af
