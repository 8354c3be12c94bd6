#pragma once
// Draws one RenderScene into a cairo context: background, floor, shadows, shaded shapes.

#include "render.h"

#include <cairo.h>

namespace af::render::detail {

/// Draws `scene` as seen by `camera` into the rectangle (0, 0, width, height) of the current user
/// space of `cr`; the caller translates and clips for a cell of a larger image.
void drawScene(cairo_t* cr, const RenderScene& scene, const Camera& camera, double width, double height);

}  // namespace af::render::detail
