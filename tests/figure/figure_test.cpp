// Building figures from decls and af_pose skeletons, and bodies driving the skeleton back.

#include "af/geometry/math.h"
#include "figure_test_util.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace af {
namespace {

using test::expectNear;

Figure buildHumanoid(const RigidPose& placement = {}) {
    const FigureResult r = buildFigure(test::humanoidDecl(), test::humanoidPose(), "humanoid.af", placement);
    EXPECT_TRUE(r.ok()) << r.formatDiagnostics();
    return r.figure.value_or(Figure{});
}

std::vector<RigidPose> spawnPoses(const Figure& f) {
    std::vector<RigidPose> poses;
    for (const FigureBody& b : f.bodies) poses.push_back(b.pose);
    return poses;
}

RigidPose somePlacement() {
    return {Vec3(100, -40, 25), rotationFromAngles(10, 120, -30)};
}

TEST(Figure, HumanoidBuildsWithoutWarnings) {
    const FigureResult r = buildFigure(test::humanoidDecl(), test::humanoidPose(), "humanoid.af");
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.formatDiagnostics(), "");
}

TEST(Figure, TotalMassIsWhatTheSettingsSay) {
    const Figure f = buildHumanoid();
    EXPECT_NEAR(f.totalMass(), 150.0, 1e-9);
    EXPECT_EQ(f.bodies[0].name, "pelvis");
}

// Without totalMass, mass is density times the exact volume of the shape.
TEST(Figure, MassIsDensityTimesVolume) {
    const FigureResult r = buildFigure(test::loadDecl("af/chain.af"), test::loadAfPose("models/chain/af_pose.md5anim"),
                                       "chain.af");
    ASSERT_TRUE(r.ok()) << r.formatDiagnostics();
    for (const FigureBody& b : r.figure->bodies) EXPECT_NEAR(b.mass, Real(0.2f) * b.volume, 1e-9 * b.mass) << b.name;
    // The chain's links are 6 x 2 x 1 boxes.
    EXPECT_NEAR(r.figure->bodies[0].volume, 12.0, 1e-9);
}

// Every body sits where the decl puts it on the af_pose skeleton: box corners at joint + bounds,
// bone tips on the two joints they name, cylinders centred on their bone centres.
TEST(Figure, HumanoidBodiesSitOnTheirJoints) {
    const Figure f = buildHumanoid();
    const DeclAF decl = test::humanoidDecl();
    const Skeleton& s = f.afPose;
    auto joint = [&](const std::string& name) { return s.joints[static_cast<std::size_t>(s.find(name))].position; };
    int checked = 0;
    for (const AFBody& d : decl.bodies) {
        const FigureBody& b = f.bodies[static_cast<std::size_t>(f.findBody(d.name))];
        std::vector<Vec3> world;
        for (const Vec3& v : b.shape.vertices) world.push_back(b.pose.apply(v));
        if (d.shape.type == ShapeType::Box) {
            const Vec3 origin = d.origin.kind == AFVector::Kind::Joint
                                    ? joint(d.origin.joint1)
                                    : Vec3(0.5 * (joint(d.origin.joint1) + joint(d.origin.joint2)));
            const Real3 lo = d.shape.v1.coordinates, hi = d.shape.v2.coordinates;
            for (int corner = 0; corner < 8; ++corner) {
                const Vec3 expected = origin + Vec3(corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1],
                                                    corner & 4 ? hi[2] : lo[2]);
                const bool found = std::any_of(world.begin(), world.end(),
                                               [&](const Vec3& v) { return (v - expected).norm() < 1e-6; });
                EXPECT_TRUE(found) << d.name << " corner " << expected.transpose();
            }
            ++checked;
        } else if (d.shape.type == ShapeType::Bone) {
            const Vec3 a = joint(d.shape.v1.joint1), c = joint(d.shape.v2.joint1);
            auto near = [&](const Vec3& p) {
                return std::any_of(world.begin(), world.end(), [&](const Vec3& v) { return (v - p).norm() < 1e-6; });
            };
            EXPECT_TRUE(near(a) && near(c)) << d.name;
            expectNear(b.pose.position, 0.5 * (a + c), 1e-6, d.name);
            ++checked;
        } else if (d.shape.type == ShapeType::Cylinder) {
            expectNear(b.pose.position, 0.5 * (joint(d.origin.joint1) + joint(d.origin.joint2)), 1e-6, d.name);
            ++checked;
        }
    }
    EXPECT_EQ(checked, static_cast<int>(decl.bodies.size()));
}

