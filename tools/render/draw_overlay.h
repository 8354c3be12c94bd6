#pragma once
// Draws a RenderScene's Overlay (render.h) over what drawScene has shaded.

#include "projection.h"

#include <cairo.h>

namespace af::render::detail {

/// `lineScale`: pixels per pixel of a 480-pixel-high picture.
void drawOverlay(cairo_t* cr, const Projector& proj, const Overlay& overlay, double lineScale);

}  // namespace af::render::detail
