// The benchmark ragdoll's tables, placements and angle formulas against hand-computed values.

#include "scene_def.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <numbers>

namespace benchscene {
namespace {

constexpr double kTol = 1e-9;

Quat rot(const Vec3& axis, double angle) { return Quat(Eigen::AngleAxisd(angle, axis.normalized())); }

double lowestCorner(const BodyState& s, const BoxBody& b) {
    return s.x.z() - s.q.toRotationMatrix().row(2).cwiseAbs().dot(b.halfExtents);
}

double highestCorner(const BodyState& s, const BoxBody& b) {
    return s.x.z() + s.q.toRotationMatrix().row(2).cwiseAbs().dot(b.halfExtents);
}

bool insideClosedBox(const Vec3& p, const BoxBody& b) {
    return ((p - b.centre).cwiseAbs() - b.halfExtents).maxCoeff() <= kTol;
}

TEST(BenchScene, RagdollHasSixteenBodiesFifteenJointsAndSeventyKilograms) {
    ASSERT_EQ(ragdollBodies().size(), 16u);
    ASSERT_EQ(ragdollJoints().size(), 15u);
    double total = 0;
    for (const BoxBody& b : ragdollBodies()) total += b.mass;
    EXPECT_NEAR(total, 70.000, 1e-9);
}

TEST(BenchScene, SolidBoxInertiaOfTheChest) {
    const BoxBody& chest = ragdollBodies()[2];
    const Vec3 I = boxInertia(chest);
    EXPECT_NEAR(I.x(), 15.12 * (0.11 * 0.11 + 0.14 * 0.14) / 3, 1e-12);
    EXPECT_NEAR(I.y(), 15.12 * (0.205 * 0.205 + 0.14 * 0.14) / 3, 1e-12);
    EXPECT_NEAR(I.z(), 15.12 * (0.205 * 0.205 + 0.11 * 0.11) / 3, 1e-12);
}

TEST(BenchScene, NoTwoBoxesOverlapInTheTPose) {
    const auto bodies = ragdollBodies();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        for (std::size_t j = i + 1; j < bodies.size(); ++j) {
            const Vec3 gap = (bodies[i].centre - bodies[j].centre).cwiseAbs() - bodies[i].halfExtents -
                             bodies[j].halfExtents;
            EXPECT_GE(gap.maxCoeff(), -kTol) << bodies[i].name << " overlaps " << bodies[j].name;
        }
    }
}

TEST(BenchScene, EveryAnchorLiesOnOrInsideBothOfItsBoxes) {
    const auto bodies = ragdollBodies();
    for (const JointDef& j : ragdollJoints()) {
        EXPECT_TRUE(insideClosedBox(j.anchor, bodies[j.parent])) << j.name << " outside " << bodies[j.parent].name;
        EXPECT_TRUE(insideClosedBox(j.anchor, bodies[j.child])) << j.name << " outside " << bodies[j.child].name;
    }
}

TEST(BenchScene, SolesOnTheGroundHeadTopAndArmSpan) {
    const auto bodies = ragdollBodies();
    double low = 1e9, high = -1e9, left = 1e9, right = -1e9;
    for (const BoxBody& b : bodies) {
        low = std::min(low, b.centre.z() - b.halfExtents.z());
        high = std::max(high, b.centre.z() + b.halfExtents.z());
        left = std::min(left, b.centre.x() - b.halfExtents.x());
        right = std::max(right, b.centre.x() + b.halfExtents.x());
    }
    EXPECT_NEAR(low, 0.0, kTol);
    EXPECT_NEAR(high, 1.78, kTol);
    EXPECT_NEAR(right - left, 1.77, kTol);
}

TEST(BenchScene, AllAnglesAreZeroInTheTPose) {
    const Quat I = Quat::Identity();
    for (const JointDef& j : ragdollJoints()) {
        switch (j.kind) {
            case JointKind::Hinge: EXPECT_NEAR(hingeAngle(j, I, I), 0, kTol) << j.name; break;
            case JointKind::Universal: {
                const auto [t1, t2] = universalAngles(j, I, I);
                EXPECT_NEAR(t1, 0, kTol) << j.name;
                EXPECT_NEAR(t2, 0, kTol) << j.name;
                break;
            }
            case JointKind::ConeTwist: EXPECT_NEAR(swingTwist(j, I, I)[1], 0, kTol) << j.name; break;
            case JointKind::Fixed: break;
        }
    }
}

TEST(BenchScene, HingeAngleIsTheRotationAboutItsAxisWithSign) {
    const JointDef& elbow = ragdollJoints()[4];  // r_elbow, axis +Z: + = forearm swings forward
    const Quat qA = rot(Vec3(0.3, -0.2, 0.9), 0.7);  // parent anywhere: only the relative rotation counts
    EXPECT_NEAR(hingeAngle(elbow, qA, qA * rot(Vec3::UnitZ(), 0.9)), 0.9, kTol);
    EXPECT_NEAR(hingeAngle(elbow, qA, qA * rot(Vec3::UnitZ(), -0.4)), -0.4, kTol);
    EXPECT_NEAR(hingeAngle(elbow, qA, qA * rot(Vec3::UnitZ(), 3.0)), 3.0, kTol);
    // Past π it wraps to the other side.
    EXPECT_NEAR(hingeAngle(elbow, qA, qA * rot(Vec3::UnitZ(), 3.5)), 3.5 - 2 * std::numbers::pi, kTol);
    // The same quaternion with the opposite sign is the same rotation.
    const Quat neg(-(qA * rot(Vec3::UnitZ(), 0.9)).coeffs());
    EXPECT_NEAR(hingeAngle(elbow, qA, Quat(neg)), 0.9, kTol);
    // Forearm tip (+X of the elbow) moves toward +Y (forward) for a positive angle.
    EXPECT_GT((rot(Vec3::UnitZ(), 0.2) * Vec3::UnitX()).y(), 0);
}

TEST(BenchScene, KneeFlexionMovesTheFootBackward) {
    const JointDef& knee = ragdollJoints()[10];  // axis −X
    const Quat bend = rot(knee.axis1, 0.5);
    EXPECT_NEAR(hingeAngle(knee, Quat::Identity(), bend), 0.5, kTol);
    EXPECT_LT((bend * Vec3(0, 0, -0.4)).y(), 0);  // the foot, below the knee, goes to −Y
}

TEST(BenchScene, UniversalAnglesOfAComposedRotationComeBack) {
    for (const int index : {9, 12}) {
        const JointDef& hip = ragdollJoints()[index];
        for (const auto& [t1, t2] : {std::pair{0.3, -0.2}, std::pair{-0.25, 2.2}, std::pair{0.9, 0.4}}) {
            const Quat qA = rot(Vec3(1, 2, 3), 0.4);
            const Quat qB = qA * rot(hip.axis1, t1) * rot(hip.axis2, t2);
            const auto angles = universalAngles(hip, qA, qB);
            EXPECT_NEAR(angles[0], t1, kTol) << hip.name;
            EXPECT_NEAR(angles[1], t2, kTol) << hip.name;
        }
    }
}

TEST(BenchScene, HipAbductionMovesTheFootOutwardAndFlexionForward) {
    for (const int index : {9, 12}) {
        const JointDef& hip = ragdollJoints()[index];
        const Vec3 foot(0, 0, -0.8);  // below the hip
        const double outward = hip.anchor.x() > 0 ? 1 : -1;
        EXPECT_GT((rot(hip.axis1, 0.3) * foot).x() * outward, 0) << hip.name;
        EXPECT_GT((rot(hip.axis2, 0.3) * foot).y(), 0) << hip.name;
    }
}

TEST(BenchScene, SwingIsTheBoneAngleFromTheConeAxis) {
    const JointDef& neck = ragdollJoints()[2];  // cone and bone both +Z
    EXPECT_NEAR(swingTwist(neck, Quat::Identity(), rot(Vec3::UnitX(), 0.6))[0], 0.6, kTol);
    EXPECT_NEAR(swingTwist(neck, Quat::Identity(), rot(Vec3::UnitX(), 0.6))[1], 0, kTol);
    // A pure rotation about the bone is all twist, with the sign of the right-hand rule about it.
    const auto [swing, twist] = swingTwist(neck, Quat::Identity(), rot(Vec3::UnitZ(), 0.5));
    EXPECT_NEAR(swing, 0, kTol);
    EXPECT_NEAR(twist, 0.5, kTol);
    // Twist then swing: the swing is undone in the measurement, the twist is kept.
    const Quat composed = rot(Vec3(1, 1, 0), 0.4) * rot(Vec3::UnitZ(), -0.3);
    const auto st = swingTwist(neck, Quat::Identity(), composed);
    EXPECT_NEAR(st[0], 0.4, kTol);
    EXPECT_NEAR(st[1], -0.3, kTol);
}

TEST(BenchScene, ShoulderTPoseSwingIsSeventySixDegrees) {
    for (const int index : {3, 6}) {
        const JointDef& shoulder = ragdollJoints()[index];
        const auto [swing, twist] = swingTwist(shoulder, Quat::Identity(), Quat::Identity());
        EXPECT_NEAR(swing, std::acos(1 / std::sqrt(18.0)), kTol) << shoulder.name;  // 76.37°
        EXPECT_NEAR(twist, 0, kTol) << shoulder.name;
        // Arm swung onto the cone axis: swing 0. Then a rotation about the bone: twist.
        const Quat ontoCone = Quat::FromTwoVectors(shoulder.axis2, shoulder.axis1);
        const auto onAxis = swingTwist(shoulder, Quat::Identity(), ontoCone);
        EXPECT_NEAR(onAxis[0], 0, kTol) << shoulder.name;
        EXPECT_NEAR(onAxis[1], 0, kTol) << shoulder.name;
        const auto twisted = swingTwist(shoulder, Quat::Identity(), rot(shoulder.axis2, 0.35));
        EXPECT_NEAR(twisted[0], swing, kTol) << shoulder.name;
        EXPECT_NEAR(twisted[1], 0.35, kTol) << shoulder.name;
    }
}

TEST(BenchScene, SingleDropStartsWithTheLowestCornerAboutOneMetreUp) {
    const auto placements = scenePlacements("single");
    ASSERT_EQ(placements.size(), 1u);
    double lowest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < kBodiesPerRagdoll; ++i) {
        lowest = std::min(lowest, lowestCorner(placeBody(placements[0], i), ragdollBodies()[i]));
    }
    EXPECT_NEAR(lowest, 0.987, 0.0005);
}

