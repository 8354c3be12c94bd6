// One step of the world; see world.h for the order of its parts and why.

#include "world_state.h"

#include <algorithm>

namespace af {

namespace {

constexpr Real kShakeTrust = 2;         // a SHAKE move may be at most this many times its drift
constexpr Real kShakeTolerance = 1e-9;  // length units: drift this small counts as closed
constexpr Real kPenetrationTolerance = 1e-3;  // units beyond the contact slop worth another projection
constexpr int kProjectionHalvings = 4;        // see projectPositions
constexpr int kBoxPasses = 8;                 // see solveByBoxIteration
constexpr Real kBoxTolerance = 1e-9;          // relative change of a friction box that counts as none

// Row keys of joints (see warm_start.h): the joint's number and the row's place in it. Contact
// keys are hashes (contact_set.cpp) and rows of the extra source are keyed by their order.
constexpr std::uint64_t kJointKeyTag = 0x4a4full << 48;
constexpr std::uint64_t kExtraKeyTag = 0x4558ull << 48;

}  // namespace

void World::step() {
    State& s = *state_;
    s.report = {};
    s.startLinear.resize(s.bodies.size());
    s.startAngular.resize(s.bodies.size());
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
        s.startLinear[i] = s.bodies[i].linearVelocity;
        s.startAngular[i] = s.bodies[i].angularVelocity;
    }
    const int substeps = std::max(1, s.settings.substeps);
    const Real dt = s.settings.timeStep / substeps;
    for (int i = 0; i < substeps; ++i) s.substep(dt);
    s.time += s.settings.timeStep;
    s.failures += s.report.failures;
    s.testRest(s.settings.timeStep);
}

// Contacts are looked for as far as each body can travel in the step (its velocity, with the
// turn of its farthest vertex), plus contactMargin, which also covers what gravity adds within
// the step (g·dt², 0.3 units at 60 Hz). This runs before the velocities are advanced, so that
// each point's bounce is judged from the velocity the bodies arrived with. Resting bodies are not looked at,
// unless an awake body touches them: then their figure wakes and the search runs again.
void World::State::findContacts(Real dt) {
    if (collision.bodyCount() == 0) return;
    do {
        findContactsOnce(dt);
    } while (wakeTouched());
    contacts.gather(manifolds, bodies, materials);
}

void World::State::findContactsOnce(Real dt) {
    reach.resize(bodies.size());
    moves.resize(bodies.size());
    poses.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const RigidBody& b = bodies[i];
        reach[i] = dt * b.angularVelocity.norm() * radius[i];
        moves[i] = dt * b.linearVelocity;
        poses[i] = {b.position, b.rotation()};
    }
    collision.findContacts(poses, moves, reach, settings.contactMargin, bodyAwake, manifolds);
}

void World::State::writeRows() {
    rows.clear();
    ranges.clear();
    rowKeys.clear();
    for (std::size_t k = 0; k < joints.size(); ++k) {
        if (!awake(joints[k].bodyA) && !awake(joints[k].bodyB)) {
            ranges.push_back({static_cast<int>(rows.size()), 0, 0, 0});
            continue;
        }
        const JointRowRange range = writeJointRows(joints[k], bodies, settings.rows, rows);
        ranges.push_back(range);
        const std::uint64_t joint = kJointKeyTag | (static_cast<std::uint64_t>(k) << 8);
        for (int r = 0; r < range.equalityRows; ++r) rowKeys.push_back(joint | static_cast<std::uint64_t>(r));
        for (int r = 0; r < range.limitRows; ++r) rowKeys.push_back(joint | static_cast<std::uint64_t>(64 + r));
        for (int r = 0; r < range.frictionRows; ++r) rowKeys.push_back(joint | static_cast<std::uint64_t>(128 + r));
    }
    contacts.writeRows(bodies, settings.contact, rows, rowKeys);
    if (extraRows) {
        const std::size_t first = rows.size();
        extraRows(bodies, rows);
        for (std::size_t r = first; r < rows.size(); ++r) rowKeys.push_back(kExtraKeyTag | (r - first));
    }
}

