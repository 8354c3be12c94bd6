// Malformed .af text: every problem is one error at its place, and nothing crashes.

#include "af_test_util.h"

namespace af {
namespace {

using test::errorsOf;
using test::withRoot;

TEST(AFParserErrors, MissingCommaInVector) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" origin ( 1 2, 3 ) })af")),
              "bad.af:3:33: error: expected ',' between vector components, found '2'\n");
}

TEST(AFParserErrors, UnknownBodyKey) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" mass 3 })af")),
              "bad.af:3:22: error: expected a body key (joint, mod, model, origin, angles, density, inertiaScale, "
              "friction, contents, clipMask, selfCollision, containedJoints, frictionDirection, "
              "contactMotorDirection) or '}', found 'mass'\n");
}

TEST(AFParserErrors, UnknownTopLevelKeyword) {
    EXPECT_EQ(errorsOf(withRoot("joint \"x\"")),
              "bad.af:3:1: error: expected settings, body, a constraint (fixed, ballAndSocketJoint, universalJoint, "
              "hinge, slider, spring) or '}', found 'joint'\n");
}

TEST(AFParserErrors, BodyNameMustBeQuoted) {
    EXPECT_EQ(errorsOf(withRoot("body b { joint \"j\" }")),
              "bad.af:3:6: error: expected a body name in double quotes, found 'b'\n");
}

TEST(AFParserErrors, BodyWithoutJoint) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "lost" { density 1 })af")),
              "bad.af:3:6: error: body \"lost\" has no joint; add joint \"NAME\"\n");
}

TEST(AFParserErrors, ReservedBodyNames) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "World" { joint "j" })af")),
              "bad.af:3:6: error: a body may not be named 'World'; the name is reserved for the world\n");
}

TEST(AFParserErrors, DuplicateBodyAndConstraintNames) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "root" { joint "j" }
fixed "f" { body1 "root" } fixed "f" { body1 "root" })af")),
              "bad.af:3:6: error: a second body named \"root\" (the first is at line 2)\n"
              "bad.af:4:34: error: a second constraint named \"f\" (the first is at line 4)\n");
}

TEST(AFParserErrors, UnknownBody1) {
    EXPECT_EQ(errorsOf(withRoot(R"af(fixed "f" { body1 "ghost" })af")),
              "bad.af:3:19: error: fixed \"f\": body1 must name a body of this figure, found \"ghost\"\n");
}

TEST(AFParserErrors, Body1CannotBeTheWorld) {
    EXPECT_EQ(errorsOf(withRoot(R"af(fixed "f" { body1 "world" body2 "root" })af")),
              "bad.af:3:19: error: fixed \"f\": body1 must name a body of this figure, found \"world\"\n");
}

TEST(AFParserErrors, ConstraintBeforeAnyBodyHasNoBody1) {
    EXPECT_EQ(errorsOf("t { fixed \"f\" { } body \"root\" { joint \"origin\" } }"),
              "bad.af:1:11: error: fixed \"f\": body1 must name a body of this figure, found \"world\" "
              "(body1 was not given)\n");
}

TEST(AFParserErrors, ZeroShaftsAndHingeAxis) {
    EXPECT_EQ(errorsOf(withRoot(R"af(universalJoint "u" { body1 "root" shafts ( 0, 0, 0 ), ( 0, 0, 1 ) }
hinge "h" { body1 "root" })af")),
              "bad.af:3:42: error: universalJoint \"u\": the first shaft must not be zero (the joint cannot be "
              "simulated)\n"
              "bad.af:4:7: error: hinge \"h\": the axis must not be zero (the joint cannot be simulated)\n");
}

TEST(AFParserErrors, UniversalJointWithoutShafts) {
    EXPECT_EQ(errorsOf(withRoot(R"af(universalJoint "u" { body1 "root" })af")),
              "bad.af:3:16: error: universalJoint \"u\": the first shaft must not be zero (the joint cannot be "
              "simulated)\n"
              "bad.af:3:16: error: universalJoint \"u\": the second shaft must not be zero (the joint cannot be "
              "simulated)\n");
}

TEST(AFParserErrors, NegativeDensity) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" density -0.5 })af")),
              "bad.af:3:30: error: density must be greater than 0, found -0.5 (a body without mass cannot be "
              "simulated)\n");
}

TEST(AFParserErrors, NotANumber) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" density 1.#QNAN })af")),
              "bad.af:3:30: error: density must be a finite number, found '1.#QNAN'\n");
}

TEST(AFParserErrors, FloatOverflow) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" density 1e39 })af")),
              "bad.af:3:30: error: density is out of range for a 32-bit float, found '1e39'\n");
}

TEST(AFParserErrors, LeadingPlusIsNotANumber) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" density +1 })af")),
              "bad.af:3:30: error: expected a number for density, found '+'\n");
}

TEST(AFParserErrors, SpringWithoutItsValues) {
    EXPECT_EQ(errorsOf(withRoot(R"af(spring "s" { body1 "root" stretch 1 restLength 2 })af")),
              "bad.af:3:8: error: spring \"s\" lacks compress, damping, minLength, maxLength (Doom leaves them "
              "undefined; give all six)\n");
}

TEST(AFParserErrors, SpringMinLongerThanMax) {
    EXPECT_EQ(errorsOf(withRoot(R"af(spring "s" { body1 "root" stretch 1 compress 1 damping 0 restLength 2 minLength 9 maxLength 3 })af")),
              "bad.af:3:8: error: spring \"s\": minLength 9 is greater than maxLength 3 (no length satisfies both, "
              "so the spring cannot be simulated)\n");
}