TEST(Figure, PlacementMovesBodiesAndConstraintsRigidly) {
    const Figure here = buildHumanoid();
    const RigidPose p = somePlacement();
    const Figure there = buildHumanoid(p);
    for (std::size_t i = 0; i < here.bodies.size(); ++i) {
        expectNear(there.bodies[i].pose.position, p.apply(here.bodies[i].pose.position), 1e-9, here.bodies[i].name);
        expectNear(there.bodies[i].pose.rotation, p.rotation * here.bodies[i].pose.rotation, 1e-12, here.bodies[i].name);
        expectNear(there.bodies[i].inertia, here.bodies[i].inertia, 1e-9, "body-frame inertia");
    }
    for (std::size_t i = 0; i < here.constraints.size(); ++i) {
        const FigureConstraint &a = here.constraints[i], &b = there.constraints[i];
        expectNear(b.anchor, p.apply(a.anchor), 1e-9, a.name + " anchor");
        if (a.type == ConstraintType::Hinge) expectNear(b.axis, p.rotation * a.axis, 1e-12, a.name + " axis");
        if (a.limit != LimitType::None && a.type != ConstraintType::Hinge)
            expectNear(b.limitAxis, p.rotation * a.limitAxis, 1e-12, a.name + " limit axis");
    }
}

// The lowest and highest points of the placed shapes: a translation moves both by its z, and a
// half turn about X swaps them (negated).
TEST(Figure, HeightRangeFollowsThePlacement) {
    const Figure f = buildHumanoid();
    const HeightRange here = heightRange(f);
    EXPECT_GT(here.highest - here.lowest, 60) << "our humanoid stands about 70 units tall";
    RigidPose up;
    up.position = Vec3(3, -4, 25);
    const HeightRange lifted = heightRange(f, up);
    EXPECT_NEAR(lifted.lowest, here.lowest + 25, 1e-12);
    EXPECT_NEAR(lifted.highest, here.highest + 25, 1e-12);
    RigidPose flipped;
    flipped.rotation = Eigen::AngleAxis<Real>(std::numbers::pi_v<Real>, Vec3::UnitX()).toRotationMatrix();
    const HeightRange upsideDown = heightRange(f, flipped);
    EXPECT_NEAR(upsideDown.lowest, -here.highest, 1e-9);
    EXPECT_NEAR(upsideDown.highest, -here.lowest, 1e-9);
}

TEST(Figure, ConstraintAnchorsResolveToJoints) {
    const Figure f = buildHumanoid();
    const DeclAF decl = test::humanoidDecl();
    for (std::size_t i = 0; i < decl.constraints.size(); ++i) {
        const AFConstraint& c = decl.constraints[i];
        if (c.anchor.kind != AFVector::Kind::Joint) continue;
        const int j = f.afPose.find(c.anchor.joint1);
        ASSERT_GE(j, 0) << c.name;
        expectNear(f.constraints[i].anchor, f.afPose.joints[static_cast<std::size_t>(j)].position, 1e-12, c.name);
        EXPECT_EQ(f.constraints[i].body1, f.findBody(c.body1));
    }
    for (const FigureConstraint& c : f.constraints) {
        if (c.type == ConstraintType::Universal) {
            EXPECT_NEAR(c.shafts[0].norm(), 1.0, 1e-12);
            EXPECT_NEAR(c.shafts[1].norm(), 1.0, 1e-12);
        }
        if (c.type == ConstraintType::Hinge) {
            EXPECT_NEAR(c.axis.norm(), 1.0, 1e-12);
        }
    }
}

// docs/figures.md §3.6 round trip: bodies in their spawn poses give back the af_pose skeleton.
TEST(Figure, SkeletonRoundTripReproducesTheAfPose) {
    for (const RigidPose& placement : {RigidPose{}, somePlacement()}) {
        const Figure f = buildHumanoid(placement);
        const Skeleton posed = poseSkeleton(f, spawnPoses(f));
        ASSERT_EQ(posed.size(), f.afPose.size());
        for (std::size_t i = 0; i < posed.size(); ++i) {
            const RigidPose expected = placement * RigidPose{f.afPose.joints[i].position, f.afPose.joints[i].rotation};
            expectNear(posed.joints[i].position, expected.position, 1e-6, posed.names[i]);
            expectNear(posed.joints[i].rotation, expected.rotation, 1e-6, posed.names[i]);
        }
    }
}

TEST(Figure, SkeletonFollowsARigidMotionOfAllBodies) {
    const Figure f = buildHumanoid();
    const RigidPose motion = somePlacement();
    std::vector<RigidPose> moved = spawnPoses(f);
    for (RigidPose& p : moved) p = motion * p;
    const Skeleton posed = poseSkeleton(f, moved);
    for (std::size_t i = 0; i < posed.size(); ++i)
        expectNear(posed.joints[i].position, motion.apply(f.afPose.joints[i].position), 1e-6, posed.names[i]);
}

