#pragma once
// What the af_show* cvars describe, measured on a world as it is now: where a joint's parts are,
// how far its limits are used, and which body hangs on which. Shared by the console's printed
// blocks (session_show.h) and the overlays of af-console's screenshot, so the two agree.

#include "af/dynamics/world.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace af::console {

// af_showContacts draws each contact's normal impulse as a line this long per mass unit ·
// unit/s (its help says so): our humanoid coming to rest on the floor takes 2665 a step (150 mass
// units · 1066 units/s² · 1/60 s) over 17 points, from 25 units of line under a thigh to 4 under
// a foot; longer lines left the screenshot's frame.
inline constexpr Real kContactImpulseLength = 0.02;

// A point or direction carried by a joint's body (world for kWorldBody), in world space now.
Vec3 pointOn(std::span<const RigidBody> bodies, int body, const Vec3& local);
Vec3 directionOn(std::span<const RigidBody> bodies, int body, const Vec3& local);

// The joint's anchor as body A carries it (spring: anchor1).
Vec3 jointAnchor(const Joint& joint, std::span<const RigidBody> bodies);

// How a joint stands against one of its limits, in degrees: the measured angles, each with its
// allowed interval (a cone's is the shaft's angle from its axis, up to half the decl's apex
// angle). A joint has none, one, or two (a ball and socket's shaft limit and twist limit).
struct LimitReading {
    std::string name;  // "cone", "pyramid", "hinge", "twist", "cardan"
    struct Angle {
        Real value = 0, lower = 0, upper = 0;
    };
    std::vector<Angle> angles;
    // How far the farthest angle is past its interval; 0 inside.
    Real past() const;
};
std::vector<LimitReading> limitReadings(const Joint& joint, std::span<const RigidBody> bodies);

// A figure's trees as parent → child pairs of its body indices: outward over its constraints from
// the first body of each tree (body 0, the root, for a well-formed figure), breadth first, as
// Doom orders a tree from its root.
std::vector<std::pair<int, int>> treeEdges(const Figure& figure);

// The joints of the world that hold a body of `figure`: its own, then its binds to the world.
std::vector<const Joint*> figureJoints(const World& world, FigureId figure);

}  // namespace af::console