// Limit and contact rows are written a little before they are reached (speculatively), so that
// they hold from the first step they are needed. Until the gap C > 0 is closed such a row must
// not push: it allows approaching by the gap within the step, Cdot ≥ −C/dt. A bounce
// (restitution target > 0) stays only if the bodies close the gap within this step.
void World::State::allowApproach(Real dt) {
    for (std::size_t i = 0; i < rows.size(); ++i) {
        ConstraintRow& r = rows[i];
        if (r.lo != 0 || r.frictionSource >= 0 || r.error <= 0) continue;
        const bool impactThisStep = -rowVelocity(r, bodies) * dt >= r.error;
        if (r.target > 0 && impactThisStep) continue;
        r.target = std::min(r.target > 0 ? Real(0) : r.target, -r.error / dt);
    }
}

// Warm-started from the rows with the same keys in the previous step. PGS running out of sweeps
// is its normal way of stopping, not a failure.
LcpStatus World::State::solveVelocities() {
    const LcpProblem problem = system.problem();
    std::span<Real> x = system.solution();
    std::span<LcpRowState> states = system.states();
    warmStart.recall(rowKeys, states, x);
    if (settings.solver == SolverKind::Tree) {
        if (solveWithTree()) return LcpStatus::Solved;
        ++report.treeFallbacks;
    }
    if (settings.solver == SolverKind::Pgs) {
        const LcpPgsResult r = pgs.solve(problem, x);
        report.iterations = r.iterations;
        report.residual = r.residual;
        return r.status == LcpStatus::NotConverged ? LcpStatus::Solved : r.status;
    }
    if (solveByBoxIteration(problem)) return LcpStatus::Solved;
    const LcpResult r = exact.solve(problem, x, states);
    report.pivots += r.pivots;
    report.residual = r.residual;
    if (r.status != LcpStatus::Solved) solveWithFrozenFriction(problem);
    return r.status;
}

// Friction boxes follow their normals by fixed-point iteration: each pass freezes every box at
// mu·|x_normal| of the last answer and solves that plain boxed LCP (convex, so the pivoting never
// cycles), warm-started from the pattern before. When a pass leaves every box where it found it,
// its answer is complementary with the coupled bounds too. False when that does not happen
// within kBoxPasses; the coupled solve then starts from the last pattern.
bool World::State::solveByBoxIteration(const LcpProblem& problem) {
    std::span<Real> x = system.solution();
    std::span<LcpRowState> states = system.states();
    const std::size_t n = static_cast<std::size_t>(problem.size);
    frozenLo.assign(problem.lo.begin(), problem.lo.end());
    frozenHi.assign(problem.hi.begin(), problem.hi.end());
    LcpProblem frozen = problem;
    frozen.lo = frozenLo;
    frozen.hi = frozenHi;
    frozen.findex = {};
    frozen.mu = {};
    for (int pass = 0; pass <= kBoxPasses; ++pass) {
        Real change = 0, largest = 0;
        for (std::size_t i = 0; i < n && !problem.findex.empty(); ++i) {
            const int source = problem.findex[i];
            if (source < 0) continue;
            const Real box = problem.mu[i] * std::abs(x[static_cast<std::size_t>(source)]);
            change = std::max(change, std::abs(box - frozenHi[i]));
            largest = std::max(largest, box);
            frozenLo[i] = -box;
            frozenHi[i] = box;
        }
        if (pass > 0 && change <= kBoxTolerance * (1 + largest)) return true;
        if (pass == kBoxPasses) return false;
        const LcpResult r = exact.solve(frozen, x, states);
        report.pivots += r.pivots;
        report.residual = r.residual;
        if (r.status != LcpStatus::Solved) return false;
    }
    return false;
}

// The tree solver's answer is the dense one; its impulses go where the dense solve's would, so
// that applying them and SHAKE work alike. False when it cannot serve these rows.
bool World::State::solveWithTree() {
    if (treeJoints != joints.size()) {
        tree.setStructure(bodies, joints);
        treeJoints = joints.size();
    }
    tree.factor(rows, ranges, bodies);
    const TreeSolveResult r = tree.solveVelocity(rows, bodies);
    if (r.status != LcpStatus::Solved) return false;
    const std::span<const Real> lambda = tree.impulses();
    std::copy(lambda.begin(), lambda.end(), system.solution().begin());
    report.pivots = r.pivots;
    report.residual = r.residual;
    return true;
}

