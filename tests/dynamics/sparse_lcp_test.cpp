// The sparse path (sparse_factor.h, sparse_lcp.h) against the dense exact one (RowSystem +
// LcpExactSolver) on the same rows: the factorisation of any free set against a dense LDLᵀ (and
// the entries of its inverse that friction coupling takes from it), and
// the LCP's impulses on figures with limits, joint friction, contacts with friction, loops and a
// second path to the world. Also that a held guess costs one trial, a guess one step on is
// refined without factorising, and that rows the
// factorisation cannot take are refused rather than solved wrongly.

#include "dynamics/solver_tuning.h"
#include "dynamics/sparse_lcp.h"
#include "row_scene_util.h"

#include <Eigen/Dense>

#include <cmath>

namespace af {
namespace {

using namespace test;

// The pivoting solver's settings as a world uses them (tolerance, frozen friction boxes).
const LcpExactSettings kSettings = SolverTuning{}.exact;

// What the sparse solver is given: the rows (friction held at 0 for the position problem, as
// World does), their responses and the problem's right-hand side and bounds.
struct Rows {
    ConstraintRows rows;
    RowSystem system;
    std::vector<RowResponse> responses;

    Rows(const Scene& scene, bool position) : rows(scene.rows) {
        if (position) holdFrictionAtZero(rows, scene.ranges);
        system.build(rows, scene.bodies);
        if (position) {
            system.setPositionRhs(rows);
        } else {
            system.setVelocityRhs(rows, scene.bodies);
        }
        for (std::size_t i = 0; i < rows.size(); ++i) responses.push_back(system.response(i));
    }
};

// ‖A_FF y − r‖∞ / (‖A_FF‖∞ ‖y‖∞) of the sparse solve of random right-hand sides on random free
// sets, against the same of Eigen's dense LDLᵀ (which rounding alone allows).
void expectFactorSolvesLikeDense(const Scene& scene, unsigned seed, const char* what) {
    SCOPED_TRACE(what);
    Rows in(scene, false);
    const std::size_t n = in.rows.size();
    const LcpProblem p = in.system.problem();
    SparseRowFactor factor;
    ASSERT_TRUE(factor.analyse(in.rows.all(), scene.bodies));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(-1, 1);
    Real worstSparse = 0, worstDense = 0;
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<std::uint8_t> free(n);
        std::vector<int> index;
        for (std::size_t i = 0; i < n; ++i) {
            free[i] = trial == 0 || u(rng) < 0.4 ? 1 : 0;
            if (free[i]) index.push_back(static_cast<int>(i));
        }
        const Eigen::Index m = static_cast<Eigen::Index>(index.size());
        Eigen::MatrixXd a(m, m);
        Eigen::VectorXd r(m);
        for (Eigen::Index i = 0; i < m; ++i) {
            const std::size_t ri = static_cast<std::size_t>(index[static_cast<std::size_t>(i)]);
            r(i) = u(rng);
            for (Eigen::Index j = 0; j < m; ++j) a(i, j) = p.a[ri * n + static_cast<std::size_t>(index[static_cast<std::size_t>(j)])];
            a(i, i) += p.cfm[ri];
        }
        ASSERT_TRUE(factor.factor(in.rows.all(), in.responses, p.cfm, free));
        std::vector<Real> x(n, 7.0);
        for (Eigen::Index i = 0; i < m; ++i) x[static_cast<std::size_t>(index[static_cast<std::size_t>(i)])] = r(i);
        factor.solve(x);
        Eigen::VectorXd y(m);
        for (Eigen::Index i = 0; i < m; ++i) y(i) = x[static_cast<std::size_t>(index[static_cast<std::size_t>(i)])];
        for (std::size_t i = 0; i < n; ++i) {
            if (free[i]) continue;
            EXPECT_EQ(x[i], 7.0) << "a row outside the free set was written";
        }
        const Eigen::VectorXd dense = a.ldlt().solve(r);
        const Real norm = a.cwiseAbs().rowwise().sum().maxCoeff();
        worstSparse = std::max(worstSparse, (a * y - r).lpNorm<Eigen::Infinity>() / (norm * y.lpNorm<Eigen::Infinity>()));
        worstDense = std::max(worstDense, (a * dense - r).lpNorm<Eigen::Infinity>() / (norm * dense.lpNorm<Eigen::Infinity>()));
    }
    std::printf("sparse factor, %s (%zu rows): relative residual %.2g (dense LDLT %.2g)\n", what, n, worstSparse, worstDense);
    EXPECT_LE(worstSparse, std::max(Real(1e-14), 100 * worstDense));
}

TEST(SparseRowFactor, SolvesAnyFreeSetAsADenseFactorisationDoes) {
    TreeSolver tree;
    Scene loops(loopFigure());
    spin(loops, 7, 3);
    tree.setStructure(loops.bodies, loops.joints);
    for (int i = 0; i < 5; ++i) step(loops, tree);
    loops.write();
    expectFactorSolvesLikeDense(loops, 1, "loops and a second path to the world");
    TreeSolver chainTree, humanoidTree;
    expectFactorSolvesLikeDense(freeChainOnTheGround(chainTree), 2, "free chain on the ground");
    expectFactorSolvesLikeDense(humanoidWithContacts(humanoidTree), 3, "humanoid with contacts");
}

// The sliding friction rows' coupling (sparse_lcp.cpp) takes entries of A_FF⁻¹ as products of
// forwarded vectors over the groups both reach: the column A_F,j of a row outside F and a free
// row's unit vector e_i give (A_FF⁻¹ A_F,j)_i, two such columns A_j,F A_FF⁻¹ A_F,k; against the
// dense solve.
TEST(SparseRowFactor, ScaledDotsOfForwardedVectorsAreEntriesOfTheInverse) {
    TreeSolver tree;
    const Scene scene = humanoidWithContacts(tree);
    Rows in(scene, false);
    const std::size_t n = in.rows.size();
    const LcpProblem p = in.system.problem();
    SparseRowFactor factor;
    ASSERT_TRUE(factor.analyse(in.rows.all(), scene.bodies));
    std::mt19937 rng(5);
    std::uniform_real_distribution<Real> u(0, 1);
    std::vector<std::uint8_t> free(n);
    std::vector<int> index, outside;
    for (std::size_t i = 0; i < n; ++i) {
        free[i] = u(rng) < 0.7 ? 1 : 0;
        (free[i] ? index : outside).push_back(static_cast<int>(i));
    }
    ASSERT_FALSE(outside.empty());
    ASSERT_TRUE(factor.factor(in.rows.all(), in.responses, p.cfm, free));
    const Eigen::Index m = static_cast<Eigen::Index>(index.size());
    Eigen::MatrixXd a(m, m), columns(m, static_cast<Eigen::Index>(n));
    for (Eigen::Index i = 0; i < m; ++i) {
        const std::size_t ri = static_cast<std::size_t>(index[static_cast<std::size_t>(i)]);
        for (Eigen::Index j = 0; j < m; ++j) a(i, j) = p.a[ri * n + static_cast<std::size_t>(index[static_cast<std::size_t>(j)])];
        a(i, i) += p.cfm[ri];
        for (std::size_t j = 0; j < n; ++j) columns(i, static_cast<Eigen::Index>(j)) = p.a[ri * n + j];
    }
    const Eigen::MatrixXd solved = a.ldlt().solve(columns);  // A_FF⁻¹ A_F,j for every row j
    const std::size_t vars = static_cast<std::size_t>(factor.variables()), groups = static_cast<std::size_t>(factor.groups());
    std::vector<Real> y1(vars), y2(vars);
    std::vector<std::uint8_t> r1(groups), r2(groups);
    std::vector<int> s1, s2;
    Real worst = 0, scale = 0;
    int checked = 0;
    for (int pair = 0; pair < 60; ++pair) {
        auto pick = [&] { return static_cast<std::size_t>(outside[static_cast<std::size_t>(u(rng) * static_cast<Real>(outside.size()))]); };
        const std::size_t j = pick(), k = pick();
        const Eigen::Index i = static_cast<Eigen::Index>(u(rng) * static_cast<Real>(m));
        factor.column(static_cast<int>(j), in.rows.all(), in.responses, y1, r1);
        factor.forward(y1, r1);
        s1.clear();
        factor.support(r1, s1);
        const bool unit = pair % 2 == 0;
        if (unit) {
            factor.unit(index[static_cast<std::size_t>(i)], y2, r2);
        } else {
            factor.column(static_cast<int>(k), in.rows.all(), in.responses, y2, r2);
        }
        factor.forward(y2, r2);
        s2.clear();
        factor.support(r2, s2);
        const Real sparse = factor.scaledDot(y2, s2, y1, s1);
        const Real dense = unit ? solved(i, static_cast<Eigen::Index>(j))
                                : columns.col(static_cast<Eigen::Index>(k)).dot(solved.col(static_cast<Eigen::Index>(j)));
        worst = std::max(worst, std::abs(sparse - dense));
        scale = std::max(scale, std::abs(dense));
        ++checked;
    }
    EXPECT_EQ(checked, 60);
    EXPECT_GT(scale, 0);
    EXPECT_LE(worst, 1e-9 * scale);
}

// Contacts that touch without pushing (all their rows clamped) couple nothing: a chain whose
// links all touch each other that way (a chain lying in a heap) factorises as small as the bare
// chain, although those contacts close loops everywhere.
TEST(SparseRowFactor, LoopsClosedOnlyByRowsThatAreNotFreeCostNoFill) {
    auto entries = [](const Scene& s, std::size_t freeRows) {
        Rows in(s, false);
        std::vector<std::uint8_t> free(in.rows.size(), 0);
        std::fill(free.begin(), free.begin() + static_cast<std::ptrdiff_t>(freeRows), 1);
        SparseRowFactor factor;
        EXPECT_TRUE(factor.analyse(in.rows.all(), s.bodies));
        EXPECT_TRUE(factor.factor(in.rows.all(), in.responses, in.system.problem().cfm, free));
        return factor.entries();
    };
    Scene chain(test::horizontalChain(12, 0, true));
    chain.write();
    const std::size_t jointRows = chain.rows.size();
    const std::size_t bare = entries(chain, jointRows);
    for (int a = 0; a < 12; ++a)
        for (int b = a + 2; b < 12; ++b) {
            Contact c;
            c.bodyA = a;
            c.bodyB = b;
            c.point = (chain.bodies[static_cast<std::size_t>(a)].position + chain.bodies[static_cast<std::size_t>(b)].position) / 2;
            c.normal = Vec3::UnitZ();
            c.friction = 0.5;
            chain.contacts.push_back(c);
        }
    chain.write();
    const std::size_t touching = entries(chain, jointRows), pushing = entries(chain, chain.rows.size());
    std::printf("sparse factor, chain of 12: %zu entries bare, %zu with all links touching, %zu with them pushing\n",
                bare, touching, pushing);
    EXPECT_EQ(touching, bare);
    EXPECT_GT(pushing, 2 * bare);  // the loops, when they push, do cost fill
}

struct SparseRun {
    SparseLcpResult result;
    std::vector<Real> lambda;
    std::vector<LcpRowState> states;
};

// The sparse solve of a scene's velocity or position problem, from the states `guess` (all
// unknown if empty).
SparseRun solveSparse(const Scene& scene, bool position, std::span<const LcpRowState> guess = {}) {
    Rows in(scene, position);
    SparseRun run;
    run.lambda.assign(in.rows.size(), 0);
    run.states.assign(in.rows.size(), LcpRowState::Unknown);
    std::copy(guess.begin(), guess.end(), run.states.begin());
    SparseLcpSolver solver;
    run.result = solver.solve(in.rows.all(), in.responses, in.system.problem(), scene.bodies, run.lambda, run.states, kSettings);
    return run;
}

// A solved sparse answer against the dense one: the bodies' velocity change (or move) M⁻¹Jᵀλ,
// which is unique, within 1e-9 of the largest; and the dense problem's natural residual at the
// sparse λ within 1e-9 of the largest impulse. (λ itself need not be unique where rows are
// redundant up to their CFM.) Returns the relative velocity difference.
Real expectSameAsDense(const Scene& scene, bool position, const SparseRun& sparse, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_EQ(sparse.result.status, LcpStatus::Solved) << sparse.result.trials << " trials";
    if (sparse.result.status != LcpStatus::Solved) return kInfinity;
    Dense dense;
    solveDense(scene, position, dense);
    EXPECT_EQ(dense.result.status, LcpStatus::Solved);
    Rows in(scene, position);
    const std::size_t bodies = scene.bodies.size();
    std::vector<Vec3> linear(bodies), angular(bodies), denseLinear(bodies), denseAngular(bodies);
    accumulateResponses(in.rows.all(), in.responses, sparse.lambda, linear, angular);
    accumulateResponses(in.rows.all(), in.responses, dense.lambda, denseLinear, denseAngular);
    Real scale = 1, worst = 0;
    for (std::size_t k = 0; k < bodies; ++k) scale = std::max({scale, denseLinear[k].norm(), denseAngular[k].norm()});
    for (std::size_t k = 0; k < bodies; ++k)
        worst = std::max({worst, (linear[k] - denseLinear[k]).norm(), (angular[k] - denseAngular[k]).norm()});
    EXPECT_LE(worst, 1e-9 * scale);
    const Real lambdaScale = std::max(Real(1), largest(dense.lambda));
    EXPECT_LE(sparse.result.residual, 1e-9 * lambdaScale);
    EXPECT_LE(lcpResidual(dense.system.problem(), sparse.lambda), 1e-9 * lambdaScale);
    return worst / scale;
}

void reportSparseAgreement(const char* what, const Scene& scene, Real velocity, Real position) {
    std::printf("sparse vs dense, %s (%zu rows): max |Δv_sparse − Δv_dense| / max |Δv|: velocity %.2g, position %.2g\n",
                what, scene.rows.size(), velocity, position);
}

// The shaken humanoid's steps, limits engaging and joint friction slipping, each solve guessed
// from the previous step's answer as World does (here by row index, while the rows stay the
// same): the answers agree with the dense solve. Where the guess's pattern does not hold, the
// rows its trial found wrong are solved as a dense core, which settles in one round as a rule
// (without the core 3 of the 120 solves gave up).
TEST(SparseLcp, ShakenHumanoidWithLimitsAndJointFrictionMatchesTheDenseSolve) {
    Scene scene(hungHumanoid());
    spin(scene, 3, 6);
    TreeSolver tree;
    tree.setStructure(scene.bodies, scene.joints);
    Real velocity = 0, position = 0;
    int withLimits = 0, gaveUp = 0, cores = 0, coreRounds = 0;
    const int steps = 60;
    SparseRun lastVelocity, lastPosition;
    for (int i = 0; i < steps; ++i) {
        step(scene, tree);
        scene.write();
        if (scene.count(&JointRowRange::limitRows) >= 4) ++withLimits;
        const std::string at = ", step " + std::to_string(i);
        for (const bool isPosition : {false, true}) {
            SparseRun& last = isPosition ? lastPosition : lastVelocity;
            const bool same = last.states.size() == scene.rows.size();
            SparseRun run = solveSparse(scene, isPosition, same ? std::span<const LcpRowState>(last.states) : std::span<const LcpRowState>());
            if (run.result.coreRows > 0) ++cores;
            coreRounds += run.result.coreRounds;
            if (run.result.status != LcpStatus::Solved) {
                ++gaveUp;
                last = {};
                continue;
            }
            Real& worst = isPosition ? position : velocity;
            worst = std::max(worst, expectSameAsDense(scene, isPosition, run, (isPosition ? "position" : "velocity") + at));
            last = std::move(run);
        }
    }
    reportSparseAgreement("shaken humanoid, 60 steps", scene, velocity, position);
    std::printf("sparse, shaken humanoid: %d dense cores in %d rounds, %d of %d solves gave up\n", cores, coreRounds,
                gaveUp, 2 * steps);
    EXPECT_GE(withLimits, 8) << "poses with at least 4 limit rows";
    EXPECT_GE(cores, 1);
    EXPECT_EQ(gaveUp, 0);
    EXPECT_LE(coreRounds, cores + cores / 4) << "a core settles in one round as a rule";
}

// Joint friction rows guessed at the wrong bound, as the jumps of their bounds (f·|λ| of the
// joint's previous impulse) from step to step leave them: the trial finds them wrong, and the
// core takes all of them at once rather than a few per round, so one core round settles them,
// with the dense answer.
TEST(SparseLcp, JointFrictionRowsGuessedWrongAreSettledInOneCoreRound) {
    TreeSolver tree;
    const Scene scene = humanoidWithContacts(tree);
    Dense dense;
    solveDense(scene, false, dense);
    ASSERT_EQ(dense.result.status, LcpStatus::Solved);
    std::vector<LcpRowState> guess = dense.states;
    int jointFriction = 0, wrongSide = 0;
    for (std::size_t i = 0; i < scene.rows.size(); ++i) {
        const ConstraintRow& r = scene.rows[i];
        if (r.frictionSource >= 0 || !std::isfinite(r.lo) || !std::isfinite(r.hi) || !(r.lo < r.hi)) continue;
        ++jointFriction;
        if (dense.states[i] != LcpRowState::Free) ++wrongSide;
        guess[i] = dense.states[i] == LcpRowState::AtUpper ? LcpRowState::AtLower : LcpRowState::AtUpper;
    }
    ASSERT_GE(jointFriction, 20);
    EXPECT_GE(wrongSide, 3) << "rows sent to the other bound, not only sticking ones to a bound";
    const SparseRun run = solveSparse(scene, false, guess);
    expectSameAsDense(scene, false, run, "joint friction guessed at the wrong bound");
    std::printf("sparse, joint friction guessed wrong: %d joint friction rows (%d at a bound), %d trials, core of %d "
                "rows in %d rounds\n",
                jointFriction, wrongSide, run.result.trials, run.result.coreRows, run.result.coreRounds);
    EXPECT_GE(run.result.coreRows, jointFriction);
    EXPECT_EQ(run.result.coreRounds, 1);
}

// Contacts that all arrive at once, pushing and sliding: the sparse solve is meant for guesses
// close to the answer (the previous step's), so from the dense answer's pattern it settles at
// once and agrees; cold it may give up (the caller then pivots), which is reported.
void expectSameAsDenseFromItsPattern(const char* what, const Scene& scene) {
    Real velocity = 0, position = 0;
    for (const bool isPosition : {false, true}) {
        Dense dense;
        solveDense(scene, isPosition, dense);
        const SparseRun warm = solveSparse(scene, isPosition, dense.states);
        EXPECT_EQ(warm.result.coreRows, 0) << what << ": the dense answer's own pattern holds without a core";
        (isPosition ? position : velocity) = expectSameAsDense(scene, isPosition, warm, what);
        const SparseRun cold = solveSparse(scene, isPosition);
        std::printf("sparse, %s, %s: from the dense pattern %d trials, cold %d trials (%s)\n", what,
                    isPosition ? "position" : "velocity", warm.result.trials, cold.result.trials, toString(cold.result.status));
        if (cold.result.status == LcpStatus::Solved) expectSameAsDense(scene, isPosition, cold, std::string(what) + ", cold");
    }
    reportSparseAgreement(what, scene, velocity, position);
}

TEST(SparseLcp, ContactsWithFrictionLoopsAndChainsMatchTheDenseSolve) {
    TreeSolver chainTree, humanoidTree, loopTree;
    expectSameAsDenseFromItsPattern("free chain on the ground", freeChainOnTheGround(chainTree));
    expectSameAsDenseFromItsPattern("humanoid with contacts", humanoidWithContacts(humanoidTree));
    Scene loops(loopFigure());
    spin(loops, 7, 3);
    loopTree.setStructure(loops.bodies, loops.joints);
    for (int i = 0; i < 20; ++i) step(loops, loopTree);
    loops.write();
    expectSameAsDenseFromItsPattern("loops", loops);
}

// The answer's own states as the guess: nothing to correct, one factorisation.
TEST(SparseLcp, AGuessThatHoldsCostsOneTrial) {
    TreeSolver tree;
    const Scene scene = humanoidWithContacts(tree);
    Dense dense;
    solveDense(scene, false, dense);
    const SparseRun first = solveSparse(scene, false, dense.states);
    ASSERT_EQ(first.result.status, LcpStatus::Solved);
    const SparseRun again = solveSparse(scene, false, first.states);
    EXPECT_EQ(again.result.status, LcpStatus::Solved);
    EXPECT_EQ(again.result.trials, 1);
    EXPECT_EQ(again.result.factorisations, 1);
    EXPECT_GT(again.result.couplingSolves, 0) << "some contacts slide";
}

// The humanoid with contacts' velocity problem and one sparse solver kept across solves, as an
// island keeps its own from step to step.
struct HumanoidSolves {
    TreeSolver tree;
    Scene scene = humanoidWithContacts(tree);
    Rows in{scene, false};
    LcpProblem problem = in.system.problem();
    SparseLcpSolver solver;
    std::vector<Real> x = std::vector<Real>(in.rows.size(), 0);
    std::vector<LcpRowState> states = std::vector<LcpRowState>(in.rows.size(), LcpRowState::Unknown);