TEST(AFParserErrors, ConeAngleOutOfRange) {
    EXPECT_EQ(errorsOf(withRoot(R"af(ballAndSocketJoint "b" { body1 "root" coneLimit ( 0, 0, 1 ), -10, ( 0, 0, 1 ) })af")),
              "bad.af:3:62: error: the cone angle must be between 0 and 360 degrees, found -10 (a limit beyond a "
              "full turn means nothing and cannot be simulated)\n");
}

TEST(AFParserErrors, FloatWhereIntegerExpected) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" model cylinder( ( -1, -1, -1 ), ( 1, 1, 1 ), 6.0 ) })af")),
              "bad.af:3:67: error: expected an integer for the number of sides, found '6.0'\n");
}

TEST(AFParserErrors, NoOriginBody) {
    EXPECT_EQ(errorsOf("t { body \"a\" { joint \"Origin\" } }"),
              "bad.af:1:10: error: the root body's joint must be spelled \"origin\", found \"Origin\"\n");
    EXPECT_EQ(errorsOf("t { body \"a\" { joint \"hips\" } }"),
              "bad.af:1:1: error: figure \"t\" has no body with joint \"origin\"; its root body needs one\n");
}

// An unknown name is a warning (af_parser_test.cpp); what is not a name at all is an error.
TEST(AFParserErrors, ContentsListOfSomethingOtherThanNames) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" contents solid, 5 })af")),
              "bad.af:3:38: error: expected a contents name (none, solid, body, corpse, playerclip, monsterclip, "
              "opaque, water, moveableclip, ikclip, blood, projectile, rendermodel, trigger, aas_solid, "
              "aas_obstacle, flashlight_trigger), found '5'\n");
}

// Doom loads these with a warning, or quietly; so do we, saying what they do.
TEST(AFParserErrors, WhatDoomLoadsIsAWarningNotAnError) {
    const AFParseResult r = parseAF("{ body \"b\" { } }\n" + withRoot(R"af(settings { noMoveTime -1 }
body "b" { joint "j" angles joint( "x" ) mod 3 })af"), "w.af");
    EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll();
    EXPECT_EQ(r.diagnostics.formatAll(),
              "w.af:1:1: warning: a braced section without a decl name is skipped, as in Doom 3\n"
              "w.af:4:23: warning: noMoveTime is negative, found -1; Doom 3 loads it, and so do we: the no-move "
              "window is then judged from the first step\n"
              "w.af:5:29: warning: angles written as joint(), bonecenter() or bonedir() read as ( 0, 0, 0 ), as in "
              "Doom 3; write ( pitch, yaw, roll ) in degrees\n"
              "w.af:5:46: warning: unknown mod '3' (orientation, position or both); orientation is used, as in "
              "Doom 3\n");
    ASSERT_EQ(r.file.decls.size(), 1u);
    EXPECT_EQ(r.file.decls[0].bodies[1].angles, (Real3{0, 0, 0}));
}

TEST(AFParserErrors, NegativeBodyFrictionIsRefusedAsDoomRefusesIt) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" friction -1, 0, 0 })af")),
              "bad.af:3:31: error: linear friction must not be negative, found -1 (Doom 3 refuses it too: it keeps "
              "its default friction and warns)\n");
}

TEST(AFParserErrors, VectorWordsAreCaseSensitive) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" origin Joint( "x" ) })af")),
              "bad.af:3:29: error: expected the body origin as ( x, y, z ), joint( \"J\" ), bonecenter( \"A\", "
              "\"B\" ) or bonedir( \"A\", \"B\" ), found 'Joint'\n");
}

TEST(AFParserErrors, EndOfFileInsideABlock) {
    EXPECT_EQ(errorsOf("t { body \"root\" { joint \"origin\""),
              "bad.af:1:33: error: expected a body key (joint, mod, model, origin, angles, density, inertiaScale, "
              "friction, contents, clipMask, selfCollision, containedJoints, frictionDirection, "
              "contactMotorDirection) or '}', found end of file\n");
}

TEST(AFParserErrors, MissingBraceAfterDeclName) {
    EXPECT_EQ(errorsOf("articulatedFigure t body"),
              "bad.af:1:21: error: expected '{' after the decl name, found 'body'\n");
}

TEST(AFParserErrors, ParsingResumesAtTheNextDecl) {
    const AFParseResult r = parseAF("a { bogus } b { body \"r\" { joint \"origin\" } }", "two.af");
    EXPECT_EQ(r.diagnostics.errorCount(), 1u);
    ASSERT_EQ(r.file.decls.size(), 1u);
    EXPECT_EQ(r.file.decls[0].name, "b");
}

TEST(AFParserErrors, LexicalErrorIsReportedOnce) {
    EXPECT_EQ(errorsOf(withRoot(R"af(body "b" { joint "j" density 1.2.3 })af")),
              "bad.af:3:30: error: more than one dot in number '1.2.3'\n");
}

TEST(AFParserErrors, UnreadableFile) {
    const AFParseResult r = loadAFFile("/nonexistent/dir/x.af");
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.diagnostics.formatAll(), "/nonexistent/dir/x.af: error: cannot open the file for reading\n");
}

}  // namespace
}  // namespace af
