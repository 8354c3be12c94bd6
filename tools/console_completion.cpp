// Tab completion at af-console's prompt (console_completion.h). The session's names are added
// here rather than by the commands' completers because two of the places a body is named are
// cvar values, which the command system completes only from a cvar's allowed values.

#include "console_completion.h"

#include "console/command_line.h"

#include "af/text/strings.h"

#include <algorithm>

namespace af::console {

namespace {

// The cvar whose value is being typed: `NAME value` or `set NAME value` (seta, toggle too).
std::string_view cvarBeingSet(const std::vector<std::string>& words) {
    if (words.size() == 1) return words[0];
    if (words.size() == 2 && (equalsIgnoreCase(words[0], "set") || equalsIgnoreCase(words[0], "seta") || equalsIgnoreCase(words[0], "toggle")))
        return words[1];
    return {};
}

std::vector<std::string> sessionNames(const Session& session, const std::vector<std::string>& words) {
    if (words.size() == 2 && equalsIgnoreCase(words[0], "drag")) return session.bodyNames(words[1]);
    const std::string_view cvar = cvarBeingSet(words);
    const bool bodies = equalsIgnoreCase(cvar, "af_highlightBody"), constraints = equalsIgnoreCase(cvar, "af_highlightConstraint");
    std::vector<std::string> names;
    if (!bodies && !constraints) return names;
    const World& world = session.world();
    for (const FigureId id : world.figureIds()) {
        const Figure& figure = world.definition(id);
        if (bodies)
            for (const FigureBody& b : figure.bodies) names.push_back(b.name);
        if (constraints)
            for (const FigureConstraint& c : figure.constraints) names.push_back(c.name);
    }
    return names;
}

}  // namespace

std::vector<std::string> completeConsoleLine(const CommandSystem& console, const Session& session, std::string_view lineBeforeCursor) {
    std::vector<std::string> candidates = console.complete(lineBeforeCursor);
    const PartialCommand typed = splitForCompletion(lineBeforeCursor);
    for (std::string& name : sessionNames(session, typed.words))
        if (name.size() >= typed.partial.size() && equalsIgnoreCase(std::string_view(name).substr(0, typed.partial.size()), typed.partial))
            candidates.push_back(std::move(name));
    std::sort(candidates.begin(), candidates.end(), [](const std::string& a, const std::string& b) {
        return std::pair(toLower(a), a) < std::pair(toLower(b), b);
    });
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    return candidates;
}

}  // namespace af::console