// Never apply the impulses of a failed pivoting solve: they may be far from any solution. The
// failure is counted, and the step goes on with the best answer at hand: PGS estimates the
// normal impulses, the friction boxes are frozen at μ times those, and the pivoting solver solves
// that uncoupled problem, which is a convex one it always solves. If even that fails, PGS's
// bounded answer is used.
void World::State::solveWithFrozenFriction(const LcpProblem& problem) {
    std::span<Real> x = system.solution();
    std::span<LcpRowState> states = system.states();
    warmStart.recall(rowKeys, states, x);
    const LcpPgsResult estimate = pgs.solve(problem, x);
    report.iterations = estimate.iterations;
    report.residual = estimate.residual;

    const std::size_t n = static_cast<std::size_t>(problem.size);
    frozenLo.assign(problem.lo.begin(), problem.lo.end());
    frozenHi.assign(problem.hi.begin(), problem.hi.end());
    for (std::size_t i = 0; i < n && !problem.findex.empty(); ++i) {
        const int source = problem.findex[i];
        if (source < 0) continue;
        const Real box = problem.mu[i] * std::abs(x[static_cast<std::size_t>(source)]);
        frozenLo[i] = -box;
        frozenHi[i] = box;
    }
    LcpProblem frozen = problem;
    frozen.lo = frozenLo;
    frozen.hi = frozenHi;
    frozen.findex = {};
    frozen.mu = {};
    pgsAnswer.assign(x.begin(), x.end());
    std::fill(states.begin(), states.end(), LcpRowState::Unknown);
    const LcpResult r = exact.solve(frozen, x, states);
    if (r.status == LcpStatus::Solved) {
        report.residual = r.residual;
    } else {
        std::copy(pgsAnswer.begin(), pgsAnswer.end(), x.begin());
    }
}

// Warm-started from the pattern of the last position solve (the previous pass, or the previous
// step's last pass): resting contacts and limits keep their pattern from pass to pass.
LcpStatus World::State::solvePositions() {
    std::span<LcpRowState> states = system.states();
    std::span<Real> x = system.solution();
    positionWarmStart.recall(rowKeys, states, x);
    const LcpStatus status = exactPosition.solve(system.problem(), x, states).status;
    if (status != LcpStatus::Solved) {
        // As for velocities: a failed pivoting solve's displacements may be far from any
        // solution, and moving bodies by them can tear a figure apart. PGS's are bounded.
        positionWarmStart.recall(rowKeys, states, x);
        pgs.solve(system.problem(), x);
    }
    positionWarmStart.remember(rowKeys, states, x);
    return status;
}

void World::State::substep(Real dt) {
    for (const Joint& j : joints)
        if (j.type == ConstraintType::Spring && (awake(j.bodyA) || awake(j.bodyB))) applySpringForces(j, bodies);
    findContacts(dt);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (!bodyAwake[i]) continue;
        RigidBody& b = bodies[i];
        integrateVelocity(b, settings.gravity, dt, settings.integration);
        b.force.setZero();
        b.torque.setZero();
    }
    writeRows();
    report.rows = static_cast<int>(rows.size());
    allowApproach(dt);
    system.build(rows, bodies);
    system.setVelocityRhs(rows, bodies);
    if (solveVelocities() != LcpStatus::Solved) ++report.failures;
    const StepReport velocityReport = report;
    system.applyImpulses(rows, bodies);
    // Doom caps the speeds after the constraint forces too (§4.9): a whipping chain end must not
    // outrun what one step can follow.
    for (RigidBody& b : bodies) clampVelocity(b, settings.integration);
    shake.capture(rows, ranges, system);

    // The joint's impulse of this step bounds its friction in the next step, as in Doom.
    const std::span<const Real> lambda = system.solution();
    for (std::size_t k = 0; k < joints.size(); ++k) {
        Real sum = 0;
        for (int r = 0; r < ranges[k].equalityRows; ++r) {
            const Real l = lambda[static_cast<std::size_t>(ranges[k].first + r)];
            sum += l * l;
        }
        joints[k].lastImpulse = std::sqrt(sum);
    }
    warmStart.remember(rowKeys, system.states(), lambda);

    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (!bodyAwake[i]) continue;
        integratePosition(bodies[i], dt);
        applyAirFriction(bodies[i], dt);
    }
    closeDrift(dt);
    projectPositions();
    settleNewContacts();
    const int failures = report.failures;
    report = velocityReport;
    report.failures = failures;
}