    SparseLcpResult solve() { return solver.solve(in.rows.all(), in.responses, problem, scene.bodies, x, states, kSettings); }
};

// The answer itself as the next guess (a figure at rest meets its last problem again): it holds
// as it is, nothing is factorised and the impulses stay. A right-hand side moved by more than
// the tolerance is solved again.
TEST(SparseLcp, AnAnswerThatStillHoldsIsKeptWithoutFactorising) {
    HumanoidSolves h;
    ASSERT_EQ(h.solve().status, LcpStatus::Solved);
    const std::vector<Real> answer = h.x;
    const SparseLcpResult held = h.solve();
    EXPECT_EQ(held.status, LcpStatus::Solved);
    EXPECT_EQ(held.trials, 0);
    EXPECT_EQ(held.factorisations, 0);
    EXPECT_EQ(h.x, answer);

    std::vector<Real> moved(h.problem.b.begin(), h.problem.b.end());
    for (Real& b : moved) b += 1e-6;
    h.problem.b = moved;
    const SparseLcpResult again = h.solve();
    EXPECT_EQ(again.status, LcpStatus::Solved);
    EXPECT_GE(again.trials, 1);
    EXPECT_NE(h.x, answer);
}

// A guess in the last answer's pattern whose right-hand side has moved a little (a resting
// figure one step on: b = −J v moves with the bodies' velocities) is refined with the last
// factorisation, sliding friction's coupling included: nothing is factorised, and the answer is
// a fresh solve's. (The redundant contacts' impulses are fixed only by the CFM; a move of b
// outside J's range would shift them along that near-null space, far and in any pattern.)
// b = target − J v as it moves when every body's velocities move by up to 1e-9 at random.
void nudgeVelocities(std::span<const ConstraintRow> rows, std::size_t bodies, std::mt19937& rng, std::vector<Real>& b) {
    std::uniform_real_distribution<Real> u(-1, 1);
    std::vector<Vec3> dv(bodies), dw(bodies);
    for (std::size_t k = 0; k < bodies; ++k) {
        dv[k] = 1e-9 * Vec3(u(rng), u(rng), u(rng));
        dw[k] = 1e-9 * Vec3(u(rng), u(rng), u(rng));
    }
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const ConstraintRow& r = rows[i];
        const auto a = static_cast<std::size_t>(r.bodyA);
        b[i] -= r.linearA.dot(dv[a]) + r.angularA.dot(dw[a]);
        if (r.bodyB == kWorldBody) continue;
        const auto c = static_cast<std::size_t>(r.bodyB);
        b[i] -= r.linearB.dot(dv[c]) + r.angularB.dot(dw[c]);
    }
}

