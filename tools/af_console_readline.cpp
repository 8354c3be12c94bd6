// The interactive loop of af-console (af_console_readline.h): GNU readline for editing, history
// and completion. Readline is a C library with global state, so the completer it asks is held in
// a file-local pointer for the duration of runTerminal.

#include "af_console_readline.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string_view>
#include <vector>

#include <readline/history.h>
#include <readline/readline.h>

namespace af::console {

namespace {

// Doom's console prompt.
constexpr const char* kPrompt = "] ";

const LineCompleter* lineCompleter = nullptr;
std::vector<std::string> completionCandidates;

// Readline calls this with state 0 for the first match and then for each next one; it frees
// what it is given, so each match is malloc'd.
char* nextCandidate(const char*, int state) {
    static std::size_t next = 0;
    if (state == 0) next = 0;
    if (next >= completionCandidates.size()) return nullptr;
    return strdup(completionCandidates[next++].c_str());
}

// The console completes the last word of the line before the cursor and already keeps only the
// candidates that fit it, so readline is told not to fall back to file names.
char** completeLine(const char* text, int, int end) {
    rl_attempted_completion_over = 1;
    if (!lineCompleter) return nullptr;
    completionCandidates = (*lineCompleter)(std::string_view(rl_line_buffer, std::size_t(end)));
    if (completionCandidates.empty()) return nullptr;
    return rl_completion_matches(text, nextCandidate);
}

// Frees readline's line however the loop leaves.
struct LineBuffer {
    char* text = nullptr;
    ~LineBuffer() { std::free(text); }
};

}  // namespace

std::optional<std::filesystem::path> defaultHistoryFile() {
    const char* home = std::getenv("HOME");
    if (!home || !*home) return std::nullopt;
    return std::filesystem::path(home) / ".af_console_history";
}

void runTerminal(const LineCompleter& complete, const TerminalOptions& options,
                 const std::function<bool(const std::string& line)>& runLine) {
    rl_readline_name = "af-console";  // for `$if af-console` in ~/.inputrc
    // Words end where the console's do (command_line.h): at spaces and `;`; a `"` opens a
    // quoted word, which readline then completes inside the quote.
    static char wordBreaks[] = " \t\n;";
    static char quotes[] = "\"";
    rl_completer_word_break_characters = wordBreaks;
    rl_completer_quote_characters = quotes;
    rl_attempted_completion_function = completeLine;
    lineCompleter = &complete;

    using_history();
    stifle_history(options.historyLines);
    const std::string history = options.historyFile ? options.historyFile->string() : std::string();
    if (!history.empty()) read_history(history.c_str());  // a first run has none: not an error

    for (;;) {
        std::cout.flush();  // what the last command printed comes before the prompt
        LineBuffer line{readline(kPrompt)};
        if (!line.text) {
            std::cout << '\n';  // Ctrl-D leaves the cursor after the prompt
            break;
        }
        const std::string text = line.text;
        // A blank line or the same line again would only make the history longer to scroll.
        if (text.find_first_not_of(" \t") != std::string::npos) {
            const HIST_ENTRY* last = history_length > 0 ? history_get(history_base + history_length - 1) : nullptr;
            if (!last || text != last->line) add_history(text.c_str());
        }
        if (!runLine(text)) break;
    }

    if (!history.empty()) {
        // write_history replaces the file with the session's list, which starts with what was
        // read, so histories of runs at two terminals do not merge: the last to end wins.
        if (write_history(history.c_str()) == 0) history_truncate_file(history.c_str(), options.historyLines);
        else std::cerr << "af-console: warning: cannot write the history file " << history << '\n';
    }
    lineCompleter = nullptr;
}

}  // namespace af::console
