#include "af/text/diagnostics.h"

#include <algorithm>

namespace af {

std::string Diagnostic::format() const {
    std::string out = file.empty() ? std::string("<input>") : file;
    if (where.line > 0) {
        out += ':' + std::to_string(where.line);
        if (where.column > 0) out += ':' + std::to_string(where.column);
    }
    out += severity == Severity::Error ? ": error: " : ": warning: ";
    out += message;
    return out;
}

void Diagnostics::error(SourceLocation where, std::string message) {
    items_.push_back({Severity::Error, file_, where, std::move(message)});
    ++errors_;
}

void Diagnostics::warning(SourceLocation where, std::string message) {
    items_.push_back({Severity::Warning, file_, where, std::move(message)});
}

void Diagnostics::sortByPosition() {
    std::stable_sort(items_.begin(), items_.end(), [](const Diagnostic& a, const Diagnostic& b) {
        return a.where.line != b.where.line ? a.where.line < b.where.line : a.where.column < b.where.column;
    });
}

std::string Diagnostics::formatAll() const {
    std::string out;
    for (const Diagnostic& d : items_) {
        out += d.format();
        out += '\n';
    }
    return out;
}

}  // namespace af
