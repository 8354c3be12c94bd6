#pragma once
// Which body a ray from the camera hits first: the ray against each body's convex hull, clipped
// face plane by face plane (a hull is the intersection of its faces' half-spaces).

#include "orbit_camera.h"

#include "render/render.h"

#include <optional>

namespace af::view {

struct BodyHit {
    int body = -1;   // index into the scene's bodies (the world's body order)
    Vec3 point;      // where the ray enters the hull, world space
    Real distance = 0;
};

// The first hull the ray enters in front of its origin; none when it misses every one (a ray
// starting inside a hull hits that hull at its origin).
std::optional<BodyHit> pickBody(const std::vector<render::RenderShape>& bodies, const Ray& ray);

}  // namespace af::view
