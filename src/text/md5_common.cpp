#include "md5_common.h"


namespace af::md5detail {

void failAt(TokenReader& in, SourceLocation where, const std::string& message) {
    in.diagnostics().error(where, message);
    throw ParseAbort{};
}

void expectKeyword(TokenReader& in, std::string_view keyword, std::string_view context) {
    const Token t = in.next();
    if (t.type == TokenType::Name && t.text == keyword) return;
    std::string expected = "'" + std::string(keyword) + "'";
    if (!context.empty()) expected += " " + std::string(context);
    in.fail(t, expected);
}

std::string readHeader(TokenReader& in) {
    expectKeyword(in, "MD5Version", "at the start of the file");
    const Token version = in.next();
    if (!version.isInteger() || version.numberValue() != 10) in.fail(version, "MD5Version 10");
    expectKeyword(in, "commandline");
    return std::string(in.expectString("the command line").text);
}

int readCount(TokenReader& in, std::string_view keyword, int minimum) {
    expectKeyword(in, keyword);
    SourceLocation where;
    const int n = in.readInt(keyword, &where);
    if (n < minimum) {
        failAt(in, where, "expected " + std::string(keyword) + (minimum == 0 ? " of 0 or more" : " greater than 0") +
                              ", found '" + std::to_string(n) + "'");
    }
    return n;
}

void readTuple(TokenReader& in, Real* values, int count, std::string_view what) {
    in.expectPunctuation("(", "before " + std::string(what));
    for (int i = 0; i < count; ++i) values[i] = in.readFloat(what);
    in.expectPunctuation(")", "after the " + std::to_string(count) + " values of " + std::string(what));
}

Real3 readTuple3(TokenReader& in, std::string_view what) {
    Real3 v{};
    readTuple(in, v.data(), 3, what);
    return v;
}

Md5Quat readQuat(TokenReader& in, std::string_view what) {
    const Real3 xyz = readTuple3(in, what);
    return md5QuatFromXyz(xyz[0], xyz[1], xyz[2]);
}

Token readWord(TokenReader& in, std::string_view what) {
    const Token t = in.next();
    if (t.type != TokenType::String && t.type != TokenType::Name) in.fail(t, what);
    return t;
}

void expectEnd(TokenReader& in, std::string_view after) {
    const Token t = in.next();
    if (t.type != TokenType::End) in.fail(t, "end of file after " + std::string(after));
}

}  // namespace af::md5detail
