#pragma once
// af-console's `screenshot FILE`: the session's world drawn with af-sim's renderer.

#include "console/command_system.h"
#include "console/session.h"

namespace af::console {

void addScreenshotCommand(CommandSystem& console, const Session& session);

}  // namespace af::console
