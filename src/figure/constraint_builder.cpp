// Constraints in world space at spawn (docs/figures.md §3.8); the limits stay as written.

#include "af/text/strings.h"
#include "figure_build_context.h"

namespace af {

namespace {

// Anchors closer than this (units) are one point: far below any modelled length.
constexpr Real kCoincidentAnchors = 1e-6;

}  // namespace

void buildConstraints(FigureBuildContext& context, Figure& figure) {
    for (const AFConstraint& c : context.decl.constraints) {
        const std::string label = std::string(toString(c.type)) + " \"" + c.name + "\"";
        FigureConstraint out;
        out.type = c.type;
        out.name = c.name;
        out.where = c.where;
        out.body1 = figure.findBody(c.body1);
        if (out.body1 < 0) {
            context.diagnostics.error(c.body1Where, label + ": body1 \"" + c.body1 + "\" is not a body of the figure");
            continue;
        }
        // Doom attaches an unknown body2 to the world; the parser has warned about it.
        out.body2 = equalsIgnoreCase(c.body2, "world") ? kWorld : figure.findBody(c.body2);
        out.friction = c.friction;
        out.limit = c.limit;
        out.limitAngles = c.limitAngles;

        switch (c.type) {
        case ConstraintType::Fixed: break;
        case ConstraintType::BallAndSocket:
            out.anchor = context.worldPoint(c.anchor);
            if (c.limit != LimitType::None) out.shafts[0] = context.worldDirection(c.shafts[0], label + ": the limited shaft");
            break;
        case ConstraintType::Universal:
            out.anchor = context.worldPoint(c.anchor);
            out.shafts[0] = context.worldDirection(c.shafts[0], label + ": the first shaft");
            out.shafts[1] = context.worldDirection(c.shafts[1], label + ": the second shaft");
            break;
        case ConstraintType::Hinge:
            out.anchor = context.worldPoint(c.anchor);
            out.axis = context.worldDirection(c.axis, label + ": the axis");
            break;
        case ConstraintType::Slider: out.axis = context.worldDirection(c.axis, label + ": the axis"); break;
        case ConstraintType::Spring:
            out.anchor = context.worldPoint(c.anchor);
            out.anchor2 = context.worldPoint(c.anchor2);
            // Doom 3 loads it, and the spring works once the bodies move, but until then it has no
            // direction to pull along: suspicious rather than broken (docs/figures.md §3.8).
            if ((out.anchor2 - out.anchor).norm() <= kCoincidentAnchors)
                context.diagnostics.warning(c.anchor2.where.line ? c.anchor2.where : c.where,
                                            label + ": anchor1 and anchor2 coincide at spawn, so the spring has "
                                                    "no direction until its bodies move apart");
            out.stretch = c.stretch;
            out.compress = c.compress;
            out.damping = c.damping;
            out.restLength = c.restLength;
            out.minLength = c.minLength;
            out.maxLength = c.maxLength;
            break;
        }
        if (c.limit != LimitType::None && c.type != ConstraintType::Hinge)
            out.limitAxis = context.worldDirection(c.limitAxis, label + ": the limit axis");
        figure.constraints.push_back(std::move(out));
    }
}

}  // namespace af
