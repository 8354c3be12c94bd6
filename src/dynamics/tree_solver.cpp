// The tree solver's steps: which rows are primary, the two problems (velocity, position) on one
// factorisation, the auxiliary LCP warm-started by row identity, and the primary impulses.

#include "tree_solver.h"

#include "frozen_boxes.h"
#include "row_system.h"
#include "tree_internal.h"

#include <algorithm>
#include <stdexcept>

namespace af {

using namespace tree_detail;

namespace {

constexpr int kPrimary = -1;
constexpr int kLeftOut = -2;  // a friction row, in a factorisation for the position problem only

// A row's identity from step to step, unless the caller names the rows: joint k's row q of a
// kind, or the q-th row after the joints' rows.
enum class RowKind : std::uint64_t { Equality = 0, Limit = 1, Friction = 2, Other = 3 };

std::uint64_t rowKey(std::uint64_t group, RowKind kind, std::uint64_t offset) {
    return (group << 24) | (static_cast<std::uint64_t>(kind) << 20) | offset;
}

}  // namespace

// What the last solve of one problem ended with, to warm-start the next: one entry per
// auxiliary row, sorted by key. (Named, not anonymous: Impl's members are of these types.)
namespace tree_detail {

struct WarmEntry {
    std::uint64_t key;
    int bodyA, bodyB;
    LcpRowState state;
    Real impulse;  // the guess of a coupled problem's friction boxes (lcp.h)
    bool operator<(const WarmEntry& o) const { return key < o.key; }
};

struct WarmStart {
    std::vector<WarmEntry> entries;
};

}  // namespace tree_detail

struct TreeSolver::Impl {
    LcpExactSolver lcp;
    // A coupled friction problem the pivoting solve does not settle gets the frozen-box answer.
    LcpPgsSolver pgs;
    FrozenBoxFallback frozenBoxes;
    std::size_t pivotRowLimit = 0;  // beyond it, the auxiliary LCP by iterativePgs
    bool pivoting = true;           // false: every auxiliary LCP by iterativePgs
    LcpPgsSolver iterativePgs;
    Forest forest;
    TreeFactor tree;
    Auxiliary aux;
    bool valid = false;         // the last factor() matched the structure
    bool auxiliaryBuilt = false;  // by factor(), not factorPrimary()
    bool withFriction = true;  // the last factor() kept the friction rows

    // Per row of the last factor().
    std::vector<int> auxIndex;  // index among the auxiliary rows, kPrimary, or kLeftOut (λ = 0)
    std::vector<std::uint64_t> key;
    std::vector<std::uint8_t> friction;  // a joint friction or coupled row: 0 in the position problem
    // Per auxiliary row.
    std::vector<int> auxRows;
    // Per node: the rows of a joint node.
    std::vector<int> nodeFirst, nodeRows;

    // Workspace of a solve.
    std::vector<Real> b, bAux, rhs, lo, hi, mu, cfm, x, xStart, lambda;
    std::vector<int> findex;
    std::vector<LcpRowState> states;
    std::vector<Vec6> z, solution, bodyImpulse;
    WarmStart velocityStart, positionStart;

