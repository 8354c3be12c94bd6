// The load-time guards of docs/figures.md §3.4.1: a figure that cannot be simulated (no volume,
// no mass, a singular inertia, a zero axis) is one error at the key that caused it; one Doom 3
// loads but that is suspicious (an absurd density, coincident spring anchors) one warning. Never
// a crash, never a silent default, and a figure that passes has finite, positive masses and
// invertible inertias.

#include "figure_test_util.h"

#include <Eigen/Eigenvalues>

#include <sstream>

namespace af {
namespace {

// Two bodies on the humanoid's af_pose, apart: a root box at the pelvis and the left hand at the
// model's origin, hinged together; `hand` and `joint` replace the hand's keys and the hinge's,
// line 4 and lines 6-7 of the text.
std::string figureText(const std::string& hand, const std::string& joint = "axis ( 0, 0, 1 )") {
    return "articulatedFigure g {\n"
           "body \"root\" { joint \"origin\" origin joint( \"pelvis\" ) model box( ( -5, -5, -5 ), ( 5, 5, 5 ) ) "
           "containedJoints \"*origin -*lhand\" }\n"
           "body \"hand\" {\n"
           "\tjoint \"lhand\" containedJoints \"*lhand\" " + hand + "\n"
           "}\n"
           "hinge \"wrist\" { body1 \"hand\" body2 \"root\" anchor joint( \"lhand\" )\n"
           "\t" + joint + " }\n"
           "}\n";
}

FigureResult build(const std::string& text) {
    const AFParseResult parsed = parseAF(text, "g.af");
    EXPECT_TRUE(parsed.ok()) << parsed.diagnostics.formatAll();
    return buildFigure(parsed.file.decls.at(0), test::humanoidPose(), "g.af");
}

// The diagnostics of one severity, one formatted line each.
std::string linesOf(const FigureResult& r, Severity severity) {
    std::string out;
    for (const Diagnostic& d : r.diagnostics)
        if (d.severity == severity) out += d.format() + "\n";
    return out;
}

void expectSimulable(const Figure& figure) {
    for (const FigureBody& b : figure.bodies) {
        EXPECT_TRUE(std::isfinite(b.mass) && b.mass > 0) << b.name << " mass " << b.mass;
        ASSERT_TRUE(b.inertia.allFinite()) << b.name;
        const Vec3 moments = Eigen::SelfAdjointEigenSolver<Mat3>(0.5 * (b.inertia + b.inertia.transpose())).eigenvalues();
        EXPECT_GT(moments[0], 1e-12 * moments[2]) << b.name << " moments " << moments.transpose();
    }
}

TEST(FigureGuards, TheTwoBodyFigureItselfPassesWithoutAWord) {
    const FigureResult r = build(figureText("model box( ( -2, -2, -2 ), ( 2, 2, 2 ) )"));
    ASSERT_TRUE(r.ok()) << r.formatDiagnostics();
    EXPECT_EQ(r.formatDiagnostics(), "");
    expectSimulable(*r.figure);
}

TEST(FigureGuards, AFlatBoxIsAnErrorAtItsShape) {
    const FigureResult r = build(figureText("model box( ( -2, -2, 0 ), ( 2, 2, 0 ) )"));
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(linesOf(r, Severity::Error),
              "g.af:4:47: error: body \"hand\": the box has no volume (its extents are 4 x 4 x 0 units); the figure "
              "cannot be simulated (Doom 3 would use mass 1 and unit inertia)\n");
}

TEST(FigureGuards, ABoneOfZeroLengthIsAnErrorAtItsShape) {
    const FigureResult r = build(figureText("model bone( joint( \"lhand\" ), joint( \"LHAND\" ), 3 )"));
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(linesOf(r, Severity::Error),
              "g.af:4:47: error: body \"hand\": the bone has no volume (its extents are 3 x 2.25 x 0 units); the "
              "figure cannot be simulated (Doom 3 would use mass 1 and unit inertia)\n");
}

// A width of zero is refused by the parser already, at the number (docs/formats.md §1.6).
TEST(FigureGuards, ABoneOfZeroWidthIsRefusedAtTheWidth) {
    const AFParseResult r = parseAF(figureText("model bone( joint( \"lloarm\" ), joint( \"lhand\" ), 0 )"), "g.af");
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.diagnostics.formatAll(), "g.af:4:90: error: the bone width must be greater than 0, found 0 (a bone "
                                         "without volume cannot be simulated)\n");
}

// The parser refuses density <= 0; a decl made in code is refused when it is built, at the
// density when one was written and at the body's name otherwise.
TEST(FigureGuards, ZeroOrNegativeMassIsAnErrorEvenForADeclMadeInCode) {
    const AFParseResult parsed = parseAF(figureText("model box( ( -2, -2, -2 ), ( 2, 2, 2 ) ) density 1"), "g.af");
    ASSERT_TRUE(parsed.ok());
    for (const Real density : {Real(0), Real(-1)}) {
        DeclAF d = parsed.file.decls.at(0);
        d.bodies[1].density = density;
        const FigureResult r = buildFigure(d, test::humanoidPose(), "g.af");
        EXPECT_FALSE(r.ok());
        EXPECT_EQ(linesOf(r, Severity::Error), "g.af:4:90: error: body \"hand\": density times volume is not a "
                                               "positive mass; the figure cannot be simulated\n");
    }
}

TEST(FigureGuards, AnInertiaScaleThatMakesTheInertiaSingularIsAnErrorAtIt) {
    for (const char* scale : {"( 0 0 0 0 1 0 0 0 1 )", "( 1 0 0 0 -1 0 0 0 1 )"}) {
        const FigureResult r =
            build(figureText(std::string("model box( ( -2, -2, -2 ), ( 2, 2, 2 ) ) inertiaScale ") + scale));
        EXPECT_FALSE(r.ok()) << scale;
        const std::string errors = linesOf(r, Severity::Error);
        EXPECT_EQ(errors.rfind("g.af:4:95: error: body \"hand\": its inertia is singular (principal moments ", 0), 0u)
            << errors;
        EXPECT_NE(errors.find("); the figure cannot be simulated\n"), std::string::npos) << errors;
    }
}

// Doom 3 loads it; the body is 1e29 times heavier than its neighbour. A warning at the density,
// and the figure still builds with finite masses.
TEST(FigureGuards, AnAbsurdDensityIsAWarningAtTheValue) {
    const FigureResult r = build(figureText("model box( ( -2, -2, -2 ), ( 2, 2, 2 ) ) density 1e30"));
    ASSERT_TRUE(r.ok()) << r.formatDiagnostics();
    EXPECT_NE(r.formatDiagnostics().find("g.af:4:90: warning: body \"hand\": density 1e+30 is absurd (the default is "
                                         "0.2; 1e-4 to 1e4 passes without a word); Doom 3 loads it, but the body's "
                                         "mass will swamp or vanish beside the others\n"),
              std::string::npos)
        << r.formatDiagnostics();
    expectSimulable(*r.figure);
}

TEST(FigureGuards, AZeroAxisOnTheSkeletonIsAnErrorAtTheAxis) {
    const FigureResult r =
        build(figureText("model box( ( -2, -2, -2 ), ( 2, 2, 2 ) )", "axis bonedir( \"lhand\", \"lhand\" )"));
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(linesOf(r, Severity::Error), "g.af:7:7: error: hinge \"wrist\": the axis is a zero vector on this "
                                           "skeleton, so the joint cannot be simulated\n");
}

TEST(FigureGuards, CoincidentSpringAnchorsAreAWarningAtTheSecondAnchor) {
    const std::string text = "articulatedFigure g {\n"
                             "body \"root\" { joint \"origin\" containedJoints \"*origin -*lhand\" }\n"
                             "body \"hand\" { joint \"lhand\" containedJoints \"*lhand\" }\n"
                             "spring \"s\" { body1 \"hand\" body2 \"root\" anchor1 joint( \"lhand\" )\n"
                             "\tanchor2 joint( \"lhand\" ) stretch 1 compress 1 damping 0 restLength 0 minLength 0 "
                             "maxLength 0 }\n"
                             "}\n";
    const FigureResult r = build(text);
    ASSERT_TRUE(r.ok()) << r.formatDiagnostics();
    EXPECT_NE(r.formatDiagnostics().find("g.af:5:10: warning: spring \"s\": anchor1 and anchor2 coincide at spawn, so "
                                         "the spring has no direction until its bodies move apart\n"),
              std::string::npos)
        << r.formatDiagnostics();
}

// Whatever passes the guards is something the World can integrate: the sample figures, and the
// humanoid with extreme but accepted densities and total masses.
TEST(FigureGuards, EveryFigureThatPassesHasFinitePositiveMassesAndInvertibleInertias) {
    for (const Real density : {Real(1e-30f), Real(0.2f), Real(1e30f)}) {
        for (const Real totalMass : {Real(-1), Real(1e-30f), Real(3e38f)}) {
            DeclAF d = test::humanoidDecl();
            for (AFBody& b : d.bodies) b.density = density;
            d.settings.totalMass = totalMass;
            const FigureResult r = buildFigure(d, test::humanoidPose(), "h.af");
            ASSERT_TRUE(r.ok()) << density << " " << totalMass << "\n" << r.formatDiagnostics();
            expectSimulable(*r.figure);
        }
    }
}

}  // namespace
}  // namespace af
