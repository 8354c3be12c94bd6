#pragma once
// The af_show* cvars that have a picture, as overlays of af-console's screenshot: constraints
// (anchors and axes), limits (cones, pyramids, hinge ranges), trees (parent → child), velocities,
// body and constraint names, masses and each figure's total mass, principal inertia axes, contacts
// with their normal impulses, and the highlighted body and constraint.

#include "console/session_show.h"
#include "render/render.h"

namespace af::console {

// Adds to `scene`, whose bodies are the world's in order, what `flags` asks to see.
void addShowOverlays(render::RenderScene& scene, const World& world, const ShowFlags& flags);

}  // namespace af::console
