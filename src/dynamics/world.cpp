#include "af/dynamics/world.h"

#include "row_system.h"
#include "shake.h"

#include <algorithm>

namespace af {

struct World::State {
    WorldSettings settings;
    std::vector<RigidBody> bodies;
    std::vector<Joint> joints;
    RowSource contacts;
    Real time = 0;
    StepReport report;
    int failures = 0;

    ConstraintRows rows;
    std::vector<JointRowRange> ranges;
    RowSystem system;
    LcpExactSolver exact;
    LcpExactSolver exactPosition;
    LcpPgsSolver pgs;
    ShakeCorrection shake;
    std::vector<RigidBody> beforeShake;
    // Warm start: the row pattern of the previous velocity solve, reused when the rows line up.
    std::vector<int> layout, previousLayout;
    std::vector<LcpRowState> previousStates;
    std::vector<Real> previousImpulses;

    void substep(Real dt);
    void allowApproach(Real dt);
    void closeDrift(Real dt);

    void writeRows();
    LcpStatus solve(LcpExactSolver& exactSolver, bool warmStart);
    void projectPositions();
    Real largestViolation() const;
};

namespace {

constexpr Real kShakeTrust = 2;         // a SHAKE move may be at most this many times its drift
constexpr Real kShakeTolerance = 1e-9;  // length units: drift this small counts as closed

std::vector<RigidBody> bodiesOf(const Figure& figure) {
    std::vector<RigidBody> out;
    for (const FigureBody& b : figure.bodies) {
        RigidBody body = RigidBody::dynamic(b.mass, b.inertia, b.pose.position, Quat(b.pose.rotation));
        body.linearFriction = b.linearFriction;
        body.angularFriction = b.angularFriction;
        out.push_back(body);
    }
    return out;
}

}  // namespace

World::World(const Figure& figure, const WorldSettings& settings)
    : World(bodiesOf(figure), makeJoints(figure), settings) {}

World::World(std::vector<RigidBody> bodies, std::vector<Joint> joints, const WorldSettings& settings)
    : state_(std::make_unique<State>()) {
    state_->settings = settings;
    state_->bodies = std::move(bodies);
    state_->joints = std::move(joints);
    state_->exact.setSettings(settings.exact);
    state_->exactPosition.setSettings(settings.exact);
    state_->pgs.setSettings(settings.pgs);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

void World::step() {
    State& s = *state_;
    s.report = {};
    const int substeps = std::max(1, s.settings.substeps);
    const Real dt = s.settings.timeStep / substeps;
    for (int i = 0; i < substeps; ++i) s.substep(dt);
    s.time += s.settings.timeStep;
    s.failures += s.report.failures;
}

void World::State::writeRows() {
    rows.clear();
    ranges.clear();
    layout.clear();
    for (const Joint& j : joints) {
        ranges.push_back(writeJointRows(j, bodies, settings.rows, rows));
        layout.push_back(static_cast<int>(rows.size()));
    }
    if (contacts) contacts(bodies, rows);
    layout.push_back(static_cast<int>(rows.size()));
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

// PGS running out of sweeps is its normal way of stopping, not a failure.
LcpStatus World::State::solve(LcpExactSolver& exactSolver, bool warmStart) {
    const LcpProblem problem = system.problem();
    if (settings.solver == SolverKind::Pgs) {
        std::span<Real> x = system.solution();
        std::fill(x.begin(), x.end(), Real(0));
        if (warmStart && previousImpulses.size() == x.size()) std::copy(previousImpulses.begin(), previousImpulses.end(), x.begin());
        const LcpPgsResult r = pgs.solve(problem, x);
        report.iterations = r.iterations;
        report.residual = r.residual;
        return r.status == LcpStatus::NotConverged ? LcpStatus::Solved : r.status;
    }
    std::span<LcpRowState> states = system.states();
    std::fill(states.begin(), states.end(), LcpRowState::Unknown);
    if (warmStart && previousStates.size() == states.size())
        std::copy(previousStates.begin(), previousStates.end(), states.begin());
    const LcpResult r = exactSolver.solve(problem, system.solution(), states);
    report.pivots = r.pivots;
    report.residual = r.residual;
    return r.status;
}

void World::State::substep(Real dt) {
    for (const Joint& j : joints)
        if (j.type == ConstraintType::Spring) applySpringForces(j, bodies);
    for (RigidBody& b : bodies) {
        integrateVelocity(b, settings.gravity, dt, settings.integration);
        b.force.setZero();
        b.torque.setZero();
    }

    writeRows();
    report.rows = static_cast<int>(rows.size());
    allowApproach(dt);
    system.build(rows, bodies);
    system.setVelocityRhs(rows, bodies);
    if (solve(exact, layout == previousLayout) != LcpStatus::Solved) ++report.failures;
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
    previousLayout = layout;
    previousStates.assign(system.states().begin(), system.states().end());
    previousImpulses.assign(lambda.begin(), lambda.end());

    for (RigidBody& b : bodies) {
        integratePosition(b, dt);
        applyAirFriction(b, dt);
    }
    closeDrift(dt);
    projectPositions();
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
// SHAKE refused) is removed by moving positions only, so correcting it never adds energy.
void World::State::projectPositions() {
    for (int pass = 0; pass < settings.positionIterations; ++pass) {
        writeRows();
        if (largestViolation() <= settings.positionTolerance) return;
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
        if (solve(exactPosition, false) != LcpStatus::Solved) ++report.failures;
        system.applyDisplacements(rows, bodies);
    }
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

void World::setContactSource(RowSource source) { state_->contacts = std::move(source); }
std::vector<RigidBody>& World::bodies() { return state_->bodies; }
const std::vector<RigidBody>& World::bodies() const { return state_->bodies; }
const std::vector<Joint>& World::joints() const { return state_->joints; }
const WorldSettings& World::settings() const { return state_->settings; }
Real World::time() const { return state_->time; }
const StepReport& World::lastStep() const { return state_->report; }
int World::solverFailures() const { return state_->failures; }

Real World::maxJointError() const {
    Real worst = 0;
    for (const Joint& j : state_->joints) worst = std::max(worst, jointError(j, state_->bodies));
    return worst;
}

Real World::maxLimitViolationDegrees() const {
    Real worst = 0;
    for (const Joint& j : state_->joints) worst = std::max(worst, limitViolationDegrees(j, state_->bodies));
    return worst;
}

Real World::kineticEnergy() const {
    Real sum = 0;
    for (const RigidBody& b : state_->bodies) sum += b.kineticEnergy();
    return sum;
}

std::vector<RigidPose> World::bodyPoses() const {
    std::vector<RigidPose> out;
    for (const RigidBody& b : state_->bodies) out.push_back({b.position, b.rotation()});
    return out;
}

}  // namespace af
