// Splitting console text into commands and words (command_line.h). One scanner reads a line;
// splitCommands keeps every finished command, splitForCompletion keeps the unfinished one at
// the cursor.

#include "console/command_line.h"

namespace af::console {

namespace {

// Control characters and space separate words, as Doom's lexer skips them; line breaks never
// reach the scanner.
bool isSpace(char c) { return static_cast<unsigned char>(c) <= ' '; }

// The commands of one line, and where the scan stopped: in a word, in a quote, or between words.
class LineScanner {
public:
    explicit LineScanner(int lineNumber) : line_(lineNumber) {}

    void scan(std::string_view text) {
        for (std::size_t i = 0; i < text.size(); ++i) {
            const char c = text[i];
            const int column = static_cast<int>(i) + 1;
            if (inQuote_) {
                if (c == '"') inQuote_ = false;
                else word_ += c;
            } else if (c == '"') {
                startWord(column);
                inQuote_ = true;
                quoteColumn_ = column;
            } else if (c == ';') {
                endCommand();
            } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
                break;  // a comment runs to the end of the line
            } else if (isSpace(c)) {
                endWord();
            } else {
                startWord(column);
                word_ += c;
            }
        }
    }

    // Ends the line: the last command is finished unless a quote is still open.
    void finish() {
        if (!inQuote_) endCommand();
    }

    bool inQuote() const { return inQuote_; }
    int quoteColumn() const { return quoteColumn_; }
    bool inWord() const { return inWord_; }
    const std::string& word() const { return word_; }
    const std::vector<std::string>& currentWords() const { return current_.words; }
    std::vector<CommandText>& commands() { return commands_; }

private:
    void startWord(int column) {
        if (inWord_) return;
        inWord_ = true;
        if (current_.words.empty()) current_.where = {line_, column};
    }
    void endWord() {
        if (!inWord_) return;
        current_.words.push_back(std::move(word_));
        word_.clear();
        inWord_ = false;
    }
    void endCommand() {
        endWord();
        if (!current_.words.empty()) commands_.push_back(std::move(current_));
        current_ = {};
    }

    int line_;
    std::vector<CommandText> commands_;
    CommandText current_;
    std::string word_;
    bool inWord_ = false;  // a quote starts a word, so `""` is an empty word
    bool inQuote_ = false;
    int quoteColumn_ = 0;
};

// Calls `onLine(line, number)` for every line of `text`; "\n", "\r\n" and a lone "\r" end lines
// (diagnostics.h).
template <class OnLine>
void forEachLine(std::string_view text, OnLine onLine) {
    int number = 1;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find_first_of("\r\n", start);
        onLine(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start), number);
        if (end == std::string_view::npos) return;
        start = end + 1;
        if (text[end] == '\r' && start < text.size() && text[start] == '\n') ++start;
        ++number;
    }
}

}  // namespace

SplitResult splitCommands(std::string_view text) {
    SplitResult result;
    forEachLine(text, [&](std::string_view line, int number) {
        LineScanner scanner(number);
        scanner.scan(line);
        scanner.finish();
        if (scanner.inQuote()) {
            result.errors.push_back({{number, scanner.quoteColumn()}, "unterminated quote"});
            return;
        }
        for (CommandText& command : scanner.commands()) result.commands.push_back(std::move(command));
    });
    return result;
}

PartialCommand splitForCompletion(std::string_view lineBeforeCursor) {
    // Only the text after the last line break matters; the scanner finds the last `;` itself.
    const std::size_t lastBreak = lineBeforeCursor.find_last_of("\r\n");
    if (lastBreak != std::string_view::npos) lineBeforeCursor.remove_prefix(lastBreak + 1);
    LineScanner scanner(1);
    scanner.scan(lineBeforeCursor);
    PartialCommand partial;
    partial.words = scanner.currentWords();
    if (scanner.inWord()) partial.partial = scanner.word();
    return partial;
}

PlusCommands parsePlusCommands(const std::vector<std::string>& arguments) {
    PlusCommands result;
    for (const std::string& argument : arguments) {
        if (argument.starts_with('+')) {
            result.commands.push_back({{argument.substr(1)}, {}});
        } else if (result.commands.empty()) {
            result.leading.push_back(argument);
        } else {
            result.commands.back().words.push_back(argument);
        }
    }
    return result;
}

}  // namespace af::console
