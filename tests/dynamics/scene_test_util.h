#pragma once
// Figures for the scene tests (collision, rest): our humanoid placed in the world, and free boxes.

#include "../../bench/hung_humanoid.h"
#include "../figure/figure_test_util.h"
#include "world_test_util.h"

namespace af::test {

// Our humanoid with its feet at `position`, standing (pitch 0) or lying face down along +X
// (pitch 90).
inline Figure humanoidAt(const Vec3& position, Real yawDegrees = 0, Real pitchDegrees = 0) {
    RigidPose placement;
    placement.position = position;
    placement.rotation = rotationFromAngles(pitchDegrees, yawDegrees, 0);
    const FigureResult r = buildFigure(humanoidDecl(), humanoidPose(), "humanoid.af", placement);
    EXPECT_TRUE(r.ok()) << r.formatDiagnostics();
    return r.figure.value_or(Figure{});
}

// Our humanoid at its af_pose, hung from the world by its chest with a fixed joint.
inline Figure hungHumanoid() {
    const FigureResult r = buildFigure(bench::hungByTheChest(humanoidDecl()), humanoidPose(), "humanoid.af");
    EXPECT_TRUE(r.ok()) << r.formatDiagnostics();
    return r.figure.value_or(Figure{});
}

// One free box (its own figure) of half extents `half` centred at `centre`, density 0.01, with
// contact friction μ.
inline Figure freeBox(const Vec3& half, const Vec3& centre, Real friction = 0.8) {
    return figureOfBlocks({"origin"}, "body \"box\" { joint \"origin\" model box( " + afVector(-half) + ", " +
                                          afVector(half) + " ) origin " + afVector(centre) +
                                          " density 0.01 friction 0, 0, " + afNumber(friction) + " }\n");
}

}  // namespace af::test
