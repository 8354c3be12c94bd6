#pragma once
// Console text split into commands and words, as Doom's command buffer splits it
// (docs/doom-physics.md §5.1): a line break or a `;` ends a command, `//` starts a comment to the
// end of the line, and a double-quoted stretch keeps its spaces, `;` and `//`. There are no
// escapes, as in Doom; a quote cannot span lines. Also the process's `+command args` arguments.
// Nothing here runs anything: CommandSystem does that.

#include "af/text/diagnostics.h"

#include <string>
#include <string_view>
#include <vector>

namespace af::console {

// One command as written: its words (the first is the command's name) and where it starts.
// `where` is zero for commands that came from process arguments.
struct CommandText {
    std::vector<std::string> words;
    SourceLocation where;
};

struct SyntaxError {
    SourceLocation where;
    std::string message;
};

struct SplitResult {
    std::vector<CommandText> commands;
    std::vector<SyntaxError> errors;  // one per broken line, in order

    bool ok() const { return errors.empty(); }
};

// Every command of `text`, empty ones (blank lines, `;;`, comments) left out. A line with an
// unterminated quote is an error located at the opening quote; the commands of that line are
// left out, the others are kept (the caller decides whether to run any of them).
SplitResult splitCommands(std::string_view text);

// The command a cursor is in, for completion: the words before the one being typed and what
// has been typed of it so far (empty after a space). An open quote is allowed: `exec "my fi`
// gives words {"exec"} and partial "my fi".
struct PartialCommand {
    std::vector<std::string> words;
    std::string partial;
};
PartialCommand splitForCompletion(std::string_view lineBeforeCursor);

// The process's arguments (without the program's name) as Doom's engine reads them: every
// argument that starts with `+` starts a command named by the rest of it, and the arguments
// that follow are its words. `+` alone gives a command with an empty name, which the command
// system reports as unknown.
struct PlusCommands {
    std::vector<std::string> leading;  // before the first `+`: the program's own arguments
    std::vector<CommandText> commands;
};
PlusCommands parsePlusCommands(const std::vector<std::string>& arguments);

}  // namespace af::console
