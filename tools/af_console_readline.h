#pragma once
// af-console at a terminal: Doom's `] ` prompt read through GNU readline, with line editing,
// history kept across runs and tab completion (console_completion.h).
// Kept apart from af_console.cpp so that only this file sees readline's C headers and globals.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace af::console {

struct TerminalOptions {
    // Where history is read at the start and written at the end; none keeps no history.
    std::optional<std::filesystem::path> historyFile;
    // Lines kept in the history file, so it does not grow without end.
    int historyLines = 1000;
};

// The history file's place: $HOME/.af_console_history, or none when HOME is not set.
std::optional<std::filesystem::path> defaultHistoryFile();

// The words that may complete the last word of the line before the cursor, sorted.
using LineCompleter = std::function<std::vector<std::string>(std::string_view lineBeforeCursor)>;

// Reads lines at the terminal and hands each to `runLine` until it returns false (quit, or a
// strict run's error) or the user ends the input (Ctrl-D). Tab asks `complete`.
void runTerminal(const LineCompleter& complete, const TerminalOptions& options,
                 const std::function<bool(const std::string& line)>& runLine);

}  // namespace af::console
