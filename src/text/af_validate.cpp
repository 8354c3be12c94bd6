// Checks that need the whole decl (docs/formats.md §1.3, §1.8), and the origin-body swap.

#include "af/text/number_format.h"
#include "af/text/strings.h"
#include "af_parser_impl.h"

#include <map>
#include <utility>

namespace af {

namespace {

void checkUniqueNames(const DeclAF& decl, Diagnostics& diagnostics) {
    // Case-sensitive, as Doom compares them.
    std::map<std::string, SourceLocation> seen;
    for (const AFBody& b : decl.bodies) {
        auto [it, fresh] = seen.emplace(b.name, b.where);
        if (!fresh)
            diagnostics.error(b.where, "a second body named \"" + b.name + "\" (the first is at line " +
                                           std::to_string(it->second.line) + ")");
    }
    seen.clear();
    for (const AFConstraint& c : decl.constraints) {
        auto [it, fresh] = seen.emplace(c.name, c.where);
        if (!fresh)
            diagnostics.error(c.where, "a second constraint named \"" + c.name + "\" (the first is at line " +
                                           std::to_string(it->second.line) + ")");
    }
}

void checkBodyReferences(const DeclAF& decl, const AFConstraint& c, Diagnostics& diagnostics) {
    const std::string label = std::string(toString(c.type)) + " \"" + c.name + "\"";
    const bool body1Valid = !c.body1.empty() && !equalsIgnoreCase(c.body1, "world") && decl.findBody(c.body1);
    if (!body1Valid) {
        std::string message = label + ": body1 must name a body of this figure, found \"" + c.body1 + "\"";
        if (c.body1Where == c.where) message += " (body1 was not given)";
        diagnostics.error(c.body1Where, message);
    }
    if (c.body2.empty()) {
        diagnostics.error(c.body2Where, label + ": body2 is empty; name a body or \"world\"");
    } else if (!equalsIgnoreCase(c.body2, "world") && !decl.findBody(c.body2)) {
        diagnostics.warning(c.body2Where, label + ": body2 \"" + c.body2 +
                                              "\" is not a body of this figure; it is attached to the world, as in "
                                              "Doom 3");
    }
    if (body1Valid && c.body1 == c.body2) diagnostics.error(c.body1Where, label + " joins body \"" + c.body1 + "\" to itself (such a joint cannot be simulated)");
}

void checkNonZero(const AFVector& v, const std::string& what, SourceLocation fallback, Diagnostics& diagnostics) {
    if (v.isZeroLiteral())
        diagnostics.error(v.where.line ? v.where : fallback, what + " must not be zero (the joint cannot be simulated)");
}

void checkConstraintValues(const AFConstraint& c, Diagnostics& diagnostics) {
    const std::string label = std::string(toString(c.type)) + " \"" + c.name + "\"";
    switch (c.type) {
    case ConstraintType::Universal:
        checkNonZero(c.shafts[0], label + ": the first shaft", c.where, diagnostics);
        checkNonZero(c.shafts[1], label + ": the second shaft", c.where, diagnostics);
        break;
    case ConstraintType::Hinge:
    case ConstraintType::Slider:
        checkNonZero(c.axis, label + ": the axis", c.where, diagnostics);
        break;
    case ConstraintType::BallAndSocket:
        if (c.limit != LimitType::None) checkNonZero(c.shafts[0], label + ": the limited shaft", c.where, diagnostics);
        break;
    case ConstraintType::Spring:
        if (c.minLength > c.maxLength)
            diagnostics.error(c.where, label + ": minLength " + formatDeclFloat(c.minLength) +
                                           " is greater than maxLength " + formatDeclFloat(c.maxLength) +
                                           " (no length satisfies both, so the spring cannot be simulated)");
        break;
    case ConstraintType::Fixed: break;
    }
    if (c.limit != LimitType::None && c.type != ConstraintType::Hinge)
        checkNonZero(c.limitAxis, label + ": the limit axis", c.where, diagnostics);
}

// Doom swaps the first body whose joint is exactly "origin" into slot 0, and refuses a figure
// without one.
void moveOriginBodyFirst(DeclAF& decl, Diagnostics& diagnostics) {
    for (std::size_t i = 0; i < decl.bodies.size(); ++i) {
        if (decl.bodies[i].joint != "origin") continue;
        if (i != 0) std::swap(decl.bodies[0], decl.bodies[i]);
        return;
    }
    for (const AFBody& b : decl.bodies) {
        if (equalsIgnoreCase(b.joint, "origin")) {
            diagnostics.error(b.where, "the root body's joint must be spelled \"origin\", found \"" + b.joint + "\"");
            return;
        }
    }
    diagnostics.error(decl.where, "figure \"" + decl.name + "\" has no body with joint \"origin\"; its root body needs one");
}

}  // namespace

void validateDecl(DeclAF& decl, Diagnostics& diagnostics) {
    checkUniqueNames(decl, diagnostics);
    for (const AFConstraint& c : decl.constraints) {
        checkBodyReferences(decl, c, diagnostics);
        checkConstraintValues(c, diagnostics);
    }
    moveOriginBodyFirst(decl, diagnostics);
}

}  // namespace af