TEST(BenchScene, PlacedBodiesMoveRigidlyWithTheSpin) {
    const Placement pl = scenePlacements("single")[0];
    const BodyState head = placeBody(pl, 3);
    const Vec3 expected = pl.p + pl.R * (Vec3(0, 0, 1.64) - Vec3(0, 0, 0.9));
    EXPECT_NEAR((head.x - expected).norm(), 0, kTol);
    EXPECT_NEAR((head.v - Vec3(0, 0, 0.5).cross(head.x - pl.p)).norm(), 0, kTol);
    EXPECT_TRUE(head.q.isApprox(pl.R, kTol));
    // Anchors placed like bodies: the neck anchor is the head's bottom face centre.
    const Vec3 neck = placePoint(pl, ragdollJoints()[2].anchor);
    EXPECT_NEAR((neck - (head.x + head.q * Vec3(0, 0, -0.14))).norm(), 0, kTol);
}

TEST(BenchScene, GridsAreTwoMetresApartWithGoldenAngleYaws) {
    const auto g4 = scenePlacements("grid4");
    ASSERT_EQ(g4.size(), 16u);
    EXPECT_NEAR((g4[0].p - Vec3(-3, -3, 1.9)).norm(), 0, kTol);
    EXPECT_NEAR((g4[1].p - Vec3(-3, -1, 1.9)).norm(), 0, kTol);  // k = 4i + j: j runs along Y
    EXPECT_NEAR((g4[15].p - Vec3(3, 3, 1.9)).norm(), 0, kTol);
    // Yaw of k = 5 is 0.3 + 5γ: S(ψ) x̂ projected on the ground points at angle ψ (tilt aside).
    const Quat expected = Quat(Eigen::AngleAxisd(0.3 + 5 * 2.399963229728653, Vec3::UnitZ())) *
                          Quat(Eigen::AngleAxisd(0.10, Vec3::UnitY())) * Quat(Eigen::AngleAxisd(0.15, Vec3::UnitX()));
    EXPECT_TRUE(g4[5].R.isApprox(expected, kTol));
    const auto g16 = scenePlacements("grid16");
    ASSERT_EQ(g16.size(), 256u);
    EXPECT_NEAR((g16[0].p - Vec3(-15, -15, 1.9)).norm(), 0, kTol);
    EXPECT_NEAR((g16[255].p - Vec3(15, 15, 1.9)).norm(), 0, kTol);
}