TEST(SparseLcp, AGuessInTheLastAnswersPatternIsRefinedWithoutFactorising) {
    HumanoidSolves h;
    ASSERT_EQ(h.solve().status, LcpStatus::Solved);
    std::fill(h.x.begin(), h.x.end(), 0);  // solved again from its pattern alone: by one trial
    const SparseLcpResult first = h.solve();
    ASSERT_EQ(first.status, LcpStatus::Solved);
    ASSERT_EQ(first.trials, 1);
    ASSERT_GT(first.couplingSolves, 0) << "some contacts slide";
    const std::vector<LcpRowState> pattern = h.states;

    std::vector<Real> moved(h.problem.b.begin(), h.problem.b.end());
    std::mt19937 rng(7);
    nudgeVelocities(h.in.rows.all(), h.scene.bodies.size(), rng, moved);
    h.problem.b = moved;
    const SparseLcpResult refined = h.solve();
    ASSERT_EQ(refined.status, LcpStatus::Solved);
    EXPECT_TRUE(refined.refined);
    EXPECT_EQ(refined.trials, 0);
    EXPECT_EQ(refined.factorisations, 0);
    EXPECT_EQ(h.states, pattern);

    HumanoidSolves fresh;
    fresh.problem.b = moved;
    ASSERT_EQ(fresh.solve().status, LcpStatus::Solved);
    const std::vector<Real>& x = h.x;
    const std::vector<Real>& expected = fresh.x;
    Real largest = 0, worst = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        largest = std::max(largest, std::abs(expected[i]));
        worst = std::max(worst, std::abs(x[i] - expected[i]));
    }
    EXPECT_LE(worst, 1e-9 * largest);
}

