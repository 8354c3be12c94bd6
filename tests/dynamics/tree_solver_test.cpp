// The tree solver (primary joints factorised in linear time, the rest as an LCP on the Schur
// complement) against the dense exact path (RowSystem + LcpExactSolver) on the same rows: the
// hung humanoid with limits and joint friction active, a 20-link chain, a figure with loops and
// a second path to the world, and contacts with friction. Also which joints are primary, and
// how little the warm start of the next step has to pivot.

#include "../figure/figure_test_util.h"
#include "af/dynamics/contact.h"
#include "af/dynamics/tree_solver.h"
#include "dynamics/row_system.h"
#include "scene_test_util.h"

#include <algorithm>
#include <random>

namespace af {
namespace {

constexpr Real kDt = Real(1) / 60;
const Vec3 kGravity(0, 0, -1066);

std::vector<RigidBody> bodiesOf(const Figure& figure) {
    std::vector<RigidBody> out;
    for (const FigureBody& b : figure.bodies)
        out.push_back(RigidBody::dynamic(b.mass, b.inertia, b.pose.position, Quat(b.pose.rotation)));
    return out;
}

// A square of four bars joined by ball joints, pinned to the world at the middle of its top bar
// (hang) and off the middle of its bottom bar (ground: a second path to the world; at the middle
// the two pins would make the square's rows dependent), closed by `loop`. Below the bottom bar
// a hinge, a universal joint and a slider (written parent first, body1 = the parent), and a
// spring to the world.
Figure loopFigure() {
    using test::boxBodyText;
    const Vec3 across(5, 1, 1), down(1, 1, 5);
    return test::figureOfBlocks(
        {"origin", "j1", "j2", "j3", "j4", "j5", "j6"},
        boxBodyText("b0", "origin", across, Vec3(5, 0, 0), 0.2) + boxBodyText("b1", "j1", down, Vec3(10, 0, -5), 0.2) +
            boxBodyText("b2", "j2", across, Vec3(5, 0, -10), 0.2) + boxBodyText("b3", "j3", down, Vec3(0, 0, -5), 0.2) +
            boxBodyText("b4", "j4", down, Vec3(5, 0, -15), 0.2) + boxBodyText("b5", "j5", down, Vec3(5, 0, -25), 0.2) +
            boxBodyText("b6", "j6", down, Vec3(5, 0, -35), 0.2) +
            "ballAndSocketJoint \"hang\" { body1 \"b0\" body2 \"world\" anchor ( 5, 0, 0 ) friction 0 }\n"
            "ballAndSocketJoint \"j1\" { body1 \"b1\" body2 \"b0\" anchor ( 10, 0, 0 ) friction 0 }\n"
            "ballAndSocketJoint \"j2\" { body1 \"b2\" body2 \"b1\" anchor ( 10, 0, -10 ) friction 0 }\n"
            "ballAndSocketJoint \"j3\" { body1 \"b3\" body2 \"b2\" anchor ( 0, 0, -10 ) friction 0 }\n"
            "ballAndSocketJoint \"loop\" { body1 \"b3\" body2 \"b0\" anchor ( 0, 0, 0 ) friction 0 }\n"
            "ballAndSocketJoint \"ground\" { body1 \"b2\" body2 \"world\" anchor ( 2, 0, -10 ) friction 0 }\n"
            "hinge \"knee\" { body1 \"b4\" body2 \"b2\" anchor ( 5, 0, -10 ) axis ( 0, 1, 0 ) friction 0 }\n"
            "universalJoint \"hip\" { body1 \"b5\" body2 \"b4\" anchor ( 5, 0, -20 ) shafts ( 0, 0, -1 ), ( 0, 0, 1 ) "
            "friction 0 }\n"
            "slider \"rail\" { body1 \"b5\" body2 \"b6\" axis ( 0, 0, 1 ) friction 0 }\n"
            "spring \"bungee\" { body1 \"b6\" body2 \"world\" anchor1 ( 5, 0, -40 ) anchor2 ( 5, 0, -60 ) friction 0 "
            "stretch 1 compress 0 damping 0 restLength 10 minLength 0 maxLength 30 }\n");
}

// Bodies, joints and the rows of one pose, written as World writes them: the joints' rows in
// order, then the contacts'.
struct Scene {
    std::vector<RigidBody> bodies;
    std::vector<Joint> joints;
    std::vector<Contact> contacts;
    ConstraintRows rows;
    std::vector<JointRowRange> ranges;

    explicit Scene(const Figure& figure) : bodies(bodiesOf(figure)), joints(makeJoints(figure)) {}