TEST(BenchScene, PileRagdollsLieFaceUpSixtyCentimetresApart) {
    const auto pile = scenePlacements("pile");
    ASSERT_EQ(pile.size(), 32u);
    for (std::size_t k = 0; k < pile.size(); ++k) {
        double low = 1e9, high = -1e9;
        for (int i = 0; i < kBodiesPerRagdoll; ++i) {
            const BodyState s = placeBody(pile[k], i);
            low = std::min(low, lowestCorner(s, ragdollBodies()[i]));
            high = std::max(high, highestCorner(s, ragdollBodies()[i]));
            EXPECT_EQ(s.v.norm() + s.w.norm(), 0.0);
        }
        const double pz = 0.5 + 0.6 * static_cast<double>(k);
        EXPECT_NEAR(pile[k].p.z(), pz, kTol);
        EXPECT_NEAR(low, pz - 0.11, kTol) << k;
        EXPECT_NEAR(high, pz + 0.20, kTol) << k;
        EXPECT_GT((pile[k].R * Vec3::UnitY()).z(), 1 - kTol) << k;  // forward (the face) points up
    }
    EXPECT_NEAR(pile.front().p.z() - 0.11, 0.39, kTol);
    EXPECT_NEAR(pile.back().p.z(), 19.1, kTol);
}

TEST(BenchScene, UnknownSceneThrows) { EXPECT_THROW(scenePlacements("stack"), std::invalid_argument); }

}  // namespace
}  // namespace benchscene