// Three rows of one joint that repeat each other and carry no CFM: no pivot for the third.
// A figure resting for several steps refines each one from the last (its sliding rows' answers
// kept with the factorisation from the first): every answer is the fresh solve's.
TEST(SparseLcp, StepAfterStepTheRefinedAnswersAreTheFreshOnes) {
    HumanoidSolves h;
    ASSERT_EQ(h.solve().status, LcpStatus::Solved);
    std::fill(h.x.begin(), h.x.end(), 0);  // solved again from its pattern alone: by one trial
    const SparseLcpResult first = h.solve();
    ASSERT_EQ(first.trials, 1);
    ASSERT_GT(first.couplingSolves, 0) << "some contacts slide";
    std::mt19937 rng(11);
    std::vector<Real> b(h.problem.b.begin(), h.problem.b.end());
    for (int step = 0; step < 4; ++step) {
        nudgeVelocities(h.in.rows.all(), h.scene.bodies.size(), rng, b);
        h.problem.b = b;
        const SparseLcpResult refined = h.solve();
        ASSERT_EQ(refined.status, LcpStatus::Solved);
        EXPECT_TRUE(refined.refined) << "step " << step;
        HumanoidSolves fresh;
        fresh.problem.b = b;
        ASSERT_EQ(fresh.solve().status, LcpStatus::Solved);
        Real largest = 0, worst = 0;
        for (std::size_t i = 0; i < b.size(); ++i) {
            largest = std::max(largest, std::abs(fresh.x[i]));
            worst = std::max(worst, std::abs(h.x[i] - fresh.x[i]));
        }
        EXPECT_LE(worst, 1e-9 * largest) << "step " << step;
    }
}

