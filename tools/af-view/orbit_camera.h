#pragma once
// The viewer's camera: it orbits a target point (yaw about world +Z, pitch above the horizon) at
// a distance, with world +Z up on screen. Perspective, vertical field of view in degrees. The fly
// mode uses the same camera the other way round: it turns about the eye (look) and carries eye
// and target together (fly), so switching modes keeps the picture and view_camera serves both.
//
// Pixels: x to the right, y down, origin at the top-left corner of the view; pixel (i, j) covers
// [i, i+1) × [j, j+1). A view point (right, up, depth) shows at
// x = w/2 · (1 + f/aspect · right/depth), y = h/2 · (1 − f · up/depth), f = 1/tan(fovY/2).

#include "af/geometry/math.h"

#include <Eigen/Core>

#include <optional>

namespace af::view {

struct Ray {
    Vec3 origin, direction;  // direction unit length
};

class OrbitCamera {
public:
    // Looking from `eye` at `target` (they must differ).
    void lookAt(const Vec3& eye, const Vec3& target, Real fovYDegrees = 30);

    Vec3 eye() const;
    const Vec3& target() const { return target_; }
    Real fovYDegrees() const { return fovY_; }
    Vec3 forward() const;  // unit, from the eye into the picture
    Vec3 right() const;
    Vec3 up() const;

    // Mouse moves in pixels of a view `height` pixels high.
    void rotate(Real dxPixels, Real dyPixels);
    void pan(Real dxPixels, Real dyPixels, int height);
    // Wheel steps: positive comes closer.
    void zoom(Real steps);
    // Fly mode: mouse look about the eye (pixels, as rotate), and a move of the eye and the target
    // by `forward` units along the view, `right` to the right and `up` along world +Z.
    void look(Real dxPixels, Real dyPixels);
    void fly(Real forward, Real right, Real up);
    // The distance from the eye to the target: the fly mode's speeds scale with it.
    Real distance() const { return distance_; }

    // Column-major matrices for OpenGL, for a view of aspect width / height.
    Eigen::Matrix4f viewMatrix() const;
    Eigen::Matrix4f projectionMatrix(Real aspect) const;

    // A world point's pixel in a width × height view; none behind the near plane.
    std::optional<Eigen::Vector2d> project(const Vec3& world, int width, int height) const;
    // The ray from the eye through pixel coordinates (x, y) (a pixel's centre is i + 0.5).
    Ray ray(Real x, Real y, int width, int height) const;

private:
    Real nearDepth() const { return distance_ * 0.01; }

    Vec3 target_ = Vec3::Zero();
    Real yaw_ = 0, pitch_ = 0;  // radians; forward = (cos p cos y, cos p sin y, sin p)
    Real distance_ = 100;
    Real fovY_ = 30;
};

}  // namespace af::view
