#pragma once
// From world points to pixels for one Camera and image size.

#include "render.h"

#include <Eigen/Core>

#include <vector>

namespace af::render::detail {

using Vec2 = Eigen::Vector2d;

/// The camera's orthonormal basis: right, up (towards world +Z) and forward (into the picture).
struct ViewBasis {
    Vec3 right, up, forward;
};
ViewBasis viewBasis(const Vec3& forward);

class Projector {
public:
    Projector(const Camera& camera, double width, double height);

    /// World point in camera coordinates: x right, y up, z depth along the view direction.
    Vec3 toView(const Vec3& world) const;
    /// A camera-space point in front of the camera (z ≥ nearDepth()) to pixels.
    Vec2 toPixels(const Vec3& view) const;
    /// Clips a camera-space polygon to z ≥ nearDepth() and returns its pixels (empty if nothing
    /// is left); points behind the camera would otherwise project mirrored.
    std::vector<Vec2> polygonToPixels(const std::vector<Vec3>& view) const;
    /// The same for a segment; false when all of it is behind the near plane.
    bool segmentToPixels(Vec3 a, Vec3 b, Vec2& pa, Vec2& pb) const;

    const Vec3& eye() const { return eye_; }
    double nearDepth() const { return near_; }
    double width() const { return width_; }
    double height() const { return height_; }

private:
    Vec3      eye_;
    ViewBasis basis_;
    double    focal_;  // pixels per unit of x/z
    double    width_, height_;
    double    near_;
};

}  // namespace af::render::detail
