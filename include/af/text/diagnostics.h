#pragma once
// Diagnostics: every problem found in a text file, with the place it was found.
// Printed as `file:line:col: error: message` (or `warning:`), the form compilers use, so
// editors and CI logs can jump to the spot.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace af {

// A place in a text file. Lines and columns count from 1; a column counts bytes (a tab is one
// column). Line breaks are "\n", "\r\n" and a lone "\r". Zero means "no particular place".
struct SourceLocation {
    int line = 0;
    int column = 0;

    friend bool operator==(const SourceLocation&, const SourceLocation&) = default;
};

enum class Severity { Warning, Error };

struct Diagnostic {
    Severity severity = Severity::Error;
    std::string file;
    SourceLocation where;
    std::string message;

    // `file:line:col: error: message`; the position is left out when it is unknown.
    std::string format() const;
};

// Collects the diagnostics of one file, in the order they were found.
class Diagnostics {
public:
    explicit Diagnostics(std::string fileName = {}) : file_(std::move(fileName)) {}

    void error(SourceLocation where, std::string message);
    void warning(SourceLocation where, std::string message);

    const std::string& fileName() const { return file_; }
    const std::vector<Diagnostic>& all() const { return items_; }
    std::size_t errorCount() const { return errors_; }
    std::size_t warningCount() const { return items_.size() - errors_; }
    bool hasErrors() const { return errors_ > 0; }

    // Orders the diagnostics by line and column (stable), as a reader goes through the file.
    void sortByPosition();

    // Every diagnostic, one formatted line each.
    std::string formatAll() const;

private:
    std::string file_;
    std::vector<Diagnostic> items_;
    std::size_t errors_ = 0;
};

}  // namespace af
