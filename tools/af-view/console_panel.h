#pragma once
// The console as an ImGui panel: what commands print (errors in red), an input line with history
// (up and down arrows) and tab completion, as af-console's prompt has (console_completion.h).

#include "console/command_system.h"
#include "console/session.h"

#include <deque>
#include <string>
#include <vector>

struct ImGuiInputTextCallbackData;

namespace af::view {

class ConsolePanel {
public:
    // Lines to show; the console's Output sinks call these.
    void info(std::string_view line) { add(line, false); }
    void error(std::string_view line) { add(line, true); }

    // Draws the panel in the rectangle given (pixels), and runs a line entered there.
    void draw(console::CommandSystem& console, const console::Session& session, float x, float y, float width, float height);

private:
    struct Line {
        std::string text;
        bool error = false;
    };
    void add(std::string_view text, bool error);
    int onInput(ImGuiInputTextCallbackData& data);

    std::deque<Line> lines_;
    std::vector<std::string> history_;
    int historyPosition_ = -1;  // -1: the line being typed, not one of history_
    std::string input_;
    bool scrollToEnd_ = false;
    bool refocus_ = true;
    console::CommandSystem* console_ = nullptr;  // during draw, for the completion callback
    const console::Session* session_ = nullptr;
};

}  // namespace af::view
