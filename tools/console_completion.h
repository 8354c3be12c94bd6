#pragma once
// What tab completes at af-console's prompt: the console's own candidates (commands, cvars and
// their values, entityDefs, entity names) and, where an argument names a part of a ragdoll, the
// session's names: an entity's bodies after `drag ENTITY`, every ragdoll's bodies as the value of
// af_highlightBody and its constraints as the value of af_highlightConstraint.

#include "console/command_system.h"
#include "console/session.h"

#include <string>
#include <string_view>
#include <vector>

namespace af::console {

// The words that may complete the last word of `lineBeforeCursor`, sorted ignoring case, as
// CommandSystem::complete gives them.
std::vector<std::string> completeConsoleLine(const CommandSystem& console, const Session& session, std::string_view lineBeforeCursor);

}  // namespace af::console