    void write() {
        rows.clear();
        ranges.clear();
        for (const Joint& j : joints) ranges.push_back(writeJointRows(j, bodies, JointRowSettings{}, rows));
        for (const Contact& c : contacts) writeContactRows(c, bodies, ContactSettings{}, rows);
    }
    int count(int JointRowRange::*field) const {
        int n = 0;
        for (const JointRowRange& r : ranges) n += r.*field;
        return n;
    }
};

void spin(Scene& scene, unsigned seed, Real speed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(-speed, speed);
    for (RigidBody& b : scene.bodies) {
        b.angularVelocity = Vec3(u(rng), u(rng), u(rng));
        b.linearVelocity = Vec3(u(rng), u(rng), u(rng));
    }
}

// The velocity problem of a step: velocities predicted with gravity, rows at the pose.
void predict(Scene& scene) {
    for (RigidBody& b : scene.bodies) integrateVelocity(b, kGravity, kDt, IntegrationSettings{});
    scene.write();
}

// One step as World takes it, with the tree solver: velocities, rows, impulses, positions, then
// one pass of position projection. Returns the velocity solve's result.
TreeSolveResult step(Scene& scene, TreeSolver& solver) {
    predict(scene);
    solver.factor(scene.rows, scene.ranges, scene.bodies);
    const TreeSolveResult result = solver.solveVelocity(scene.rows, scene.bodies);
    solver.applyImpulses(scene.bodies);
    const std::span<const Real> lambda = solver.impulses();
    for (std::size_t k = 0; k < scene.joints.size(); ++k) {
        Real sum = 0;
        for (int r = 0; r < scene.ranges[k].equalityRows; ++r) sum += std::pow(lambda[static_cast<std::size_t>(scene.ranges[k].first + r)], 2);
        scene.joints[k].lastImpulse = std::sqrt(sum);
    }
    for (RigidBody& b : scene.bodies) integratePosition(b, kDt);
    scene.write();
    solver.factor(scene.rows, scene.ranges, scene.bodies, TreeProblems::PositionOnly);
    solver.solvePosition(scene.rows);
    solver.applyDisplacements(scene.bodies);
    return result;
}

// The dense exact answer. The position problem holds friction rows at 0, as World does.
struct Dense {
    std::vector<Real> lambda;
    LcpResult result;
    RowSystem system;
};

void solveDense(const Scene& scene, bool position, Dense& out) {
    ConstraintRows rows = scene.rows;
    if (position) holdFrictionAtZero(rows, scene.ranges);
    out.system.build(rows, scene.bodies);
    if (position) {
        out.system.setPositionRhs(rows);
    } else {
        out.system.setVelocityRhs(rows, scene.bodies);
    }
    LcpExactSolver solver;
    std::vector<LcpRowState> states(rows.size(), LcpRowState::Unknown);
    out.result = solver.solve(out.system.problem(), out.system.solution(), states);
    out.lambda.assign(out.system.solution().begin(), out.system.solution().end());
}

Real largest(std::span<const Real> v) {
    Real m = 0;
    for (Real x : v) m = std::max(m, std::abs(x));
    return m;
}

enum class Problem { Velocity, Position, PositionOnly };

// The tree's λ against the dense λ, and the dense problem's natural residual at the tree's λ,
// both relative to the largest impulse, which is returned. PositionOnly: the position problem
// on a factorisation for it alone (friction rows left out).
Real expectSameAsDense(Scene& scene, TreeSolver& solver, Problem problem, const std::string& what) {
    SCOPED_TRACE(what);
    const bool position = problem != Problem::Velocity;
    solver.factor(scene.rows, scene.ranges, scene.bodies,
                  problem == Problem::PositionOnly ? TreeProblems::PositionOnly : TreeProblems::VelocityAndPosition);
    const TreeSolveResult tree = position ? solver.solvePosition(scene.rows) : solver.solveVelocity(scene.rows, scene.bodies);
    Dense dense;
    solveDense(scene, position, dense);
    EXPECT_EQ(dense.result.status, LcpStatus::Solved);
    EXPECT_EQ(tree.status, LcpStatus::Solved);
    const std::span<const Real> lambda = solver.impulses();
    if (lambda.size() != dense.lambda.size()) {
        ADD_FAILURE() << "λ sizes differ";
        return kInfinity;
    }
    const Real scale = std::max(Real(1), largest(dense.lambda));
    Real worst = 0;
    for (std::size_t i = 0; i < lambda.size(); ++i) worst = std::max(worst, std::abs(lambda[i] - dense.lambda[i]));
    EXPECT_LE(worst, 1e-9 * scale) << "largest |λ| " << scale;
    EXPECT_LE(tree.residual, 1e-9 * scale);
    EXPECT_LE(lcpResidual(dense.system.problem(), lambda), 1e-9 * scale);
    if (problem != Problem::PositionOnly) {
        EXPECT_EQ(tree.primaryRows + tree.auxiliaryRows, static_cast<int>(scene.rows.size()));
    }
    return worst / scale;
}

TEST(TreeSolverStructure, LoopClosingJointsAndSpringsStayAuxiliary) {
    Scene scene(loopFigure());
    ASSERT_EQ(scene.joints.size(), 10u);
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    const bool primary[10] = {true, true, true, true, false, false, true, true, true, false};
    for (int k = 0; k < 10; ++k) EXPECT_EQ(solver.isPrimary(k), primary[k]) << scene.joints[static_cast<std::size_t>(k)].name;
}

TEST(TreeSolverStructure, AStaticBodyCountsAsTheWorld) {
    Scene scene(test::hangingChain(3, 0));
    scene.bodies[0] = RigidBody{};  // static: the chain's top link is part of the world now
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    EXPECT_FALSE(solver.isPrimary(0)) << "joins the world to a static body";
    EXPECT_TRUE(solver.isPrimary(1));
    EXPECT_TRUE(solver.isPrimary(2));
    scene.write();
    expectSameAsDense(scene, solver, Problem::Velocity, "chain below a static link");
}

TEST(TreeSolverStructure, APositionOnlyFactorisationRefusesTheVelocityProblem) {
    Scene scene(test::hungHumanoid());
    for (Joint& j : scene.joints) j.lastImpulse = 100;  // joint friction rows
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    scene.write();
    solver.factor(scene.rows, scene.ranges, scene.bodies, TreeProblems::PositionOnly);
    EXPECT_EQ(solver.solveVelocity(scene.rows, scene.bodies).status, LcpStatus::InvalidInput);
    const TreeSolveResult position = solver.solvePosition(scene.rows);
    EXPECT_EQ(position.status, LcpStatus::Solved);
    EXPECT_EQ(position.auxiliaryRows, 0) << "only friction rows are auxiliary at spawn";
    solver.factor(scene.rows, scene.ranges, scene.bodies);
    EXPECT_GT(solver.solveVelocity(scene.rows, scene.bodies).auxiliaryRows, 20);
}

// A joint whose rows repeat each other, without CFM: its block cannot be factorised. The solve
// goes on (as Doom's does) and says so; the impulses stay finite.
TEST(TreeSolverStructure, DependentPrimaryRowsWithoutCfmAreReportedNotHidden) {
    std::vector<RigidBody> bodies = {RigidBody::dynamic(2, Mat3::Identity(), Vec3(0, 0, -5), Quat::Identity())};
    bodies[0].linearVelocity = Vec3(1, 0, -3);
    std::vector<Joint> joints(1);
    joints[0].type = ConstraintType::BallAndSocket;
    joints[0].bodyA = 0;
    ConstraintRows rows;
    const Vec3 axes[] = {Vec3::UnitX(), Vec3::UnitZ(), Vec3::UnitZ()};
    for (const Vec3& axis : axes) {
        ConstraintRow row;
        row.bodyA = 0;
        row.linearA = axis;
        row.angularA = Vec3(0, 0, 5).cross(axis);
        rows.add(row);
    }
    const std::vector<JointRowRange> ranges = {{.first = 0, .equalityRows = 3}};
    TreeSolver solver;
    solver.setStructure(bodies, joints);
    solver.factor(rows, ranges, bodies);
    EXPECT_EQ(solver.solveVelocity(rows, bodies).status, LcpStatus::Unsatisfiable);
    for (const Real l : solver.impulses()) EXPECT_TRUE(std::isfinite(l));
}

TEST(TreeSolverStructure, EveryJointOfTheHungHumanoidIsPrimaryItsWeldToTheWorldToo) {
    Scene scene(test::hungHumanoid());
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    for (std::size_t k = 0; k < scene.joints.size(); ++k) EXPECT_TRUE(solver.isPrimary(static_cast<int>(k))) << scene.joints[k].name;
}

void report(const char* what, const Scene& scene, Real velocity, Real position) {
    std::printf("tree vs dense, %s (%zu rows): max |λ_tree − λ_dense| / max |λ|: velocity %.2g, position %.2g\n", what,
                scene.rows.size(), velocity, position);
}

TEST(TreeSolverExact, HungHumanoidWithLimitsAndJointFrictionMatchesTheDenseSolve) {
    Scene scene(test::hungHumanoid());
    spin(scene, 3, 6);
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    int withLimits = 0;
    Real velocity = 0, position = 0;
    for (int i = 0; i < 60; ++i) {
        step(scene, solver);
        scene.write();
        if (scene.count(&JointRowRange::limitRows) >= 4) ++withLimits;
        ASSERT_GT(scene.count(&JointRowRange::frictionRows), 20) << "step " << i;
        velocity = std::max(velocity, expectSameAsDense(scene, solver, Problem::Velocity, "velocity, step " + std::to_string(i)));
        position = std::max(position, expectSameAsDense(scene, solver, Problem::Position, "position, step " + std::to_string(i)));
        position = std::max(position, expectSameAsDense(scene, solver, Problem::PositionOnly, "position only, step " + std::to_string(i)));
    }
    report("shaken humanoid, 60 steps", scene, velocity, position);
    EXPECT_GE(withLimits, 8) << "poses with at least 4 limit rows";
}

TEST(TreeSolverExact, TwentyLinkChainMatchesTheDenseSolve) {
    Scene scene(test::horizontalChain(20, 0));
    spin(scene, 5, 2);
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    for (int i = 0; i < 30; ++i) step(scene, solver);
    scene.write();
    const Real velocity = expectSameAsDense(scene, solver, Problem::Velocity, "velocity");
    const Real position = std::max(expectSameAsDense(scene, solver, Problem::Position, "position"),
                                   expectSameAsDense(scene, solver, Problem::PositionOnly, "position only"));
    report("20-link chain", scene, velocity, position);
}

// Without a joint to the world the tree is rooted at its middle link; every link touches the
// ground with friction, and one link touches the far end (a row whose two bodies meet only at
// the root).
TEST(TreeSolverExact, FreeChainOnTheGroundMatchesTheDenseSolve) {
    Scene scene(test::horizontalChain(20, 0, true));
    spin(scene, 9, 3);
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    for (int i = 0; i < 10; ++i) step(scene, solver);
    for (int k = 0; k < 20; ++k) {
        RigidBody& b = scene.bodies[static_cast<std::size_t>(k)];
        b.linearVelocity += Vec3(k % 2 == 0 ? 20 : -5, 0, -30);
        Contact c;
        c.bodyA = k;
        c.point = b.position + Vec3(0, 0, -1);
        c.normal = Vec3::UnitZ();
        c.depth = 0.02 * (k % 7);  // the position problem pushes the deeper ones out
        c.friction = 0.6;
        scene.contacts.push_back(c);
    }
    Contact ends;
    ends.bodyA = 0;
    ends.bodyB = 19;
    ends.point = (scene.bodies[0].position + scene.bodies[19].position) / 2;
    ends.normal = (scene.bodies[0].position - scene.bodies[19].position).normalized();
    ends.friction = 0.3;
    scene.contacts.push_back(ends);
    scene.bodies[0].linearVelocity -= 40 * ends.normal;
    scene.write();
    const Real velocity = expectSameAsDense(scene, solver, Problem::Velocity, "velocity");
    const Real position = std::max(expectSameAsDense(scene, solver, Problem::Position, "position"),
                                   expectSameAsDense(scene, solver, Problem::PositionOnly, "position only"));
    report("free 20-link chain on the ground", scene, velocity, position);
}

TEST(TreeSolverExact, LoopsAndASecondPathToTheWorldMatchTheDenseSolve) {
    Scene scene(loopFigure());
    spin(scene, 7, 3);
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    for (int i = 0; i < 20; ++i) step(scene, solver);
    scene.write();
    const Real velocity = expectSameAsDense(scene, solver, Problem::Velocity, "velocity");
    const Real position = std::max(expectSameAsDense(scene, solver, Problem::Position, "position"),
                                   expectSameAsDense(scene, solver, Problem::PositionOnly, "position only"));
    report("loops", scene, velocity, position);
}

// Contacts on the humanoid's bodies against the floor and one between two of them, all with
// friction; the bodies move into the floor and along it, so some contacts push and some slide.
// None on the chest: welded to the world, it could only be pushed out of the floor against its
// weld, an answer set by the CFM alone (λ ~ depth / CFM) and as ill-conditioned.
TEST(TreeSolverExact, ContactsWithFrictionMatchTheDenseSolve) {
    Scene scene(test::hungHumanoid());
    spin(scene, 11, 4);
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    for (int i = 0; i < 20; ++i) step(scene, solver);
    const int bodyCount = static_cast<int>(scene.bodies.size());
    const int chest = scene.joints.back().bodyA;
    for (int k = 0; k < bodyCount; k += 2) {
        if (k == chest) continue;
        RigidBody& b = scene.bodies[static_cast<std::size_t>(k)];
        b.linearVelocity += Vec3(30.0 * (k % 3) - 30, 10, -60);
        Contact c;
        c.bodyA = k;
        c.point = b.position + Vec3(1, -1, -2);
        c.normal = Vec3::UnitZ();
        c.depth = 0.03 * (k % 5);
        c.friction = k % 4 == 0 ? 0.3 : 0.9;
        scene.contacts.push_back(c);
    }
    Contact between;  // the waist (body 1) and the right foot (the last body)
    between.bodyA = 1;
    between.bodyB = bodyCount - 1;
    between.point = (scene.bodies[1].position + scene.bodies.back().position) / 2;
    between.normal = (scene.bodies[1].position - scene.bodies.back().position).normalized();
    between.friction = 0.5;
    scene.contacts.push_back(between);
    scene.bodies[1].linearVelocity -= 50 * between.normal;
    scene.write();
    const Real velocity = expectSameAsDense(scene, solver, Problem::Velocity, "velocity");
    const Real position = std::max(expectSameAsDense(scene, solver, Problem::Position, "position"),
                                   expectSameAsDense(scene, solver, Problem::PositionOnly, "position only"));
    report("humanoid with contacts", scene, velocity, position);
}

TEST(TreeSolverExact, ImpulsesAndDisplacementsMoveBodiesAsTheDensePathDoes) {
    Scene scene(test::hungHumanoid());
    spin(scene, 13, 6);
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    for (int i = 0; i < 40; ++i) step(scene, solver);
    scene.write();
    for (const bool position : {false, true}) {
        solver.factor(scene.rows, scene.ranges, scene.bodies);
        if (position) {
            solver.solvePosition(scene.rows);
        } else {
            solver.solveVelocity(scene.rows, scene.bodies);
        }
        Dense dense;
        solveDense(scene, position, dense);
        std::vector<RigidBody> tree = scene.bodies;
        std::vector<RigidBody> reference = scene.bodies;
        if (position) {
            solver.applyDisplacements(tree);
            dense.system.applyDisplacements(scene.rows, reference);
        } else {
            solver.applyImpulses(tree);
            dense.system.applyImpulses(scene.rows, reference);
        }
        for (std::size_t k = 0; k < tree.size(); ++k) {
            const Real vScale = std::max(Real(1), reference[k].linearVelocity.norm());
            EXPECT_LE((tree[k].linearVelocity - reference[k].linearVelocity).norm(), 1e-9 * vScale);
            EXPECT_LE((tree[k].angularVelocity - reference[k].angularVelocity).norm(), 1e-9 * std::max(Real(1), reference[k].angularVelocity.norm()));
            EXPECT_LE((tree[k].position - reference[k].position).norm(), 1e-9 * std::max(Real(1), reference[k].position.norm()));
            EXPECT_LE(tree[k].orientation.angularDistance(reference[k].orientation), 1e-9);
        }
    }
}

// Steps of the shaken humanoid: the velocity solve warm-started from the step before pivots
// rarely (a few times where a limit engages or a joint starts to slip), where a cold solve of
// the same rows pivots through every row it finds at a bound.
TEST(TreeSolverWarmStart, TheNextStepNeedsFewPivotsAndTheSameProblemNone) {
    Scene scene(test::hungHumanoid());
    spin(scene, 3, 6);
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    for (int i = 0; i < 30; ++i) step(scene, solver);
    long warm = 0, cold = 0;
    int worst = 0, again = 0;
    const int steps = 60;
    for (int i = 0; i < steps; ++i) {
        // The same velocity problem solved cold by a fresh solver, then again from its own states.
        Scene same = scene;
        predict(same);
        TreeSolver fresh;
        fresh.setStructure(same.bodies, same.joints);
        fresh.factor(same.rows, same.ranges, same.bodies);
        cold += fresh.solveVelocity(same.rows, same.bodies).pivots;
        again += fresh.solveVelocity(same.rows, same.bodies).pivots;

        const TreeSolveResult next = step(scene, solver);
        warm += next.pivots;
        worst = std::max(worst, next.pivots);
    }
    std::printf("tree solver, shaken humanoid, %d steps: warm-started next step %.2f pivots (max %d), cold %.2f\n",
                steps, static_cast<double>(warm) / steps, worst, static_cast<double>(cold) / steps);
    EXPECT_EQ(again, 0);
    EXPECT_LE(warm, steps) << "one pivot per step or fewer on average";
    EXPECT_LE(worst, 10) << "a few where limits or friction change";
    EXPECT_GT(cold, 10 * warm);
}

}  // namespace
}  // namespace af
