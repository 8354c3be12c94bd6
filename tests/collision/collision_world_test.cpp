#include "af/collision/collision_world.h"

#include "af/geometry/shapes.h"
#include "narrowphase_test_util.h"

#include <gtest/gtest.h>

namespace af {
namespace {

using test::kCorpse;
using test::kHits;

CollisionFilter ragdollBody(int figure, bool selfCollision = true) {
    return {figure, selfCollision, kCorpse, kHits, true};
}

const Polytope& cube() {
    static const Polytope box = makeBox(Vec3::Constant(-8), Vec3::Constant(8));
    return box;
}

TEST(CollisionFilterRules, BodiesJoinedByAConstraintNeverCollide) {
    CollisionWorld world;
    const int a = world.addBody(cube(), ragdollBody(0));
    const int b = world.addBody(cube(), ragdollBody(0));
    const int c = world.addBody(cube(), ragdollBody(0));
    world.excludePair(b, a);
    EXPECT_FALSE(world.mayCollide(a, b));
    EXPECT_FALSE(world.mayCollide(b, a));
    EXPECT_TRUE(world.mayCollide(a, c));
    EXPECT_FALSE(world.mayCollide(a, a));
}

TEST(CollisionFilterRules, SelfCollisionNeedsBothBodiesOfTheFigure) {
    CollisionWorld world;
    const int a = world.addBody(cube(), ragdollBody(0, true));
    const int b = world.addBody(cube(), ragdollBody(0, false));
    const int c = world.addBody(cube(), ragdollBody(0, true));
    EXPECT_FALSE(world.mayCollide(a, b));
    EXPECT_TRUE(world.mayCollide(a, c));
}

TEST(CollisionFilterRules, DifferentFiguresCollideUnlessDoomsRuleIsAskedFor) {
    CollisionWorld ours;
    const int a = ours.addBody(cube(), ragdollBody(0, false));
    const int b = ours.addBody(cube(), ragdollBody(1, false));
    EXPECT_TRUE(ours.mayCollide(a, b)) << "selfCollision is about one figure's own bodies";

    CollisionWorld doom(CollisionSettings{.figuresCollide = false});
    const int c = doom.addBody(cube(), ragdollBody(0));
    const int d = doom.addBody(cube(), ragdollBody(1));
    EXPECT_FALSE(doom.mayCollide(c, d));
}

TEST(CollisionFilterRules, ContentsMustMeetTheOtherClipMask) {
    CollisionWorld world;
    const int ragdoll = world.addBody(cube(), ragdollBody(0));
    const int ghost = world.addBody(cube(), {1, true, kCorpse, 0, true});            // clips nothing
    const int player = world.addBody(cube(), {2, true, contents::Body, 0, true});    // not in a corpse's mask
    const int solid = world.addBody(cube(), {3, true, contents::Solid, 0, true});
    EXPECT_TRUE(world.mayCollide(ragdoll, ghost)) << "the ragdoll's mask meets the ghost's contents";
    EXPECT_FALSE(world.mayCollide(ragdoll, player));
    EXPECT_TRUE(world.mayCollide(ragdoll, solid));
    EXPECT_FALSE(world.mayCollide(ghost, player));
}

TEST(CollisionFilterRules, StaticWorldNeedsSolidInTheMaskAndNoJointToTheWorld) {
    CollisionWorld world;
    const int floor = world.addPlane(Plane{Vec3::UnitZ(), 0});
    const int ragdoll = world.addBody(cube(), ragdollBody(0));
    const int hung = world.addBody(cube(), {0, true, kCorpse, kHits, false});
    const int ghost = world.addBody(cube(), {1, true, kCorpse, kCorpse, true});
    EXPECT_TRUE(world.mayCollideWithStatic(ragdoll, floor));
    EXPECT_FALSE(world.mayCollideWithStatic(hung, floor));
    EXPECT_FALSE(world.mayCollideWithStatic(ghost, floor));
}

}  // namespace
}  // namespace af