    void classify(const ConstraintRows& rows, std::span<const JointRowRange> ranges,
                  std::span<const std::uint64_t> rowKeys);
    // guessStates and guessImpulses (one per row, or empty) start the auxiliary LCP instead of
    // `start`, which is updated either way.
    // sumPerBody: Σ Jᵀλ per body for applyImpulses and applyDisplacements.
    TreeSolveResult solve(const ConstraintRows& rows, WarmStart& start, bool position, bool sumPerBody,
                          std::span<const LcpRowState> guessStates = {}, std::span<const Real> guessImpulses = {});
    bool setBounds(const ConstraintRows& rows, bool position);
    void warmStates(const ConstraintRows& rows, const WarmStart& start);
    void remember(const ConstraintRows& rows, WarmStart& start) const;
    void solvePrimary();
    void primaryRhs();
    void solveIteratively(const LcpProblem& problem, TreeSolveResult& result);
    TreeSolveResult finish(const ConstraintRows& rows, bool sumPerBody, TreeSolveResult result);
    void accumulateImpulses(const ConstraintRows& rows);
};

TreeSolver::TreeSolver(const LcpExactSettings& settings) : impl_(std::make_unique<Impl>()) {
    impl_->lcp.setSettings(settings);
}
TreeSolver::~TreeSolver() = default;
TreeSolver::TreeSolver(TreeSolver&&) noexcept = default;
TreeSolver& TreeSolver::operator=(TreeSolver&&) noexcept = default;

void TreeSolver::setSettings(const LcpExactSettings& settings) { impl_->lcp.setSettings(settings); }

void TreeSolver::setPivotRowLimit(std::size_t rows, const LcpPgsSettings& pgs) {
    impl_->pivotRowLimit = rows;
    impl_->iterativePgs.setSettings(pgs);
}

void TreeSolver::setPivoting(bool allowed) { impl_->pivoting = allowed; }

void TreeSolver::setStructure(std::span<const RigidBody> bodies, std::span<const Joint> joints) {
    impl_->forest = buildForest(bodies, joints);
    impl_->aux.forgetPaths();
    impl_->valid = false;
    resetWarmStart();
}

void TreeSolver::resetWarmStart() {
    impl_->velocityStart.entries.clear();
    impl_->positionStart.entries.clear();
}

bool TreeSolver::isPrimary(int joint) const {
    const std::vector<std::uint8_t>& primary = impl_->forest.primary;
    return joint >= 0 && static_cast<std::size_t>(joint) < primary.size() && primary[static_cast<std::size_t>(joint)];
}

void TreeSolver::Impl::classify(const ConstraintRows& rows, std::span<const JointRowRange> ranges,
                                std::span<const std::uint64_t> rowKeys) {
    const std::size_t n = rows.size();
    constexpr int kUnset = -3;
    const bool named = rowKeys.size() == n;
    auxIndex.assign(n, kUnset);
    if (named) {
        key.assign(rowKeys.begin(), rowKeys.end());
    } else {
        key.resize(n);
    }
    friction.assign(n, 0);
    nodeFirst.assign(forest.nodes.size(), 0);
    nodeRows.assign(forest.nodes.size(), 0);
    for (std::size_t j = 0; j < ranges.size(); ++j) {
        const JointRowRange& range = ranges[j];
        const int node = forest.nodeOfJoint[j];
        if (node >= 0) {
            nodeFirst[static_cast<std::size_t>(node)] = range.first;
            nodeRows[static_cast<std::size_t>(node)] = range.equalityRows;
        }
        const int counts[3] = {range.equalityRows, range.limitRows, range.frictionRows};
        int row = range.first;
        for (int kind = 0; kind < 3; ++kind)
            for (int q = 0; q < counts[kind]; ++q, ++row) {
                const std::size_t r = static_cast<std::size_t>(row);
                if (r >= n) {
                    valid = false;
                    return;
                }
                if (!named) key[r] = rowKey(j, static_cast<RowKind>(kind), static_cast<std::uint64_t>(q));
                friction[r] = kind == 2;
                auxIndex[r] = kind == 0 && node >= 0 ? kPrimary : 0;
            }
    }
    std::uint64_t others = 0;
    auxRows.clear();
    for (std::size_t r = 0; r < n; ++r) {
        if (auxIndex[r] == kUnset && !named) key[r] = rowKey(ranges.size(), RowKind::Other, others++);
        if (rows[r].frictionSource >= 0) friction[r] = 1;
        if (auxIndex[r] == kPrimary) continue;
        if (!withFriction && (friction[r] || (rows[r].lo == 0 && rows[r].hi == 0))) {
            auxIndex[r] = kLeftOut;
            continue;
        }
        auxIndex[r] = static_cast<int>(auxRows.size());
        auxRows.push_back(static_cast<int>(r));
    }
}

void TreeSolver::factor(const ConstraintRows& rows, std::span<const JointRowRange> ranges,
                        std::span<const RigidBody> bodies, TreeProblems problems,
                        std::span<const std::uint64_t> rowKeys) {
    Impl& s = *impl_;
    s.withFriction = problems == TreeProblems::VelocityAndPosition;
    s.valid = s.tree.factor(s.forest, rows, ranges, bodies);
    if (!s.valid) return;
    s.classify(rows, ranges, rowKeys);
    if (!s.valid) return;
    s.aux.build(s.tree, s.forest, rows, s.auxRows);
    s.lcp.reserve(static_cast<int>(s.auxRows.size()));
    s.auxiliaryBuilt = true;
}

void TreeSolver::factorPrimary(const ConstraintRows& rows, std::span<const JointRowRange> ranges,
                               std::span<const RigidBody> bodies) {
    Impl& s = *impl_;
    s.auxiliaryBuilt = false;
    s.withFriction = true;
    s.valid = s.tree.factor(s.forest, rows, ranges, bodies);
    if (s.valid) s.classify(rows, ranges, {});
}

bool TreeSolver::primaryResponse(int body, const Vec3& linear, const Vec3& angular, std::span<Vec3> linearOut,
                                 std::span<Vec3> angularOut) {
    Impl& s = *impl_;
    if (!s.valid) return false;
    const std::vector<int>& nodeOf = s.forest.nodeOfBody;
    s.z.assign(s.forest.nodes.size(), Vec6::Zero());
    const int node = nodeOf[static_cast<std::size_t>(body)];
    if (node >= 0) {
        s.z[static_cast<std::size_t>(node)].head<3>() = linear;
        s.z[static_cast<std::size_t>(node)].tail<3>() = angular;
    }
    s.solvePrimary();
    for (std::size_t b = 0; b < nodeOf.size(); ++b) {
        const int n = nodeOf[b];
        linearOut[b] = n >= 0 ? Vec3(s.solution[static_cast<std::size_t>(n)].head<3>()) : Vec3::Zero();
        angularOut[b] = n >= 0 ? Vec3(s.solution[static_cast<std::size_t>(n)].tail<3>()) : Vec3::Zero();
    }
    return true;
}

void TreeSolver::addPrimaryImpulses(std::span<const Vec3> linear, std::span<const Vec3> angular,
                                    std::span<Real> rowImpulses) {
    Impl& s = *impl_;
    if (!s.valid) return;
    const std::vector<int>& nodeOf = s.forest.nodeOfBody;
    const std::size_t nodes = s.forest.nodes.size();
    s.z.assign(nodes, Vec6::Zero());
    for (std::size_t b = 0; b < nodeOf.size(); ++b) {
        const int n = nodeOf[b];
        if (n < 0) continue;
        s.z[static_cast<std::size_t>(n)].head<3>() = linear[b];
        s.z[static_cast<std::size_t>(n)].tail<3>() = angular[b];
    }
    s.solvePrimary();
    for (std::size_t i = 0; i < nodes; ++i)
        for (int q = 0; q < s.nodeRows[i]; ++q)
            rowImpulses[static_cast<std::size_t>(s.nodeFirst[i] + q)] -= s.solution[i](q);
}

TreeSolveResult TreeSolver::solveVelocity(const ConstraintRows& rows, std::span<const RigidBody> bodies) {
    Impl& s = *impl_;
    s.b.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) s.b[i] = rows[i].target - rowVelocity(rows[i], bodies);
    return s.solve(rows, s.velocityStart, false, true);
}

