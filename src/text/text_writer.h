#pragma once
// What the canonical writers (.af, .md5anim, .map) share: text appended to one string, numbers
// in the house format (af/text/number_format.h), calls chained. Each writer derives from it with
// its own type as the parameter, so that a chain keeps reaching the format's own pieces.

#include "af/text/number_format.h"

#include <string>
#include <string_view>

namespace af::text_detail {

template <class Writer>
class TextWriter {
public:
    std::string take() { return std::move(out_); }

    Writer& raw(std::string_view s) {
        out_ += s;
        return static_cast<Writer&>(*this);
    }
    Writer& num(Real v) { return raw(formatDeclFloat(v)); }
    Writer& integer(int v) { return raw(std::to_string(v)); }
    Writer& quoted(std::string_view s) { return raw("\"").raw(s).raw("\""); }

private:
    std::string out_;
};

}  // namespace af::text_detail
