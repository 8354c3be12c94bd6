#pragma once
// Worlds for the physics tests: figures written as .af text on a skeleton that is only names.

#include "af/dynamics/world.h"
#include "af/figure/figure.h"
#include "af/text/af_parser.h"
#include "dynamics/world_access.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace af::test {

// A skeleton of `names`, all at the origin, each the child of the one before: enough for decls
// whose vectors are all literal coordinates.
inline Skeleton namesOnlySkeleton(const std::vector<std::string>& names) {
    Skeleton s;
    for (std::size_t i = 0; i < names.size(); ++i) {
        s.names.push_back(names[i]);
        s.parents.push_back(static_cast<int>(i) - 1);
        s.joints.push_back({});
    }
    return s;
}

inline Figure figureFromText(const std::string& text, const Skeleton& skeleton) {
    const AFParseResult parsed = parseAF(text, "test.af");
    EXPECT_TRUE(parsed.ok()) << parsed.diagnostics.formatAll();
    const FigureResult built = buildFigure(parsed.file.decls.at(0), skeleton, "test.af");
    EXPECT_TRUE(built.ok()) << built.formatDiagnostics();
    return built.figure.value_or(Figure{});
}

// A box `half` on each side hanging from a ball joint `length` above its centre.
inline Figure pendulum(Real half, Real length) {
    const std::string h = std::to_string(half);
    return figureFromText("articulatedFigure pendulum {\n"
                          "settings { friction 0, 0, 0 }\n"
                          "body \"bob\" { joint \"origin\" model box( ( -" + h + ", -" + h + ", -" + h + " ), ( " +
                              h + ", " + h + ", " + h + " ) ) origin ( 0, 0, 0 ) density 1 }\n"
                          "ballAndSocketJoint \"pivot\" { body1 \"bob\" body2 \"world\" anchor ( 0, 0, " +
                              std::to_string(length) + " ) friction 0 }\n}\n",
                          namesOnlySkeleton({"origin"}));
}

// `links` boxes of length 10 laid out along +X at height `height`, each joined to the one before
// by a ball joint at their common end; the first hangs from the world at x = 0 unless `free`.
// Links are `2·half` thick (half = 5 makes them cubes).
inline Figure horizontalChain(int links, Real height, bool free = false, Real half = 1) {
    const std::string h = std::to_string(half);
    std::string text = "articulatedFigure chain {\nsettings { friction 0, 0, 0 }\n";
    std::vector<std::string> names;
    for (int i = 0; i < links; ++i) {
        const std::string name = i == 0 ? std::string("origin") : "link" + std::to_string(i);
        names.push_back(name);
        text += "body \"b" + std::to_string(i) + "\" { joint \"" + name +
                "\" model box( ( -5, -" + h + ", -" + h + " ), ( 5, " + h + ", " + h + " ) ) origin ( " + std::to_string(10 * i + 5) + ", 0, " +
                std::to_string(height) + " ) density 0.2 containedJoints \"" + name + "\" }\n";
    }
    for (int i = free ? 1 : 0; i < links; ++i) {
        text += "ballAndSocketJoint \"j" + std::to_string(i) + "\" { body1 \"b" + std::to_string(i) + "\" body2 \"" +
                (i == 0 ? std::string("world") : "b" + std::to_string(i - 1)) + "\" anchor ( " +
                std::to_string(10 * i) + ", 0, " + std::to_string(height) + " ) friction 0 }\n";
    }
    return figureFromText(text + "}\n", namesOnlySkeleton(names));
}

// `links` boxes of length 10 hanging straight down from the world at (0, 0, height), joined end
// to end by ball joints.
inline Figure hangingChain(int links, Real height) {
    std::string text = "articulatedFigure chain {\nsettings { friction 0, 0, 0 }\n";
    std::vector<std::string> names;
    for (int i = 0; i < links; ++i) {
        const std::string name = i == 0 ? std::string("origin") : "link" + std::to_string(i);
        names.push_back(name);
        text += "body \"b" + std::to_string(i) + "\" { joint \"" + name +
                "\" model box( ( -1, -1, -5 ), ( 1, 1, 5 ) ) origin ( 0, 0, " + std::to_string(height - 10 * i - 5) +
                " ) density 0.2 containedJoints \"" + name + "\" }\n";
        text += "ballAndSocketJoint \"j" + std::to_string(i) + "\" { body1 \"b" + std::to_string(i) + "\" body2 \"" +
                (i == 0 ? std::string("world") : "b" + std::to_string(i - 1)) + "\" anchor ( 0, 0, " +
                std::to_string(height - 10 * i) + " ) friction 0 }\n";
    }
    return figureFromText(text + "}\n", namesOnlySkeleton(names));
}

// Settings for tests of joints and integration alone: no rest test and no self collision, so
// that what is measured is the constraint physics.
inline WorldSettings dynamicsOnly(WorldSettings settings = {}) {
    settings.comeToRest = false;
    settings.collision.skipSelfCollision = true;
    return settings;
}

// Turns every body rigidly about `pivot` by `degrees` about +X, before the first step (the
// bodies written as they are, where World::setPose would round each rotation through a
// quaternion anew).
inline void swingAbout(World& world, const Vec3& pivot, Real degrees) {
    const Quat turn(Eigen::AngleAxis<Real>(degrees * 3.14159265358979323846 / 180, Vec3::UnitX()));
    for (RigidBody& b : detail::WorldAccess::bodies(world)) {
        b.position = pivot + turn * (b.position - pivot);
        b.orientation = turn * b.orientation;
    }
}

// Literal .af text for a number or a vector, 12 decimals. The parser reads 32-bit floats, as
// Doom does: a test that measures against a direction should write one floats hold exactly
// (small integers), not a rounded unit vector.
inline std::string afNumber(Real x) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.12f", static_cast<double>(x));
    return buffer;
}

inline std::string afVector(const Vec3& v) {
    return "( " + afNumber(v.x()) + ", " + afNumber(v.y()) + ", " + afNumber(v.z()) + " )";
}

// A `body` block: an axis-aligned box of half extents `half` centred at `origin`, driving (and
// containing) skeleton joint `joint`, with air friction (linear, angular) and no contact friction.
inline std::string boxBodyText(const std::string& name, const std::string& joint, const Vec3& half, const Vec3& origin,
                               Real density = 1, Real linearFriction = 0, Real angularFriction = 0) {
    return "body \"" + name + "\" { joint \"" + joint + "\" model box( " + afVector(-half) + ", " + afVector(half) +
           " ) origin " + afVector(origin) + " density " + afNumber(density) + " friction " + afNumber(linearFriction) +
           ", " + afNumber(angularFriction) + ", 0 containedJoints \"" + joint + "\" }\n";
}

// A figure of the given body and constraint blocks on a names-only skeleton of `joints` (the
// first must be "origin").
inline Figure figureOfBlocks(const std::vector<std::string>& joints, const std::string& blocks) {
    return figureFromText("articulatedFigure test {\nsettings { friction 0, 0, 0 }\n" + blocks + "}\n",
                          namesOnlySkeleton(joints));
}

inline Real potentialEnergy(const World& world) {
    Real sum = 0;
    for (const RigidBody& b : world.bodies()) sum -= b.mass() * world.settings().gravity.dot(b.position);
    return sum;
}

}  // namespace af::test