TreeSolveResult TreeSolver::solveVelocity(const ConstraintRows& rows, std::span<const RigidBody> bodies,
                                          std::span<const LcpRowState> guessStates, std::span<const Real> guessImpulses) {
    if (guessStates.size() != rows.size() || guessImpulses.size() != rows.size())
        throw std::invalid_argument("TreeSolver::solveVelocity: one guess per row");
    Impl& s = *impl_;
    s.b.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) s.b[i] = rows[i].target - rowVelocity(rows[i], bodies);
    return s.solve(rows, s.velocityStart, false, true, guessStates, guessImpulses);
}

TreeSolveResult TreeSolver::solvePosition(const ConstraintRows& rows) {
    Impl& s = *impl_;
    s.b.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) s.b[i] = -rows[i].error;
    return s.solve(rows, s.positionStart, true, true);
}

TreeSolveResult TreeSolver::solvePositionImpulses(const ConstraintRows& rows) {
    Impl& s = *impl_;
    s.b.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) s.b[i] = -rows[i].error;
    return s.solve(rows, s.positionStart, true, false);
}

// Takes each auxiliary row's state from the last solve's row with the same identity and bodies.
void TreeSolver::Impl::warmStates(const ConstraintRows& rows, const WarmStart& start) {
    for (std::size_t k = 0; k < auxRows.size(); ++k) {
        const std::size_t r = static_cast<std::size_t>(auxRows[k]);
        const auto at = std::lower_bound(start.entries.begin(), start.entries.end(),
                                         WarmEntry{key[r], 0, 0, LcpRowState::Unknown, 0});
        const bool same = at != start.entries.end() && at->key == key[r] && at->bodyA == rows[r].bodyA &&
                          at->bodyB == rows[r].bodyB;
        states[k] = same ? at->state : LcpRowState::Unknown;
        x[k] = same ? at->impulse : 0;
    }
}