// An orientation body turns its joint; the joint stays where its parent puts it, and the joints
// below follow with their bone lengths.
TEST(Figure, TurningAForearmBendsTheElbowChain) {
    const Figure f = buildHumanoid();
    const int forearm = f.findBody("lloarm");
    ASSERT_GE(forearm, 0);
    const FigureBody& body = f.bodies[static_cast<std::size_t>(forearm)];
    ASSERT_EQ(body.mod, JointMod::Orientation);
    const std::size_t elbow = static_cast<std::size_t>(body.joint);
    const Vec3 elbowAt = f.afPose.joints[elbow].position;
    const RigidPose bend{elbowAt - rotationFromAngles(0, 0, 90) * elbowAt, rotationFromAngles(0, 0, 90)};

    std::vector<RigidPose> poses = spawnPoses(f);
    poses[static_cast<std::size_t>(forearm)] = bend * poses[static_cast<std::size_t>(forearm)];
    const Skeleton posed = poseSkeleton(f, poses);

    expectNear(posed.joints[elbow].position, elbowAt, 1e-9, "elbow");
    expectNear(posed.joints[elbow].rotation, bend.rotation * f.afPose.joints[elbow].rotation, 1e-9, "elbow turn");
    const std::size_t hand = static_cast<std::size_t>(posed.find("lhand"));
    EXPECT_NEAR((posed.joints[hand].position - elbowAt).norm(), (f.afPose.joints[hand].position - elbowAt).norm(), 1e-9);
    // The hand's own body did not move, but its joint position follows the forearm's bone.
    expectNear(posed.joints[hand].position, bend.apply(f.afPose.joints[hand].position), 1e-9, "hand joint");
}

// docs/formats.md §1.6: "*origin -*chest" means every joint except the chest subtree.
TEST(Figure, ContainedJointsExpandLikeDoom) {
    const Skeleton s = test::humanoidPose();
    const std::vector<int> all = expandJointList(s, "*origin");
    EXPECT_EQ(all.size(), s.size());
    const int chest = s.find("chest");
    std::vector<int> chestSubtree = expandJointList(s, "*CHEST");
    EXPECT_EQ(chestSubtree.front(), chest);
    for (int j : chestSubtree) {
        int k = j;
        while (k >= 0 && k != chest) k = s.parents[static_cast<std::size_t>(k)];
        EXPECT_EQ(k, chest) << s.names[static_cast<std::size_t>(j)] << " is not below the chest";
    }
    const std::vector<int> rest = expandJointList(s, "*origin -*chest");
    EXPECT_EQ(rest.size() + chestSubtree.size(), s.size());
    for (int j : chestSubtree) EXPECT_EQ(std::count(rest.begin(), rest.end(), j), 0);
    EXPECT_EQ(expandJointList(s, "pelvis waist -pelvis"), std::vector<int>{s.find("waist")});
    std::vector<std::string> unknown;
    EXPECT_TRUE(expandJointList(s, "*-chest nosuch", &unknown).empty());
    EXPECT_EQ(unknown, (std::vector<std::string>{"*-chest", "nosuch"}));
}

TEST(Figure, EveryHumanoidJointHasABody) {
    const Figure f = buildHumanoid();
    for (std::size_t j = 0; j < f.jointBody.size(); ++j) EXPECT_GE(f.jointBody[j], 0) << f.afPose.names[j];
    EXPECT_EQ(f.jointBody[static_cast<std::size_t>(f.afPose.find("lfingers"))], f.findBody("lhand"));
}

TEST(Figure, RootBodyDrivesTheFirstChildOfOrigin) {
    const Figure f = buildHumanoid();
    EXPECT_EQ(f.bodies[0].joint, f.afPose.find("pelvis"));
    EXPECT_EQ(f.bodies[0].mod, JointMod::Orientation);
}

}  // namespace
}  // namespace af

namespace af {
namespace {

TEST(Figure, HumanoidIsOneTreeAndAWristlessOneIsTwo) {
    const Figure whole = buildHumanoid();
    const auto trees = bodyTrees(whole);
    ASSERT_EQ(trees.size(), 1u);
    EXPECT_EQ(trees[0].size(), whole.bodies.size());

    DeclAF d = test::humanoidDecl();
    std::erase_if(d.constraints, [](const AFConstraint& c) { return c.name == "rwrist"; });
    const FigureResult r = buildFigure(d, test::humanoidPose(), "humanoid.af");
    ASSERT_TRUE(r.ok());
    const auto split = bodyTrees(*r.figure);
    ASSERT_EQ(split.size(), 2u);
    EXPECT_EQ(split[1], std::vector<int>{r.figure->findBody("rhand")});
}

}  // namespace
}  // namespace af
