// What the .af parser reads: every key, default and quirk of docs/formats.md §1.4–§1.9.

#include "af/text/contents.h"
#include "af_test_util.h"

namespace af {
namespace {

using test::parseOne;
using test::withRoot;

TEST(AFParser, TypeKeywordIsOptionalAndNamesAreCanonical) {
    const AFParseResult r = parseAF("Models\\Figures\\Guy.af { body \"b\" { joint \"origin\" } }\n"
                                    "ARTICULATEDFIGURE second { body \"b\" { joint \"origin\" } }",
                                    "x.af");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    ASSERT_EQ(r.file.decls.size(), 2u);
    EXPECT_EQ(r.file.decls[0].name, "models/figures/guy");
    EXPECT_EQ(r.file.decls[1].name, "second");
    EXPECT_NE(r.file.findDecl("MODELS/figures/guy.af"), nullptr);
}

TEST(AFParser, SettingsDefaultsAreDoomsBeforeAnySettings) {
    const DeclAF d = parseOne(withRoot(""));
    const AFSettings& s = d.settings;
    EXPECT_EQ(s.linearFriction, Real(0.01f));
    EXPECT_EQ(s.contactFriction, Real(0.8f));
    EXPECT_EQ(s.constraintFriction, 0.5);
    EXPECT_EQ(s.suspendAngularAcceleration, 60);
    EXPECT_EQ(s.noMoveTime, 1);
    EXPECT_EQ(s.minMoveTime, -1);
    EXPECT_EQ(s.totalMass, -1);
    EXPECT_EQ(s.contents, contents::Corpse);
    EXPECT_EQ(s.clipMask, contents::Solid | contents::Corpse);
    EXPECT_TRUE(s.selfCollision);
}

TEST(AFParser, SettingsKeysAreCaseInsensitiveAndAllRead) {
    const DeclAF d = parseOne(withRoot(R"af(
        SETTINGS {
            model "m" skin "s" mesh "ignored.md5mesh" anim "ignored.md5anim"
            friction 0.1, 0.2, 0.3, 0.4
            suspendspeed 1, 2, 3, 4
            noMoveTime 5 noMoveTranslation 6 noMoveRotation 7
            minMoveTime 8 maxMoveTime 9 totalMass 150
            contents solid, body clipMask none selfCollision 0
        })af"));
    const AFSettings& s = d.settings;
    EXPECT_EQ(s.model, "m");
    EXPECT_EQ(s.skin, "s");
    EXPECT_EQ(s.linearFriction, Real(0.1f));
    EXPECT_EQ(s.angularFriction, Real(0.2f));
    EXPECT_EQ(s.contactFriction, Real(0.3f));
    EXPECT_EQ(s.constraintFriction, Real(0.4f));
    EXPECT_EQ(s.suspendLinearVelocity, 1);
    EXPECT_EQ(s.suspendAngularVelocity, 2);
    EXPECT_EQ(s.suspendLinearAcceleration, 3);
    EXPECT_EQ(s.suspendAngularAcceleration, 4);
    EXPECT_EQ(s.noMoveTime, 5);
    EXPECT_EQ(s.noMoveTranslation, 6);
    EXPECT_EQ(s.noMoveRotation, 7);
    EXPECT_EQ(s.minMoveTime, 8);
    EXPECT_EQ(s.maxMoveTime, 9);
    EXPECT_EQ(s.totalMass, 150);
    EXPECT_EQ(s.contents, contents::Solid | contents::Body);
    EXPECT_EQ(s.clipMask, 0u);
    EXPECT_FALSE(s.selfCollision);
}

TEST(AFParser, FourthSettingsFrictionIsOptional) {
    const DeclAF d = parseOne(withRoot("settings { friction 0.1, 0.2, 0.3 }"));
    EXPECT_EQ(d.settings.contactFriction, Real(0.3f));
    EXPECT_EQ(d.settings.constraintFriction, Real(0.5f));
}

TEST(AFParser, BodiesTakeDefaultsFromSettingsParsedSoFar) {
    const DeclAF d = parseOne(R"af(articulatedFigure t {
        body "early" { joint "origin" }
        settings { friction 0.1, 0.2, 0.3 contents body clipMask solid selfCollision 0 }
        body "late" { joint "j" }
    })af");
    const AFBody& early = d.bodies[0];
    const AFBody& late = d.bodies[1];
    EXPECT_EQ(early.linearFriction, Real(0.01f));
    EXPECT_EQ(early.contents, contents::Corpse);
    EXPECT_TRUE(early.selfCollision);
    EXPECT_EQ(late.linearFriction, Real(0.1f));
    EXPECT_EQ(late.angularFriction, Real(0.2f));
    EXPECT_EQ(late.contactFriction, Real(0.3f));
    EXPECT_EQ(late.contents, contents::Body);
    EXPECT_EQ(late.clipMask, contents::Solid | contents::MoveableClip);
    EXPECT_FALSE(late.selfCollision);
}

TEST(AFParser, BodyDefaults) {
    const DeclAF d = parseOne(withRoot(""));
    const AFBody& b = d.bodies[0];
    EXPECT_EQ(b.mod, JointMod::Orientation);
    EXPECT_EQ(b.shape.type, ShapeType::Box);
    EXPECT_EQ(b.shape.v1, AFVector::literal(-10, -10, -10));
    EXPECT_EQ(b.shape.v2, AFVector::literal(10, 10, 10));
    EXPECT_EQ(b.origin, AFVector::literal(0, 0, 0));
    EXPECT_EQ(b.density, Real(0.2f));
    EXPECT_EQ(b.containedJoints, "*origin");
    EXPECT_EQ(b.clipMask, contents::Solid | contents::Corpse | contents::MoveableClip);
    EXPECT_FALSE(b.frictionDirection.has_value());
    EXPECT_FALSE(b.contactMotorDirection.has_value());
}

TEST(AFParser, EveryBodyKeyIsRead) {
    const DeclAF d = parseOne(withRoot(R"af(
        body "b" {
            JOINT "Spine" mod both
            model cylinder( ( -1, -2, -3 ), ( 1, 2, 3 ), 8 )
            origin joint( "spine" ) angles ( 10, 20, 30 ) density 0.5
            inertiaScale (1 0 0 0 2 0 0 0 3)
            friction 0.1, 0.2, 0.3 contents corpse, body clipMask solid selfCollision 0
            containedJoints "*spine -*neck"
            frictionDirection ( 1, 0, 0 ) contactMotorDirection -bonedir( "a", "b" )
        })af"));
    const AFBody& b = d.bodies[1];
    EXPECT_EQ(b.joint, "Spine");
    EXPECT_EQ(b.mod, JointMod::Both);
    EXPECT_EQ(b.shape.type, ShapeType::Cylinder);
    EXPECT_EQ(b.shape.v1, AFVector::literal(-1, -2, -3));
    EXPECT_EQ(b.shape.numSides, 8);
    EXPECT_EQ(b.origin.kind, AFVector::Kind::Joint);
    EXPECT_EQ(b.origin.joint1, "spine");
    EXPECT_EQ(b.angles, (Real3{10, 20, 30}));
    EXPECT_EQ(b.density, 0.5);
    EXPECT_EQ(b.inertiaScale, (std::array<Real, 9>{1, 0, 0, 0, 2, 0, 0, 0, 3}));
    EXPECT_EQ(b.contactFriction, Real(0.3f));
    EXPECT_EQ(b.contents, contents::Corpse | contents::Body);
    EXPECT_EQ(b.clipMask, contents::Solid | contents::MoveableClip);
    EXPECT_FALSE(b.selfCollision);
    EXPECT_EQ(b.containedJoints, "*spine -*neck");
    ASSERT_TRUE(b.frictionDirection.has_value());
    EXPECT_EQ(*b.frictionDirection, AFVector::literal(1, 0, 0));
    ASSERT_TRUE(b.contactMotorDirection.has_value());
    EXPECT_EQ(b.contactMotorDirection->kind, AFVector::Kind::BoneDir);
    EXPECT_TRUE(b.contactMotorDirection->negated);
    EXPECT_EQ(b.contactMotorDirection->joint2, "b");
}

TEST(AFParser, AllShapeWordsAreRead) {
    const DeclAF d = parseOne(withRoot(R"af(
        body "a" { joint "j" model octahedron( ( -1, -1, -1 ), ( 1, 1, 1 ) ) }
        body "b" { joint "j" model Dodecahedron( ( -1, -1, -1 ), ( 1, 1, 1 ) ) }
        body "c" { joint "j" model cone( ( -1, -1, -1 ), ( 1, 1, 1 ), 2 ) }
        body "d" { joint "j" model bone( joint( "x" ), joint( "y" ), 4.5 ) }
        body "e" { joint "j" model box( ( -1, -1, -1 ), ( 1, 1, 1 ) ) })af"));
    EXPECT_EQ(d.bodies[1].shape.type, ShapeType::Octahedron);
    EXPECT_EQ(d.bodies[2].shape.type, ShapeType::Dodecahedron);
    EXPECT_EQ(d.bodies[3].shape.type, ShapeType::Cone);
    EXPECT_EQ(d.bodies[3].shape.numSides, 2);
    EXPECT_EQ(d.bodies[4].shape.type, ShapeType::Bone);
    EXPECT_EQ(d.bodies[4].shape.width, 4.5);
    EXPECT_EQ(d.bodies[4].shape.v2.joint1, "y");
    EXPECT_EQ(d.bodies[5].shape.type, ShapeType::Box);
}

TEST(AFParser, CustomShapeIsKeptWithAWarning) {
    const AFParseResult r = parseAF(withRoot(R"af(body "c" { joint "j" model custom( "models/x.lwo" ) })af"), "c.af");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    EXPECT_EQ(r.file.decls[0].bodies[1].shape.type, ShapeType::Custom);
    EXPECT_EQ(r.file.decls[0].bodies[1].shape.customName, "models/x.lwo");
    ASSERT_EQ(r.diagnostics.warningCount(), 1u);
    EXPECT_NE(r.diagnostics.all()[0].message.find("custom models are not implemented"), std::string::npos);
}

TEST(AFParser, FourVectorFormsWithOptionalMinus) {
    const DeclAF d = parseOne(withRoot(R"af(
        body "a" { joint "j" origin -( 1, -2, 3 ) }
        body "b" { joint "j" origin joint( unquotedName ) }
        body "c" { joint "j" origin bonecenter( "p", "q" ) }
        body "d" { joint "j" origin -bonedir( "p", "q" ) })af"));
    const AFVector& a = d.bodies[1].origin;
    EXPECT_TRUE(a.negated);
    EXPECT_EQ(a.coordinates, (Real3{1, -2, 3}));
    EXPECT_EQ(d.bodies[2].origin.kind, AFVector::Kind::Joint);
    EXPECT_EQ(d.bodies[2].origin.joint1, "unquotedName");
    EXPECT_EQ(d.bodies[3].origin.kind, AFVector::Kind::BoneCenter);
    EXPECT_EQ(d.bodies[3].origin.joint1, "p");
    EXPECT_EQ(d.bodies[3].origin.joint2, "q");
    EXPECT_EQ(d.bodies[4].origin.kind, AFVector::Kind::BoneDir);
    EXPECT_TRUE(d.bodies[4].origin.negated);
}

TEST(AFParser, LeadingMinusOnAnglesIsIgnoredWithAWarning) {
    const AFParseResult r = parseAF(withRoot(R"af(body "a" { joint "j" angles -( 1, 2, 3 ) })af"), "a.af");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    EXPECT_EQ(r.file.decls[0].bodies[1].angles, (Real3{1, 2, 3}));
    EXPECT_EQ(r.diagnostics.warningCount(), 1u);
}

TEST(AFParser, UnknownModFallsBackToOrientationWithAWarning) {
    const AFParseResult r = parseAF(withRoot(R"af(body "a" { joint "j" mod sideways })af"), "m.af");
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.file.decls[0].bodies[1].mod, JointMod::Orientation);
    ASSERT_EQ(r.diagnostics.warningCount(), 1u);
    EXPECT_EQ(r.diagnostics.all()[0].where, (SourceLocation{3, 26}));
}

TEST(AFParser, NoneClearsContentsCollectedSoFar) {
    const DeclAF d = parseOne(withRoot(R"af(body "a" { joint "j" contents solid, none, body })af"));
    EXPECT_EQ(d.bodies[1].contents, contents::Body);
}

TEST(AFParser, OriginBodyIsSwappedToIndexZero) {
    const DeclAF d = parseOne(R"af(articulatedFigure t {
        body "first" { joint "a" }
        body "second" { joint "b" }
        body "root" { joint "origin" } })af");
    ASSERT_EQ(d.bodies.size(), 3u);
    EXPECT_EQ(d.bodies[0].name, "root");
    EXPECT_EQ(d.bodies[1].name, "second");
    EXPECT_EQ(d.bodies[2].name, "first");  // a swap, not a move
}

TEST(AFParser, ConstraintBody1DefaultsToFirstParsedBody) {
    const DeclAF d = parseOne(R"af(articulatedFigure t {
        body "child" { joint "a" }
        body "root" { joint "origin" }
        fixed "f" { body2 "root" } })af");
    EXPECT_EQ(d.constraints[0].body1, "child");
    EXPECT_EQ(d.constraints[0].body2, "root");
}

TEST(AFParser, ConstraintTypeDefaults) {
    const DeclAF d = parseOne(withRoot(R"af(
        body "b" { joint "j" }
        ballAndSocketJoint "ball" { body1 "b" }
        universalJoint "uni" { body1 "b" shafts ( 0, 0, 1 ), ( 0, 0, -1 ) }
        hinge "h" { body1 "b" axis ( 0, 1, 0 ) }
        slider "s" { body1 "b" }
        fixed "f" { body1 "b" })af"));
    const AFConstraint& ball = d.constraints[0];
    EXPECT_EQ(ball.type, ConstraintType::BallAndSocket);
    EXPECT_EQ(ball.body2, "world");
    EXPECT_EQ(ball.anchor, AFVector::literal(0, 0, 0));
    EXPECT_EQ(ball.shafts[0], AFVector::literal(0, 0, 0));
    EXPECT_EQ(ball.limit, LimitType::None);
    EXPECT_EQ(ball.friction, 0.5);
    EXPECT_EQ(d.constraints[1].limitAxis, AFVector::literal(0, 0, -1));
    EXPECT_EQ(d.constraints[2].limit, LimitType::None);
    EXPECT_EQ(d.constraints[3].axis, AFVector::literal(1, 0, 0));  // slider keeps the default axis
    EXPECT_EQ(d.constraints[4].type, ConstraintType::Fixed);
}

TEST(AFParser, ConstraintFrictionIgnoresFourthSettingsValue) {
    const DeclAF d = parseOne(withRoot(R"af(settings { friction 0.1, 0.1, 0.1, 0.9 }
        body "b" { joint "j" } hinge "h" { body1 "b" axis ( 0, 0, 1 ) })af"));
    EXPECT_EQ(d.constraints[0].friction, 0.5);
}

TEST(AFParser, BallAndSocketLimitsTakeAShaftAndTheLastWins) {
    const DeclAF d = parseOne(withRoot(R"af(body "b" { joint "j" }
        ballAndSocketJoint "cone" { body1 "b" anchor joint( "j" ) friction 0.2
            coneLimit ( 0, 0, 1 ), 60, bonedir( "j", "k" ) }
        ballAndSocketJoint "pyr" { body1 "b"
            coneLimit ( 0, 0, 1 ), 60, ( 1, 0, 0 )
            pyramidLimit -( 1, 0, 0 ), 30, 40, 15, ( 0, 1, 0 ) })af"));
    const AFConstraint& cone = d.constraints[0];
    EXPECT_EQ(cone.limit, LimitType::Cone);
    EXPECT_EQ(cone.limitAxis, AFVector::literal(0, 0, 1));
    EXPECT_EQ(cone.limitAngles[0], 60);
    EXPECT_EQ(cone.shafts[0].kind, AFVector::Kind::BoneDir);
    EXPECT_EQ(cone.friction, Real(0.2f));
    EXPECT_EQ(cone.anchor.joint1, "j");
    const AFConstraint& pyr = d.constraints[1];
    EXPECT_EQ(pyr.limit, LimitType::Pyramid);
    EXPECT_TRUE(pyr.limitAxis.negated);
    EXPECT_EQ(pyr.limitAngles, (Real3{30, 40, 15}));
    EXPECT_EQ(pyr.shafts[0], AFVector::literal(0, 1, 0));
}

TEST(AFParser, UniversalLimitsTakeNoShaft) {
    const DeclAF d = parseOne(withRoot(R"af(body "b" { joint "j" }
        universalJoint "u1" { body1 "b" shafts ( 0, 0, 1 ), ( 0, 0, -1 ) coneLimit ( 0, 0, 1 ), 45 }
        universalJoint "u2" { body1 "b" shafts ( 0, 0, 1 ), ( 0, 0, -1 ) pyramidLimit ( 0, 0, 1 ), 10, 20, 30 })af"));
    EXPECT_EQ(d.constraints[0].limit, LimitType::Cone);
    EXPECT_EQ(d.constraints[0].limitAngles[0], 45);
    EXPECT_EQ(d.constraints[0].shafts[0], AFVector::literal(0, 0, 1));
    EXPECT_EQ(d.constraints[1].limit, LimitType::Pyramid);
    EXPECT_EQ(d.constraints[1].limitAngles, (Real3{10, 20, 30}));
}

TEST(AFParser, HingeLimitHasThreeAngles) {
    const DeclAF d = parseOne(withRoot(R"af(body "b" { joint "j" }
        hinge "h" { body1 "b" anchor ( 1, 2, 3 ) axis ( 0, 1, 0 ) limit -45, 90, 0 })af"));
    const AFConstraint& h = d.constraints[0];
    EXPECT_EQ(h.limit, LimitType::Cone);
    EXPECT_EQ(h.limitAngles, (Real3{-45, 90, 0}));
    EXPECT_EQ(h.axis, AFVector::literal(0, 1, 0));
}

TEST(AFParser, SpringReadsAllNineKeys) {
    const DeclAF d = parseOne(withRoot(R"af(body "b" { joint "j" }
        spring "s" { body1 "b" body2 "world" anchor1 ( 0, 0, 1 ) anchor2 ( 0, 0, 2 ) friction 0.1
            stretch 100 compress 50 damping 2 restLength 10 minLength 5 maxLength 20 })af"));
    const AFConstraint& s = d.constraints[0];
    EXPECT_EQ(s.anchor, AFVector::literal(0, 0, 1));
    EXPECT_EQ(s.anchor2, AFVector::literal(0, 0, 2));
    EXPECT_EQ(s.friction, Real(0.1f));
    EXPECT_EQ(s.stretch, 100);
    EXPECT_EQ(s.compress, 50);
    EXPECT_EQ(s.damping, 2);
    EXPECT_EQ(s.restLength, 10);
    EXPECT_EQ(s.minLength, 5);
    EXPECT_EQ(s.maxLength, 20);
}

TEST(AFParser, UnknownBody2IsTheWorldWithAWarning) {
    const AFParseResult r = parseAF(withRoot(R"af(body "b" { joint "j" } fixed "f" { body1 "b" body2 "nowhere" })af"),
                                    "w.af");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    ASSERT_EQ(r.diagnostics.warningCount(), 1u);
    EXPECT_EQ(r.diagnostics.all()[0].where, (SourceLocation{3, 52}));
}

TEST(AFParser, QuakeFourFastEvalIsKeptWithAWarning) {
    const AFParseResult r = parseAF(withRoot("settings { fastEval }"), "q4.af");
    ASSERT_TRUE(r.ok());
    EXPECT_TRUE(r.file.decls[0].settings.extensions.fastEval);
    ASSERT_EQ(r.diagnostics.warningCount(), 1u);
    EXPECT_EQ(r.diagnostics.all()[0].severity, Severity::Warning);
}

TEST(AFParser, LaterGameContentsNamesAreKeptWithAWarning) {
    const AFParseResult r = parseAF(withRoot(R"af(body "b" { joint "j" contents corpse, projectile, water })af"), "c.af");
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.file.decls[0].bodies[1].contents, contents::Corpse | contents::Projectile | contents::Water);
    EXPECT_EQ(r.diagnostics.warningCount(), 2u);
}

// Doom 3 ends the list at a name it does not know and loads the figure; later games name bits of
// their own there. We warn, keep the name as written for the writer, and give it no effect.
TEST(AFParser, UnknownContentsNamesAreKeptAsWrittenWithoutEffect) {
    const AFParseResult r = parseAF(withRoot(R"af(body "b" { joint "j" contents corpse, MovableClip clipMask flyerhiveclip, solid })af"),
                                    "q4.af");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    const AFBody& b = r.file.decls[0].bodies[1];
    EXPECT_EQ(b.contents, contents::Corpse);
    EXPECT_EQ(b.unknownContents, std::vector<std::string>{"MovableClip"});
    EXPECT_EQ(b.clipMask, contents::Solid | contents::MoveableClip);  // the bit every body gets
    EXPECT_EQ(b.unknownClipMask, std::vector<std::string>{"flyerhiveclip"});
    EXPECT_EQ(r.diagnostics.formatAll(),
              "q4.af:3:39: warning: unknown contents name 'MovableClip' (a later game's?); kept and written back, "
              "no effect here\n"
              "q4.af:3:60: warning: unknown clipMask name 'flyerhiveclip' (a later game's?); kept and written back, "
              "no effect here\n");
}

TEST(AFParser, NoneAndANewListDropTheUnknownNamesBeforeThem) {
    const DeclAF d = parseOne(withRoot(R"af(settings { contents movableclip } body "a" { joint "j" } )af"
                                       R"af(body "b" { joint "j" contents movableclip, none, body } )af"
                                       R"af(body "c" { joint "j" contents body })af"));
    EXPECT_EQ(d.bodies[1].unknownContents, std::vector<std::string>{"movableclip"});  // from the settings
    EXPECT_TRUE(d.bodies[2].unknownContents.empty());
    EXPECT_TRUE(d.bodies[3].unknownContents.empty());
}

// Doom reads any decl type in any decl file; in an .af file we skip what is not a figure.
TEST(AFParser, DeclsOfOtherTypesAreSkippedWithAWarning) {
    const AFParseResult r =
        parseAF("entityDef e { \"k\" \"{v}\" }\nt { body \"r\" { joint \"origin\" } }\nMODEL m { mesh x.md5mesh }", "o.af");
    ASSERT_TRUE(r.ok()) << r.diagnostics.formatAll();
    ASSERT_EQ(r.file.decls.size(), 1u);
    EXPECT_EQ(r.file.decls[0].name, "t");
    EXPECT_EQ(r.diagnostics.formatAll(),
              "o.af:1:1: warning: a decl of type entityDef in an .af file is skipped (Doom 3 reads it as one) and "
              "not written back\n"
              "o.af:3:1: warning: a decl of type MODEL in an .af file is skipped (Doom 3 reads it as one) and not "
              "written back\n");
}

TEST(AFParser, NumbersAreHeldAtFloatPrecision) {
    const DeclAF d = parseOne(withRoot(R"af(body "b" { joint "j" density 0.1 })af"));
    EXPECT_EQ(d.bodies[1].density, Real(0.1f));
    EXPECT_NE(d.bodies[1].density, 0.1);
}

TEST(AFParser, CommentsCrLfAndTrailingNulAreAccepted) {
    const std::string text = "// header\r\narticulatedFigure t {\r\n/* block */ body \"root\" {\r joint \"origin\" }\r\n}\r\n" +
                             std::string(1, '\0');
    const AFParseResult r = parseAF(text, "crlf.af");
    EXPECT_TRUE(r.ok()) << r.diagnostics.formatAll();
    ASSERT_EQ(r.file.decls.size(), 1u);
    EXPECT_EQ(r.file.decls[0].bodies[0].where, (SourceLocation{3, 18}));
}

TEST(AFParser, DuplicateDeclNameWarnsAndFirstWins) {
    const AFParseResult r = parseAF("a { body \"x\" { joint \"origin\" } }\nA { body \"y\" { joint \"origin\" } }", "d.af");
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.diagnostics.warningCount(), 1u);
    EXPECT_EQ(r.file.findDecl("a")->bodies[0].name, "x");
}

}  // namespace
}  // namespace af