// A guess in the last answer's pattern whose rows at a bound have drifted off them (sliding rows
// off ±μ times their normals) is put back on them and refined: its free rows then follow that
// move, and the answer is the last one.
TEST(SparseLcp, AGuessOffItsBoundsIsPutBackOnThemAndRefined) {
    HumanoidSolves h;
    ASSERT_EQ(h.solve().status, LcpStatus::Solved);
    std::fill(h.x.begin(), h.x.end(), 0);  // solved again from its pattern alone: by one trial
    ASSERT_EQ(h.solve().status, LcpStatus::Solved);
    const std::vector<Real> answer = h.x;
    const std::vector<LcpRowState> pattern = h.states;
    int off = 0;
    for (std::size_t i = 0; i < h.x.size(); ++i) {
        if (h.states[i] == LcpRowState::Free) continue;
        h.x[i] += 1e-6 * (1 + std::abs(h.x[i]));
        ++off;
    }
    ASSERT_GT(off, 10);
    const SparseLcpResult refined = h.solve();
    ASSERT_EQ(refined.status, LcpStatus::Solved);
    EXPECT_TRUE(refined.refined);
    EXPECT_EQ(refined.factorisations, 0);
    EXPECT_EQ(h.states, pattern);
    Real largest = 0, worst = 0;
    for (std::size_t i = 0; i < answer.size(); ++i) {
        largest = std::max(largest, std::abs(answer[i]));
        worst = std::max(worst, std::abs(h.x[i] - answer[i]));
    }
    EXPECT_LE(worst, 1e-9 * largest);
}

