// Constraint blocks: fixed, ballAndSocketJoint, universalJoint, hinge, slider, spring
// (docs/formats.md §1.7).

#include "af/text/number_format.h"
#include "af_parser_impl.h"

#include <string>

namespace af {

namespace {

// The spring values Doom leaves uninitialised when a file omits them; we require them all.
constexpr const char* kSpringKeys[] = {"stretch", "compress", "damping", "restLength", "minLength", "maxLength"};
constexpr unsigned kAllSpringKeys = (1u << std::size(kSpringKeys)) - 1;

const char* keysOf(ConstraintType type) {
    switch (type) {
    case ConstraintType::Fixed: return "body1, body2";
    case ConstraintType::BallAndSocket: return "body1, body2, anchor, friction, coneLimit, pyramidLimit";
    case ConstraintType::Universal: return "body1, body2, anchor, shafts, friction, coneLimit, pyramidLimit";
    case ConstraintType::Hinge: return "body1, body2, anchor, axis, friction, limit";
    case ConstraintType::Slider: return "body1, body2, axis, friction";
    case ConstraintType::Spring:
        return "body1, body2, anchor1, anchor2, friction, stretch, compress, damping, restLength, minLength, "
               "maxLength";
    }
    return "";
}

}  // namespace

void AFParser::parseConstraint(DeclAF& decl, ConstraintType type) {
    const Token name = in_.expectString("a constraint name");
    in_.expectPunctuation("{", "after the constraint name");

    AFConstraint c;
    c.type = type;
    c.name = name.text;
    c.where = c.body1Where = c.body2Where = name.where;
    c.body1 = firstBodyName_.empty() ? std::string("world") : firstBodyName_;
    c.body2 = "world";
    // Doom's type parsers zero the vectors a type must be given.
    const AFVector zero = AFVector::literal(0, 0, 0);
    if (type == ConstraintType::BallAndSocket) c.shafts[0] = zero;
    if (type == ConstraintType::Universal) c.shafts = {zero, zero};
    if (type == ConstraintType::Hinge) c.axis = zero;

    unsigned springKeys = 0;
    for (;;) {
        const Token key = in_.next();
        if (key.isPunctuation("}")) break;
        springKeys |= parseConstraintKey(c, key);
    }

    if (type == ConstraintType::Spring && springKeys != kAllSpringKeys) {
        std::string missing;
        for (unsigned i = 0; i < std::size(kSpringKeys); ++i) {
            if (springKeys & (1u << i)) continue;
            missing += missing.empty() ? "" : ", ";
            missing += kSpringKeys[i];
        }
        diagnostics().error(name.where, "spring \"" + c.name + "\" lacks " + missing +
                                            " (Doom leaves them undefined; give all six)");
    }
    decl.constraints.push_back(std::move(c));
}

unsigned AFParser::parseConstraintKey(AFConstraint& c, const Token& key) {
    const ConstraintType type = c.type;
    const bool anchored = type == ConstraintType::BallAndSocket || type == ConstraintType::Universal ||
                          type == ConstraintType::Hinge;
    auto angle = [&](std::string_view what) {
        SourceLocation where;
        const Real a = in_.readFloat(what, &where);
        if (a < 0 || a > 360)
            diagnostics().error(where, std::string(what) + " must be between 0 and 360 degrees, found " +
                                           formatDeclFloat(a) + " (a limit beyond a full turn means nothing and "
                                                                "cannot be simulated)");
        return a;
    };

    if (key.isKeyword("body1")) {
        const Token b = in_.expectString("a body name");
        c.body1 = b.text;
        c.body1Where = b.where;
    } else if (key.isKeyword("body2")) {
        const Token b = in_.expectString("a body name");
        c.body2 = b.text;
        c.body2Where = b.where;
    } else if (type != ConstraintType::Fixed && key.isKeyword("friction")) {
        c.friction = readNonNegative("friction", kFrictionFeedsEnergy);
    } else if (anchored && key.isKeyword("anchor")) {
        c.anchor = parseVector("the anchor");
    } else if ((type == ConstraintType::Hinge || type == ConstraintType::Slider) && key.isKeyword("axis")) {
        c.axis = parseVector("the axis");
    } else if (type == ConstraintType::Universal && key.isKeyword("shafts")) {
        c.shafts[0] = parseVector("the first shaft");
        in_.expectPunctuation(",", "between the two shafts");
        c.shafts[1] = parseVector("the second shaft");
    } else if ((type == ConstraintType::BallAndSocket || type == ConstraintType::Universal) &&
               key.isKeyword("coneLimit")) {
        c.limit = LimitType::Cone;
        c.limitAxis = parseVector("the cone axis");
        in_.expectPunctuation(",", "after the cone axis");
        c.limitAngles = {angle("the cone angle"), 0, 0};
        if (type == ConstraintType::BallAndSocket) {
            in_.expectPunctuation(",", "after the cone angle");
            c.shafts[0] = parseVector("the limited shaft");
        }
    } else if ((type == ConstraintType::BallAndSocket || type == ConstraintType::Universal) &&
               key.isKeyword("pyramidLimit")) {
        c.limit = LimitType::Pyramid;
        c.limitAxis = parseVector("the pyramid axis");
        in_.expectPunctuation(",", "after the pyramid axis");
        c.limitAngles[0] = angle("the first pyramid angle");
        in_.expectPunctuation(",", "after the first pyramid angle");
        c.limitAngles[1] = angle("the second pyramid angle");
        in_.expectPunctuation(",", "after the second pyramid angle");
        c.limitAngles[2] = in_.readFloat("the pyramid roll");
        if (type == ConstraintType::BallAndSocket) {
            in_.expectPunctuation(",", "after the pyramid roll");
            c.shafts[0] = parseVector("the limited shaft");
        }
    } else if (type == ConstraintType::Hinge && key.isKeyword("limit")) {
        c.limit = LimitType::Cone;
        c.limitAngles[0] = in_.readFloat("the limit orientation");
        in_.expectPunctuation(",", "after the limit orientation");
        c.limitAngles[1] = angle("the limit width");
        in_.expectPunctuation(",", "after the limit width");
        c.limitAngles[2] = in_.readFloat("the limit shaft angle");
    } else if (type == ConstraintType::Spring && key.isKeyword("anchor1")) {
        c.anchor = parseVector("anchor1");
    } else if (type == ConstraintType::Spring && key.isKeyword("anchor2")) {
        c.anchor2 = parseVector("anchor2");
    } else if (type == ConstraintType::Spring) {
        Real* const values[] = {&c.stretch, &c.compress, &c.damping, &c.restLength, &c.minLength, &c.maxLength};
        for (unsigned i = 0; i < std::size(kSpringKeys); ++i) {
            if (!key.isKeyword(kSpringKeys[i])) continue;
            *values[i] = readNonNegative(kSpringKeys[i], "a negative spring value cannot be simulated");
            return 1u << i;
        }
        in_.fail(key, std::string("a spring key (") + keysOf(type) + ") or '}'");
    } else {
        in_.fail(key, std::string("a ") + toString(type) + " key (" + keysOf(type) + ") or '}'");
    }
    return 0;
}

}  // namespace af
