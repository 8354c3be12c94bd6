#pragma once
// af-console's `screenshot FILE`: the session's world drawn with af-sim's renderer.

#include "console/command_system.h"
#include "console/session.h"
#include "console/session_show.h"
#include "render/render.h"

namespace af::console {

void addScreenshotCommand(CommandSystem& console, const Session& session);

// What the picture shows: the session's bodies (in the world's order) over its statics or floor,
// with the overlays `flags` asks for.
render::RenderScene screenshotScene(const Session& session, const ShowFlags& flags);

}  // namespace af::console
