// SHAKE's Newton step (shake.h) against the same step solved densely: K = J₁ M⁻¹ J₀ᵀ built
// entry by entry from the rows and solved by a fully pivoted LU. SHAKE factorises K along the
// joints' tree (with fill for loops, block by block for unconnected figures); the answer must be
// the same up to rounding.

#include "dynamics/row_system.h"
#include "dynamics/shake.h"
#include "scene_test_util.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>

namespace af {
namespace {

constexpr Real kDt = Real(1) / 60;

struct Figures {
    std::vector<RigidBody> bodies;
    std::vector<Joint> joints;

    // Appends the figure's bodies and joints, its joints renumbered after the bodies before.
    void add(const Figure& figure) {
        const int offset = static_cast<int>(bodies.size());
        for (const FigureBody& b : figure.bodies)
            bodies.push_back(RigidBody::dynamic(b.mass, b.inertia, b.pose.position, Quat(b.pose.rotation)));
        for (Joint j : makeJoints(figure)) {
            if (j.bodyA != kWorldBody) j.bodyA += offset;
            if (j.bodyB != kWorldBody) j.bodyB += offset;
            joints.push_back(j);
        }
    }
    void write(std::span<const RigidBody> at, ConstraintRows& rows, std::vector<JointRowRange>& ranges) const {
        rows.clear();
        ranges.clear();
        for (const Joint& j : joints) ranges.push_back(writeJointRows(j, at, JointRowSettings{}, rows));
    }
};

// Four bars in a square, each joined to the next by a ball joint, the last closing the loop.
Figure square() {
    using test::boxBodyText;
    const Vec3 across(5, 1, 1), down(1, 1, 5);
    return test::figureOfBlocks(
        {"origin", "j1", "j2", "j3"},
        boxBodyText("b0", "origin", across, Vec3(5, 0, 0), 0.2) + boxBodyText("b1", "j1", down, Vec3(10, 0, -5), 0.2) +
            boxBodyText("b2", "j2", across, Vec3(5, 0, -10), 0.2) + boxBodyText("b3", "j3", down, Vec3(0, 0, -5), 0.2) +
            "ballAndSocketJoint \"j1\" { body1 \"b1\" body2 \"b0\" anchor ( 10, 0, 0 ) friction 0 }\n"
            "ballAndSocketJoint \"j2\" { body1 \"b2\" body2 \"b1\" anchor ( 10, 0, -10 ) friction 0 }\n"
            "ballAndSocketJoint \"j3\" { body1 \"b3\" body2 \"b2\" anchor ( 0, 0, -10 ) friction 0 }\n"
            "ballAndSocketJoint \"loop\" { body1 \"b0\" body2 \"b3\" anchor ( 0, 0, 0 ) friction 0 }\n");
}

void spin(std::vector<RigidBody>& bodies, unsigned seed, Real speed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(-speed, speed);
    for (RigidBody& b : bodies) {
        b.linearVelocity = Vec3(u(rng), u(rng), u(rng)) * 10;
        b.angularVelocity = Vec3(u(rng), u(rng), u(rng));
    }
}

// One step: rows captured at the start poses, the bodies moved along their velocities (the joints
// open by O(dt²)), rows written again. Then SHAKE's first Newton step, and the dense one.
struct Drifted {
    std::vector<RigidBody> start, moved, shaken, dense;
    ShakeCorrection::Step step;
    Real driftBefore = 0, driftAfter = 0;
};

Real largestDrift(const ConstraintRows& start, const ConstraintRows& now, const std::vector<JointRowRange>& ranges) {
    Real worst = 0;
    for (const JointRowRange& r : ranges)
        for (int i = r.first; i < r.first + r.equalityRows; ++i)
            worst = std::max(worst, std::abs(now[static_cast<std::size_t>(i)].error - start[static_cast<std::size_t>(i)].error));
    return worst;
}

Drifted drift(const Figures& figures, unsigned seed, Real speed, ShakeCorrection& shake) {
    Drifted d;
    d.start = figures.bodies;
    spin(d.start, seed, speed);
    ConstraintRows rows0, rows1, rows2;
    std::vector<JointRowRange> ranges0, ranges1, ranges2;
    figures.write(d.start, rows0, ranges0);
    RowSystem system;
    system.buildResponses(rows0, d.start);
    shake.capture(rows0, ranges0, system);

    d.moved = d.start;
    for (RigidBody& b : d.moved) integratePosition(b, kDt);
    figures.write(d.moved, rows1, ranges1);
    d.driftBefore = largestDrift(rows0, rows1, ranges1);
    d.shaken = d.moved;
    d.step = shake.apply(rows1, ranges1, d.shaken, kDt, 0);
    figures.write(d.shaken, rows2, ranges2);
    d.driftAfter = largestDrift(rows0, rows2, ranges2);

    // Dense: K_pq = Σ over bodies of J₁_p's block times the response of start row q on it.
    std::vector<int> captured;
    for (const JointRowRange& r : ranges0)
        for (int i = r.first; i < r.first + r.equalityRows; ++i) captured.push_back(i);
    const Eigen::Index n = static_cast<Eigen::Index>(captured.size());
    Eigen::MatrixXd k(n, n);
    Eigen::VectorXd rhs(n);
    auto blockOf = [](const ConstraintRow& row, int body, Eigen::Matrix<Real, 6, 1>& out) {
        out.setZero();
        if (body == kWorldBody) return;
        if (row.bodyA == body) out << row.linearA, row.angularA;
        if (row.bodyB == body) out += (Eigen::Matrix<Real, 6, 1>() << row.linearB, row.angularB).finished();
    };
    std::vector<ConstraintRow> startRows;
    std::vector<RowResponse> responses;
    for (Eigen::Index p = 0; p < n; ++p) {
        const std::size_t row = static_cast<std::size_t>(captured[static_cast<std::size_t>(p)]);
        startRows.push_back(rows0[row]);
        responses.push_back(system.response(row));
        rhs[p] = -(rows1[row].error - rows0[row].error);
    }
    for (Eigen::Index p = 0; p < n; ++p)
        for (Eigen::Index q = 0; q < n; ++q) {
            const ConstraintRow& now = rows1[static_cast<std::size_t>(captured[static_cast<std::size_t>(p)])];
            const ConstraintRow& s = startRows[static_cast<std::size_t>(q)];
            const RowResponse& m = responses[static_cast<std::size_t>(q)];
            Eigen::Matrix<Real, 6, 1> j, r;
            Real sum = 0;
            for (int body = 0; body < static_cast<int>(figures.bodies.size()); ++body) {
                blockOf(now, body, j);
                r.setZero();
                if (s.bodyA == body) r << m.linearA, m.angularA;
                if (s.bodyB == body) r += (Eigen::Matrix<Real, 6, 1>() << m.linearB, m.angularB).finished();
                sum += j.dot(r);
            }
            k(p, q) = sum;
        }
    const Eigen::VectorXd lambda = k.fullPivLu().solve(rhs);
    std::vector<Vec3> linear(figures.bodies.size()), angular(figures.bodies.size());
    accumulateResponses(startRows, responses, std::span<const Real>(lambda.data(), static_cast<std::size_t>(n)), linear,
                        angular);
    d.dense = d.moved;
    for (std::size_t b = 0; b < d.dense.size(); ++b) {
        displaceBody(d.dense[b], linear[b], angular[b]);
        d.dense[b].linearVelocity += linear[b] / kDt;
        d.dense[b].angularVelocity += angular[b] / kDt;
    }
    return d;
}

// Positions to 1e-9 units, orientations to 1e-12, velocities (move / dt) to 1e-7.
void expectSameBodies(const std::vector<RigidBody>& a, const std::vector<RigidBody>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        SCOPED_TRACE("body " + std::to_string(i));
        EXPECT_LT((a[i].position - b[i].position).norm(), 1e-9);
        EXPECT_LT((a[i].orientation.coeffs() - b[i].orientation.coeffs()).norm(), 1e-12);
        EXPECT_LT((a[i].linearVelocity - b[i].linearVelocity).norm(), 1e-7);
        EXPECT_LT((a[i].angularVelocity - b[i].angularVelocity).norm(), 1e-7);
    }
}

void expectDenseStep(const Figures& figures, Real speed) {
    ShakeCorrection shake;
    for (unsigned seed = 1; seed <= 4; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const Drifted d = drift(figures, seed, speed, shake);
        EXPECT_GT(d.driftBefore, 1e-4);
        EXPECT_LT(d.driftAfter, 0.1 * d.driftBefore);  // what World asks of it (measured 1.5-2.5%)
        EXPECT_GT(d.step.move, 0);
        expectSameBodies(d.shaken, d.dense);
    }
}

TEST(Shake, HungHumanoidStepIsTheDenseOne) {
    Figures f;
    f.add(test::hungHumanoid());
    expectDenseStep(f, 1);
}

TEST(Shake, FreeChainStepIsTheDenseOne) {
    Figures f;
    f.add(test::horizontalChain(12, 0, true));
    expectDenseStep(f, 1);
}

TEST(Shake, LoopStepIsTheDenseOne) {
    Figures f;
    f.add(square());
    expectDenseStep(f, 1);
}

// Two figures that share no body: two blocks, and a loop among tree joints.
TEST(Shake, SeparateFiguresStepIsTheDenseOne) {
    Figures f;
    f.add(test::horizontalChain(5, 0, false));
    f.add(square());
    f.add(test::hungHumanoid());
    expectDenseStep(f, 1);
}

// The drift measured from the joints' errors alone (what a step tests before writing any rows)
// is the drift of the rows written at the moved poses, bit for bit, and the one apply closes.
TEST(Shake, DriftFromErrorsAloneIsTheDriftOfWrittenRows) {
    Figures f;
    f.add(test::hungHumanoid());
    f.add(square());
    for (unsigned seed = 1; seed <= 4; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        ShakeCorrection shake;
        std::vector<RigidBody> bodies = f.bodies;
        spin(bodies, seed, 1);
        ConstraintRows rows0, rows1;
        std::vector<JointRowRange> ranges0, ranges1, errorRanges;
        f.write(bodies, rows0, ranges0);
        RowSystem system;
        system.buildResponses(rows0, bodies);
        shake.capture(rows0, ranges0, system);
        for (RigidBody& b : bodies) integratePosition(b, kDt);
        f.write(bodies, rows1, ranges1);
        std::vector<RowError> errors;
        for (const Joint& j : f.joints) errorRanges.push_back(writeJointErrors(j, bodies, JointRowSettings{}, errors));

        const Real measured = ShakeCorrection::drift(rows0, ranges0, errors, errorRanges);
        EXPECT_GT(measured, 1e-4);
        EXPECT_EQ(measured, largestDrift(rows0, rows1, ranges1));
        EXPECT_EQ(measured, shake.apply(rows1, ranges1, bodies, kDt, 0).drift);
    }
}

// A later Newton step on the errors measured without writing the rows (applyAgain) is the step
// apply takes on the rows written at the same poses, bit for bit: both solve with the first
// step's factors, and the errors are those of the written rows.
TEST(Shake, SecondStepFromErrorsIsTheStepFromWrittenRows) {
    Figures f;
    f.add(test::hungHumanoid());
    f.add(square());
    for (unsigned seed = 1; seed <= 4; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        ShakeCorrection fromRows;
        std::vector<RigidBody> bodies = f.bodies;
        spin(bodies, seed, 1);
        ConstraintRows rows;
        std::vector<JointRowRange> ranges, errorRanges;
        f.write(bodies, rows, ranges);
        RowSystem system;
        system.buildResponses(rows, bodies);
        fromRows.capture(rows, ranges, system);
        for (RigidBody& b : bodies) integratePosition(b, kDt);
        f.write(bodies, rows, ranges);
        fromRows.apply(rows, ranges, bodies, kDt, 0);

        ShakeCorrection fromErrors = fromRows;
        std::vector<RigidBody> again = bodies;
        f.write(bodies, rows, ranges);
        const ShakeCorrection::Step second = fromRows.apply(rows, ranges, bodies, kDt, 0);
        std::vector<RowError> errors;
        for (const Joint& j : f.joints) errorRanges.push_back(writeJointErrors(j, again, JointRowSettings{}, errors));
        const ShakeCorrection::Step secondAgain = fromErrors.applyAgain(errors, errorRanges, again, kDt);

        EXPECT_GT(second.drift, 0);
        EXPECT_EQ(second.drift, secondAgain.drift);
        EXPECT_EQ(second.move, secondAgain.move);
        for (std::size_t b = 0; b < bodies.size(); ++b) {
            EXPECT_EQ(bodies[b].position, again[b].position) << "body " << b;
            EXPECT_EQ(bodies[b].orientation.coeffs(), again[b].orientation.coeffs()) << "body " << b;
            EXPECT_EQ(bodies[b].linearVelocity, again[b].linearVelocity) << "body " << b;
            EXPECT_EQ(bodies[b].angularVelocity, again[b].angularVelocity) << "body " << b;
        }
    }
}

// The same joint twice: K is singular (its rows repeat), no move can be trusted.
TEST(Shake, RepeatedJointMovesNothingAndReportsAnInfiniteMove) {
    Figures f;
    f.add(test::horizontalChain(4, 0, false));
    f.joints.push_back(f.joints[2]);
    ShakeCorrection shake;
    const Drifted d = drift(f, 1, 2, shake);
    EXPECT_GT(d.driftBefore, 1e-4);
    EXPECT_EQ(d.step.move, kInfinity);
    for (std::size_t i = 0; i < d.moved.size(); ++i) {
        EXPECT_EQ(d.shaken[i].position, d.moved[i].position);
        EXPECT_EQ(d.shaken[i].linearVelocity, d.moved[i].linearVelocity);
    }
}

// The kinetic energy keptKineticEnergy reports is that of the velocities projected densely:
// v − M⁻¹Jᵀ(J M⁻¹ Jᵀ)⁻¹ J v over the joints' equality rows, for a tree with a loop beside it. A
// projection only removes energy, and the projected velocities break no joint row.
TEST(Shake, KeptKineticEnergyIsThatOfTheDenseProjection) {
    Figures f;
    f.add(test::hungHumanoid());
    f.add(square());
    const Eigen::Index dofs = 6 * static_cast<Eigen::Index>(f.bodies.size());
    for (unsigned seed = 1; seed <= 4; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        std::vector<RigidBody> bodies = f.bodies;
        spin(bodies, seed, 1);
        ConstraintRows rows;
        std::vector<JointRowRange> ranges;
        f.write(bodies, rows, ranges);
        RowSystem system;
        system.buildResponses(rows, bodies);
        ShakeCorrection shake;
        shake.capture(rows, ranges, system);
        const Real kept = shake.keptKineticEnergy(rows, ranges, bodies);

        Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(dofs, dofs), inverse = Eigen::MatrixXd::Zero(dofs, dofs);
        Eigen::VectorXd v(dofs);
        for (std::size_t b = 0; b < bodies.size(); ++b) {
            const Eigen::Index o = 6 * static_cast<Eigen::Index>(b);
            mass.block<3, 3>(o, o) = bodies[b].mass() * Mat3::Identity();
            mass.block<3, 3>(o + 3, o + 3) = bodies[b].inertiaWorld();
            inverse.block<3, 3>(o, o) = bodies[b].inverseMass * Mat3::Identity();
            inverse.block<3, 3>(o + 3, o + 3) = bodies[b].inverseInertiaWorld();
            v.segment<3>(o) = bodies[b].linearVelocity;
            v.segment<3>(o + 3) = bodies[b].angularVelocity;
        }
        std::vector<Eigen::VectorXd> jacobian;
        for (const JointRowRange& range : ranges)
            for (int i = range.first; i < range.first + range.equalityRows; ++i) {
                const ConstraintRow& row = rows[static_cast<std::size_t>(i)];
                Eigen::VectorXd j = Eigen::VectorXd::Zero(dofs);
                if (row.bodyA != kWorldBody) j.segment<6>(6 * row.bodyA) << row.linearA, row.angularA;
                if (row.bodyB != kWorldBody) j.segment<6>(6 * row.bodyB) << row.linearB, row.angularB;
                jacobian.push_back(j);
            }
        Eigen::MatrixXd J(static_cast<Eigen::Index>(jacobian.size()), dofs);
        for (std::size_t r = 0; r < jacobian.size(); ++r) J.row(static_cast<Eigen::Index>(r)) = jacobian[r].transpose();
        const Eigen::MatrixXd k = J * inverse * J.transpose();
        const Eigen::VectorXd projected = v - inverse * J.transpose() * k.fullPivLu().solve(J * v);
        const Real dense = projected.dot(mass * projected) / 2, before = v.dot(mass * v) / 2;

        EXPECT_NEAR(kept, dense, 1e-9 * before);
        EXPECT_LT(kept, before);
        EXPECT_LT((J * projected).lpNorm<Eigen::Infinity>(), 1e-9 * v.lpNorm<Eigen::Infinity>());
    }
}

}  // namespace
}  // namespace af
