#pragma once
// Helpers for tests of the .af parser and writer.

#include "af/text/af_parser.h"

#include <gtest/gtest.h>

#include <string>

namespace af::test {

// Parses text that must load without errors; returns its only decl.
inline DeclAF parseOne(const std::string& text) {
    AFParseResult r = parseAF(text, "test.af");
    EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll();
    EXPECT_EQ(r.file.decls.size(), 1u);
    return r.file.decls.empty() ? DeclAF{} : r.file.decls.front();
}

// Wraps items in a decl with a root body, so a test can focus on one item.
inline std::string withRoot(const std::string& items) {
    return "articulatedFigure t {\n"
           "body \"root\" { joint \"origin\" }\n" +
           items + "\n}\n";
}

// The formatted diagnostics of a text that must not load.
inline std::string errorsOf(const std::string& text) {
    AFParseResult r = parseAF(text, "bad.af");
    EXPECT_FALSE(r.ok()) << "expected an error for:\n" << text;
    return r.diagnostics.formatAll();
}

}  // namespace af::test