void TreeSolver::Impl::remember(const ConstraintRows& rows, WarmStart& start) const {
    start.entries.clear();
    for (std::size_t k = 0; k < auxRows.size(); ++k) {
        const std::size_t r = static_cast<std::size_t>(auxRows[k]);
        start.entries.push_back({key[r], rows[r].bodyA, rows[r].bodyB, states[k], x[k]});
    }
    std::sort(start.entries.begin(), start.entries.end());
}

// Bounds and friction coupling of the auxiliary LCP; false for a box on a primary row
// (docs/doom-physics.md §4.5: a fatal error in Doom).
bool TreeSolver::Impl::setBounds(const ConstraintRows& rows, bool position) {
    const std::size_t n = auxRows.size();
    lo.resize(n);
    hi.resize(n);
    mu.resize(n);
    cfm.resize(n);
    findex.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t r = static_cast<std::size_t>(auxRows[k]);
        const ConstraintRow& row = rows[r];
        cfm[k] = row.cfm;
        lo[k] = row.lo;
        hi[k] = row.hi;
        mu[k] = row.frictionCoefficient;
        findex[k] = -1;
        if (position && friction[r]) {
            lo[k] = hi[k] = 0;
        } else if (row.frictionSource >= 0) {
            const std::size_t source = static_cast<std::size_t>(row.frictionSource);
            if (source >= rows.size() || auxIndex[source] < 0) return false;
            findex[k] = auxIndex[source];
        }
    }
    return true;
}

// solution = H⁻¹ z with z = [Σ λ_k e_k; b_P] on input (z is overwritten).
void TreeSolver::Impl::solvePrimary() {
    tree.forward(z);
    solution.resize(z.size());
    tree.backward(z, solution);
}

TreeSolveResult TreeSolver::Impl::solve(const ConstraintRows& rows, WarmStart& start, bool position, bool sumPerBody,
                                        std::span<const LcpRowState> guessStates, std::span<const Real> guessImpulses) {
    TreeSolveResult result;
    lambda.assign(rows.size(), 0);
    bodyImpulse.assign(sumPerBody ? forest.nodeOfBody.size() : 0, Vec6::Zero());
    if (!valid || !auxiliaryBuilt || rows.size() != auxIndex.size() || (!position && !withFriction) || !setBounds(rows, position)) {
        result.status = LcpStatus::InvalidInput;
        return result;
    }
    const std::size_t n = auxRows.size();
    result.auxiliaryRows = static_cast<int>(n);
    result.primaryRows = static_cast<int>(std::count(auxIndex.begin(), auxIndex.end(), kPrimary));

    // What the primary rows alone do, x0 = H⁻¹ [0; b_P]; the auxiliary rows get what is left.
    primaryRhs();
    solvePrimary();
    bAux.resize(n);
    for (std::size_t k = 0; k < n; ++k) bAux[k] = b[static_cast<std::size_t>(auxRows[k])];
    rhs.resize(n);
    aux.reduce(solution, bAux, rhs);

    x.assign(n, 0);
    states.resize(n);
    if (n > 0) {
        if (guessStates.empty()) {
            warmStates(rows, start);
        } else {
            for (std::size_t k = 0; k < n; ++k) {
                const std::size_t r = static_cast<std::size_t>(auxRows[k]);
                states[k] = guessStates[r];
                x[k] = guessImpulses[r];
            }
        }
        LcpProblem problem;
        problem.size = static_cast<int>(n);
        problem.a = aux.schur();
        problem.b = rhs;
        problem.lo = lo;
        problem.hi = hi;
        if (std::any_of(findex.begin(), findex.end(), [](int f) { return f >= 0; })) {
            problem.findex = findex;
            problem.mu = mu;
        }
        problem.cfm = cfm;
        const bool coupled = !problem.findex.empty();
        if (!pivoting || (pivotRowLimit > 0 && n > pivotRowLimit)) {
            solveIteratively(problem, result);
            remember(rows, start);
            return finish(rows, sumPerBody, result);
        }
        if (coupled) xStart.assign(x.begin(), x.end());
        const LcpResult r = lcp.solve(problem, x, states);
        result.status = r.status;
        result.pivots = r.pivots;
        result.couplingPasses = r.couplingPasses;
        result.residual = r.residual;
        if (r.status == LcpStatus::NotConverged && coupled) {
            // Never the failed solve's impulses: the frozen-box answer from the same start.
            std::copy(xStart.begin(), xStart.end(), x.begin());
            frozenBoxes.solve(problem, x, states, lcp, pgs);
            result.frozenAnswer = true;
        }
        remember(rows, start);
    }
    return finish(rows, sumPerBody, result);
}

