// The tree solver (primary joints factorised in linear time, the rest as an LCP on the Schur
// complement) against the dense exact path (RowSystem + LcpExactSolver) on the same rows: the
// hung humanoid with limits and joint friction active, a 20-link chain, a figure with loops and
// a second path to the world, and contacts with friction. Also which joints are primary, and
// how little the warm start of the next step has to pivot.

#include "row_scene_util.h"
#include "scene_test_util.h"

namespace af {
namespace {

using namespace test;

enum class Problem { Velocity, Position, PositionOnly };

// TreeSolverIterative's bound on the relaxed answer's natural residual, relative to the largest
// impulse (measured: see the test's output).
constexpr Real kIterativeResidual = 1e-6;  // 9.4e-8 with 200 sweeps

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
    const ConstraintRows rows = dependentRows();
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

void reportTreeAgreement(const char* what, const Scene& scene, Real velocity, Real position) {
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
    reportTreeAgreement("shaken humanoid, 60 steps", scene, velocity, position);
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
    reportTreeAgreement("20-link chain", scene, velocity, position);
}

TEST(TreeSolverExact, FreeChainOnTheGroundMatchesTheDenseSolve) {
    TreeSolver solver;
    Scene scene = freeChainOnTheGround(solver);
    const Real velocity = expectSameAsDense(scene, solver, Problem::Velocity, "velocity");
    const Real position = std::max(expectSameAsDense(scene, solver, Problem::Position, "position"),
                                   expectSameAsDense(scene, solver, Problem::PositionOnly, "position only"));
    reportTreeAgreement("free 20-link chain on the ground", scene, velocity, position);
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
    reportTreeAgreement("loops", scene, velocity, position);
}

TEST(TreeSolverExact, ContactsWithFrictionMatchTheDenseSolve) {
    TreeSolver solver;
    Scene scene = humanoidWithContacts(solver);
    const Real velocity = expectSameAsDense(scene, solver, Problem::Velocity, "velocity");
    const Real position = std::max(expectSameAsDense(scene, solver, Problem::Position, "position"),
                                   expectSameAsDense(scene, solver, Problem::PositionOnly, "position only"));
    reportTreeAgreement("humanoid with contacts", scene, velocity, position);
}

// An answer that is not the exact one still holds every primary joint row exactly once its
// impulses are applied, and keeps every contact and friction impulse in its box; returns how many
// contact rows had a box to keep (a test whose contacts all part tests nothing).
int expectJointsHeldAndImpulsesBoxed(const Scene& scene, const TreeSolver& solver, Real scale) {
    const std::span<const Real> lambda = solver.impulses();
    std::vector<RigidBody> after = scene.bodies;
    solver.applyImpulses(after);
    int held = 0;
    for (std::size_t k = 0; k < scene.joints.size(); ++k) {
        if (!solver.isPrimary(static_cast<int>(k))) continue;
        for (int q = 0; q < scene.ranges[k].equalityRows; ++q) {
            const std::size_t i = static_cast<std::size_t>(scene.ranges[k].first + q);
            const ConstraintRow& row = scene.rows[i];
            EXPECT_NEAR(rowVelocity(row, after), row.target - row.cfm * lambda[i], 1e-9 * scale) << "joint " << k;
            ++held;
        }
    }
    EXPECT_GT(held, 40);
    int boxed = 0;
    const std::size_t contactsFrom = static_cast<std::size_t>(scene.ranges.back().first + scene.ranges.back().total());
    for (std::size_t i = contactsFrom; i < scene.rows.size(); ++i) {
        const ConstraintRow& row = scene.rows[i];
        if (row.frictionSource < 0) {
            EXPECT_GE(lambda[i], -1e-12 * scale) << "a contact pulls, row " << i;
            continue;
        }
        const Real box = row.frictionCoefficient * std::abs(lambda[static_cast<std::size_t>(row.frictionSource)]);
        EXPECT_LE(std::abs(lambda[i]), box + 1e-9 * scale) << "friction beyond its box, row " << i;
        boxed += box > 0;
    }
    return boxed;
}

// A coupled friction problem that the pivoting solve does not settle (one coupling pass for
// contacts sliding at up to 70 units/s) is never answered with that solve's impulses: the tree
// leaves the frozen-box answer, which the world keeps on large islands rather than pivoting over
// all rows (SolverTuning::denseRescueRows).
TEST(TreeSolverFailure, AnUnsettledFrictionSolveLeavesTheFrozenBoxAnswerWithTheJointsHeld) {
    TreeSolver solver(LcpExactSettings{.maxCouplingPasses = 1});
    Scene scene = humanoidWithContacts(solver);
    solver.factor(scene.rows, scene.ranges, scene.bodies);
    const TreeSolveResult result = solver.solveVelocity(scene.rows, scene.bodies);
    ASSERT_EQ(result.status, LcpStatus::NotConverged);
    EXPECT_TRUE(result.frozenAnswer);
    const Real scale = std::max(Real(1), largest(solver.impulses()));
    EXPECT_GT(expectJointsHeldAndImpulsesBoxed(scene, solver, scale), 0) << "no contact pushed";
}

// Beyond the pivot row limit the auxiliary rows are relaxed by projected Gauss–Seidel on the
// Schur complement: the joints still hold exactly whatever the contacts converged to, every
// impulse is within its box, and the answer is near the dense one.
TEST(TreeSolverIterative, BeyondThePivotRowLimitTheJointsHoldAndTheContactsAreRelaxed) {
    TreeSolver solver;
    Scene scene = humanoidWithContacts(solver);
    solver.setPivotRowLimit(5, LcpPgsSettings{.maxIterations = 200});
    solver.factor(scene.rows, scene.ranges, scene.bodies);
    const TreeSolveResult result = solver.solveVelocity(scene.rows, scene.bodies);
    ASSERT_EQ(result.status, LcpStatus::Solved);
    ASSERT_TRUE(result.iterative);
    ASSERT_GT(result.auxiliaryRows, 5);
    Dense dense;
    solveDense(scene, false, dense);
    ASSERT_EQ(dense.result.status, LcpStatus::Solved);
    const Real scale = std::max(Real(1), largest(dense.lambda));
    EXPECT_GT(expectJointsHeldAndImpulsesBoxed(scene, solver, scale), 0) << "no contact pushed";
    const Real residual = lcpResidual(dense.system.problem(), solver.impulses()) / scale;
    std::printf("[ iterative ] %d auxiliary rows: natural residual %.2g of the largest impulse\n",
                result.auxiliaryRows, residual);
    EXPECT_LE(residual, kIterativeResidual);
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
            dense.system.applyDisplacements(reference);
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

// The solve for a caller that moves the bodies itself gives the same displacements, bit for
// bit, and leaves the bodies where they are if asked to move them.
TEST(TreeSolverExact, PositionImpulsesAloneAreThoseOfTheFullPositionSolve) {
    Scene scene(test::hungHumanoid());
    spin(scene, 13, 6);
    TreeSolver full, impulsesOnly;
    full.setStructure(scene.bodies, scene.joints);
    impulsesOnly.setStructure(scene.bodies, scene.joints);
    for (int i = 0; i < 40; ++i) step(scene, full);
    scene.write();
    full.resetWarmStart();  // both start cold
    full.factor(scene.rows, scene.ranges, scene.bodies, TreeProblems::PositionOnly);
    impulsesOnly.factor(scene.rows, scene.ranges, scene.bodies, TreeProblems::PositionOnly);
    ASSERT_EQ(full.solvePosition(scene.rows).status, LcpStatus::Solved);
    ASSERT_EQ(impulsesOnly.solvePositionImpulses(scene.rows).status, LcpStatus::Solved);
    const std::span<const Real> a = full.impulses(), b = impulsesOnly.impulses();
    ASSERT_EQ(a.size(), b.size());
    Real largest = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i], b[i]);
        largest = std::max(largest, std::abs(a[i]));
    }
    EXPECT_GT(largest, 0);
    std::vector<RigidBody> unmoved = scene.bodies;
    impulsesOnly.applyDisplacements(unmoved);
    for (std::size_t k = 0; k < unmoved.size(); ++k) EXPECT_EQ(unmoved[k].position, scene.bodies[k].position);
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

// A caller that solves most steps by another path (World's sparse path) hands the tree solver its
// guess: started from the dense answer's states it pivots not at all, however old its own last
// solve is, and its answer is the dense one.
TEST(TreeSolverWarmStart, AGuessFromTheCallerReplacesItsOwnStaleStates) {
    Scene scene(test::hungHumanoid());
    spin(scene, 3, 6);
    TreeSolver solver;
    solver.setStructure(scene.bodies, scene.joints);
    solver.factor(scene.rows, scene.ranges, scene.bodies);
    solver.solveVelocity(scene.rows, scene.bodies);  // the states of the first step: stale below
    TreeSolver stepper;
    stepper.setStructure(scene.bodies, scene.joints);
    for (int i = 0; i < 40; ++i) step(scene, stepper);
    scene.write();
    Dense dense;
    solveDense(scene, false, dense);
    ASSERT_EQ(dense.result.status, LcpStatus::Solved);
    ASSERT_GE(std::count(dense.states.begin(), dense.states.end(), LcpRowState::AtLower) +
                  std::count(dense.states.begin(), dense.states.end(), LcpRowState::AtUpper),
              5) << "rows at a bound, which a cold or stale start has to pivot to";

    solver.factor(scene.rows, scene.ranges, scene.bodies);
    const TreeSolveResult guessed = solver.solveVelocity(scene.rows, scene.bodies, dense.states, dense.lambda);
    EXPECT_EQ(guessed.status, LcpStatus::Solved);
    EXPECT_EQ(guessed.pivots, 0);
    const Real scale = std::max(Real(1), largest(dense.lambda));
    for (std::size_t i = 0; i < dense.lambda.size(); ++i)
        ASSERT_NEAR(solver.impulses()[i], dense.lambda[i], 1e-9 * scale) << "row " << i;

    TreeSolver stale;
    stale.setStructure(scene.bodies, scene.joints);
    stale.factor(scene.rows, scene.ranges, scene.bodies);
    EXPECT_GT(stale.solveVelocity(scene.rows, scene.bodies).pivots, 0) << "without the guess";

    const std::vector<LcpRowState> tooFew(dense.states.begin(), dense.states.end() - 1);
    EXPECT_THROW(solver.solveVelocity(scene.rows, scene.bodies, tooFew, dense.lambda), std::invalid_argument);
}

}  // namespace
}  // namespace af