// An island applies an answer through the velocity change the solver summed when it checked it:
// bit for bit the sum of its impulses, whether a trial, the held guess or a refinement found it.
TEST(SparseLcp, TheAnswersVelocityChangeIsTheSumOfItsImpulses) {
    HumanoidSolves h;
    const auto expectSum = [&](const char* path) {
        std::vector<Vec3> linear(h.scene.bodies.size()), angular(h.scene.bodies.size());
        accumulateResponses(h.in.rows.all(), h.in.responses, h.x, linear, angular);
        const std::span<const Vec3> solverLinear = h.solver.answerLinearChange();
        const std::span<const Vec3> solverAngular = h.solver.answerAngularChange();
        EXPECT_TRUE(std::equal(linear.begin(), linear.end(), solverLinear.begin(), solverLinear.end())) << path;
        EXPECT_TRUE(std::equal(angular.begin(), angular.end(), solverAngular.begin(), solverAngular.end())) << path;
    };
    ASSERT_EQ(h.solve().status, LcpStatus::Solved);
    expectSum("first solve");
    std::fill(h.x.begin(), h.x.end(), 0);  // solved again from its pattern alone: by one trial
    ASSERT_EQ(h.solve().trials, 1);
    expectSum("one trial");
    ASSERT_EQ(h.solve().trials, 0);
    expectSum("held guess");
    std::vector<Real> moved(h.problem.b.begin(), h.problem.b.end());
    std::mt19937 rng(3);
    nudgeVelocities(h.in.rows.all(), h.scene.bodies.size(), rng, moved);
    h.problem.b = moved;
    ASSERT_TRUE(h.solve().refined);
    expectSum("refined");
    // No rows (a body in flight): nothing changes, whatever the last solve left.
    ASSERT_EQ(h.solver.solve({}, {}, h.problem, h.scene.bodies, {}, {}, kSettings).status, LcpStatus::Solved);
    for (const std::span<const Vec3> change : {h.solver.answerLinearChange(), h.solver.answerAngularChange()}) {
        ASSERT_EQ(change.size(), h.scene.bodies.size());
        for (const Vec3& v : change) EXPECT_EQ(v, Vec3::Zero());
    }
}

TEST(SparseLcp, DependentRowsWithoutCfmAreRefused) {
    const std::vector<RigidBody> bodies = {RigidBody::dynamic(2, Mat3::Identity(), Vec3(0, 0, -5), Quat::Identity())};
    const ConstraintRows rows = dependentRows();
    RowSystem system;
    system.build(rows, bodies);
    system.setVelocityRhs(rows, bodies);
    std::vector<RowResponse> responses;
    for (std::size_t i = 0; i < rows.size(); ++i) responses.push_back(system.response(i));
    std::vector<Real> x(3, 0);
    std::vector<LcpRowState> states(3, LcpRowState::Unknown);
    SparseLcpSolver solver;
    EXPECT_EQ(solver.solve(rows.all(), responses, system.problem(), bodies, x, states, kSettings).status, LcpStatus::Unsatisfiable);
}

}  // namespace
}  // namespace af