// z = [0; b_P] per node, the right-hand side of the primary rows.
void TreeSolver::Impl::primaryRhs() {
    z.assign(forest.nodes.size(), Vec6::Zero());
    for (std::size_t i = 0; i < z.size(); ++i)
        for (int q = 0; q < nodeRows[i]; ++q) z[i](q) = b[static_cast<std::size_t>(nodeFirst[i] + q)];
}

// The auxiliary LCP beyond the pivot row limit: projected Gauss–Seidel on the Schur complement
// from the warm start in x, and row states from its answer for the next warm start. Running
// out of sweeps is its way of stopping, not a failure.
void TreeSolver::Impl::solveIteratively(const LcpProblem& problem, TreeSolveResult& result) {
    const LcpPgsResult r = iterativePgs.solve(problem, x);
    result.status = r.status == LcpStatus::InvalidInput ? r.status : LcpStatus::Solved;
    result.iterative = true;
    result.residual = r.residual;
    statesFromImpulses(problem, x, states, lcp.settings().tolerance);
}

// The primary rows' impulses for the auxiliary ones in x, and every row's λ.
TreeSolveResult TreeSolver::Impl::finish(const ConstraintRows& rows, bool sumPerBody, TreeSolveResult result) {
    const std::size_t n = auxRows.size();
    const std::size_t nodes = forest.nodes.size();
    if (tree.singularBlocks() > 0 && result.status == LcpStatus::Solved) result.status = LcpStatus::Unsatisfiable;

    // The primary impulses with the auxiliary ones applied: [y; μ] = H⁻¹ [Σ λ_k e_k; b_P], λ_P = −μ.
    primaryRhs();
    aux.inject(x, z);
    solvePrimary();
    for (std::size_t i = 0; i < nodes; ++i)
        for (int q = 0; q < nodeRows[i]; ++q) lambda[static_cast<std::size_t>(nodeFirst[i] + q)] = -solution[i](q);
    for (std::size_t k = 0; k < n; ++k) lambda[static_cast<std::size_t>(auxRows[k])] = x[k];
    if (sumPerBody) accumulateImpulses(rows);
    return result;
}

// Σ Jᵀλ per body, for applyImpulses and applyDisplacements.
void TreeSolver::Impl::accumulateImpulses(const ConstraintRows& rows) {
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const ConstraintRow& row = rows[r];
        const Real l = lambda[r];
        if (l == 0) continue;
        if (row.bodyA != kWorldBody) {
            Vec6& impulse = bodyImpulse[static_cast<std::size_t>(row.bodyA)];
            impulse.head<3>() += l * row.linearA;
            impulse.tail<3>() += l * row.angularA;
        }
        if (row.bodyB != kWorldBody) {
            Vec6& impulse = bodyImpulse[static_cast<std::size_t>(row.bodyB)];
            impulse.head<3>() += l * row.linearB;
            impulse.tail<3>() += l * row.angularB;
        }
    }
}

std::span<const Real> TreeSolver::impulses() const { return impl_->lambda; }

void TreeSolver::applyImpulses(std::span<RigidBody> bodies) const {
    const std::vector<Vec6>& impulse = impl_->bodyImpulse;
    for (std::size_t k = 0; k < bodies.size() && k < impulse.size(); ++k) {
        RigidBody& body = bodies[k];
        body.linearVelocity += body.inverseMass * impulse[k].head<3>();
        body.angularVelocity += body.inverseInertiaWorld() * impulse[k].tail<3>();
    }
}

void TreeSolver::applyDisplacements(std::span<RigidBody> bodies) const {
    const std::vector<Vec6>& impulse = impl_->bodyImpulse;
    for (std::size_t k = 0; k < bodies.size() && k < impulse.size(); ++k) {
        RigidBody& body = bodies[k];
        displaceBody(body, body.inverseMass * impulse[k].head<3>(), body.inverseInertiaWorld() * impulse[k].tail<3>());
    }
}

}  // namespace af