// Two Newton steps of SHAKE (shake.h) close the in-step drift, which is O(dt²) to begin with.
// They are kept only when they behave like a correction: the first move at most
// kShakeTrust times the drift it closes, and the second step's drift a tenth of the first's.
// Otherwise (a long chain whipping through a large turn in one step) the step keeps its
// pre-SHAKE state and leaves the drift to the position-only pass, which can only remove energy.
void World::State::closeDrift(Real dt) {
    beforeShake.assign(bodies.begin(), bodies.end());
    writeRows();
    const ShakeCorrection::Step first = shake.apply(rows, ranges, bodies, dt);
    writeRows();
    const ShakeCorrection::Step second = shake.apply(rows, ranges, bodies, dt);
    const bool wellConditioned = first.move <= kShakeTrust * first.drift + kShakeTolerance;
    const bool converging = second.drift <= 0.1 * first.drift + kShakeTolerance;
    if (!wellConditioned || !converging) {
        std::copy(beforeShake.begin(), beforeShake.end(), bodies.begin());
        ++report.shakeRefusals;
    }
}

// Whatever remains (joint errors older than the step, limit and contact penetration, drift
// SHAKE refused) is removed by moving positions only, so correcting it never adds energy. Each
// pass solves the linearised problem J M⁻¹ Jᵀ Δ = −C and moves along it as far as that reduces
// the largest violation (halving the move up to kProjectionHalvings times): with large errors,
// or rows that nearly contradict each other (a limb pinned between another figure and its own
// joint), the full linear move can overshoot and tear joints open instead of closing them.
void World::State::projectPositions() {
    writeRows();
    Real violation = largestViolation();
    for (int pass = 0; pass < settings.positionIterations && violation > settings.positionTolerance; ++pass) {
        // Friction rows act on velocities only.
        for (const JointRowRange& range : ranges)
            for (int r = 0; r < range.frictionRows; ++r) {
                ConstraintRow& row = rows[static_cast<std::size_t>(range.first + range.equalityRows + range.limitRows + r)];
                row.lo = row.hi = 0;
            }
        for (std::size_t i = 0; i < rows.size(); ++i)
            if (rows[i].frictionSource >= 0) {
                rows[i].frictionSource = -1;
                rows[i].lo = rows[i].hi = 0;
            }
        system.build(rows, bodies);
        system.setPositionRhs(rows);
        if (solvePositions() != LcpStatus::Solved) ++report.failures;
        if (!moveWhileImproving(violation)) return;
    }
}

// Applies the solved displacements, halved until the largest violation drops below `violation`;
// on success leaves the rows written at the new poses and `violation` updated, otherwise puts
// the bodies back and returns false.
bool World::State::moveWhileImproving(Real& violation) {
    beforeProjection.assign(bodies.begin(), bodies.end());
    const ConstraintRows solvedRows = rows;
    std::span<Real> x = system.solution();
    for (int attempt = 0; attempt <= kProjectionHalvings; ++attempt) {
        system.applyDisplacements(solvedRows, bodies);
        writeRows();
        const Real after = largestViolation();
        if (after < violation) {
            violation = after;
            return true;
        }
        std::copy(beforeProjection.begin(), beforeProjection.end(), bodies.begin());
        for (Real& v : x) v /= 2;
    }
    writeRows();
    return false;
}

// The contacts the step started with do not see everything the step did: a vertex left out of a
// four-point manifold, or turned into the floor by the step's rotation. The contacts are looked
// for again at the final poses (no margin: only what touches), and when something penetrates
// deeper than the slop allows, the projection runs once more with them. They also make
// maxPenetration() report the poses the step ends with.
void World::State::settleNewContacts() {
    if (collision.bodyCount() == 0) return;
    std::fill(reach.begin(), reach.end(), Real(0));
    std::fill(moves.begin(), moves.end(), Vec3::Zero());
    for (std::size_t i = 0; i < bodies.size(); ++i) poses[i] = {bodies[i].position, bodies[i].rotation()};
    collision.findContacts(poses, moves, reach, 0, bodyAwake, manifolds);
    contacts.gather(manifolds, bodies, materials);
    if (contacts.maxPenetration(bodies) > settings.contact.slop + kPenetrationTolerance) projectPositions();
}

// Equality rows violate by |C|, one-sided rows (lo = 0: limits, contacts) only when C < 0.
Real World::State::largestViolation() const {
    Real worst = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const ConstraintRow& r = rows[i];
        if (r.frictionSource >= 0 || (r.lo == 0 && r.hi == 0)) continue;
        worst = std::max(worst, r.lo == 0 ? -r.error : std::abs(r.error));
    }
    return worst;
}

}  // namespace af
