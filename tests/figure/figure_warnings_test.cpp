// A deliberately broken copy of the humanoid: each thing that makes figures misbehave is warned
// about at its place in the file; things that make a figure impossible are errors.

#include "figure_test_util.h"

namespace af {
namespace {

std::string diagnosticsOf(const DeclAF& decl) {
    return buildFigure(decl, test::humanoidPose(), "broken.af").formatDiagnostics();
}

AFBody& body(DeclAF& d, const std::string& name) {
    for (AFBody& b : d.bodies)
        if (b.name == name) return b;
    throw std::runtime_error("no body " + name);
}

AFConstraint& constraint(DeclAF& d, const std::string& name) {
    for (AFConstraint& c : d.constraints)
        if (c.name == name) return c;
    throw std::runtime_error("no constraint " + name);
}

std::string at(const SourceLocation& where) {
    return "broken.af:" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": ";
}

TEST(FigureWarnings, UnknownJointInAVector) {
    DeclAF d = test::humanoidDecl();
    AFBody& head = body(d, "head");
    head.origin.joint2 = "hedtop";
    const FigureResult r = buildFigure(d, test::humanoidPose(), "broken.af");
    EXPECT_TRUE(r.ok());
    EXPECT_NE(r.formatDiagnostics().find(at(head.origin.where) +
                                         "warning: joint \"hedtop\" is not in the skeleton; (0, 0, 0) is used"),
              std::string::npos)
        << r.formatDiagnostics();
}

TEST(FigureWarnings, JointNamesMatchIgnoringCase) {
    DeclAF d = test::humanoidDecl();
    body(d, "head").origin.joint1 = "NECK";
    body(d, "lhand").joint = "LHand";
    EXPECT_EQ(diagnosticsOf(d), "");
}

TEST(FigureWarnings, BodyJointMissingFromTheSkeleton) {
    DeclAF d = test::humanoidDecl();
    AFBody& hand = body(d, "lhand");
    hand.joint = "lpalm";
    EXPECT_NE(diagnosticsOf(d).find(at(hand.where) + "warning: body \"lhand\": joint \"lpalm\" is not in the skeleton"),
              std::string::npos);
}

TEST(FigureWarnings, HeavyBodyNextToALightOne) {
    DeclAF d = test::humanoidDecl();
    body(d, "lhand").density *= 200;
    const AFConstraint& wrist = constraint(d, "lwrist");
    const std::string text = diagnosticsOf(d);
    EXPECT_NE(text.find(at(wrist.where) + "warning: ballAndSocketJoint \"lwrist\" joins \"lhand\" and \"lloarm\""),
              std::string::npos)
        << text;
}

TEST(FigureWarnings, LopsidedInertia) {
    DeclAF d = test::humanoidDecl();
    AFBody& chest = body(d, "chest");
    chest.inertiaScale = {40, 0, 0, 0, 1, 0, 0, 0, 1};
    const std::string text = diagnosticsOf(d);
    EXPECT_NE(text.find(at(chest.where) + "warning: body \"chest\": its principal moments of inertia differ by"),
              std::string::npos)
        << text;
}

TEST(FigureWarnings, JointedBodiesStartingInsideEachOther) {
    DeclAF d = test::humanoidDecl();
    body(d, "head").origin = AFVector{AFVector::Kind::Joint, false, {}, "neck", {}, {}};
    const AFConstraint& neck = constraint(d, "neck");
    const std::string text = diagnosticsOf(d);
    EXPECT_NE(text.find(at(neck.where) + "warning: ballAndSocketJoint \"neck\": \"head\" starts"), std::string::npos)
        << text;
}

TEST(FigureWarnings, BodiesInSeparateTrees) {
    DeclAF d = test::humanoidDecl();
    std::erase_if(d.constraints, [](const AFConstraint& c) { return c.name == "lwrist"; });
    const std::string text = diagnosticsOf(d);
    EXPECT_NE(text.find("warning: the bodies form 2 separate trees"), std::string::npos) << text;
    EXPECT_NE(text.find("\"lhand\""), std::string::npos) << text;
}

// The same checks, as data: each warning names the body or constraint it is about, so that an
// editor can put it beside that item; the clean humanoid has none.
TEST(FigureWarnings, EachWarningNamesTheBodyOrConstraintItConcerns) {
    const FigureResult clean = buildFigure(test::humanoidDecl(), test::humanoidPose(), "humanoid.af");
    ASSERT_TRUE(clean.ok());
    EXPECT_TRUE(figureWarnings(*clean.figure).empty());

    DeclAF d = test::humanoidDecl();
    body(d, "lhand").density *= 200;
    body(d, "chest").inertiaScale = {40, 0, 0, 0, 1, 0, 0, 0, 1};
    const FigureResult r = buildFigure(d, test::humanoidPose(), "broken.af");
    ASSERT_TRUE(r.ok());
    const Figure& f = *r.figure;
    const std::vector<FigureWarning> warnings = figureWarnings(f);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_EQ(warnings[0].subject, FigureWarning::Subject::Body);
    EXPECT_EQ(f.bodies[std::size_t(warnings[0].index)].name, "chest");
    EXPECT_EQ(warnings[1].subject, FigureWarning::Subject::Constraint);
    EXPECT_EQ(f.constraints[std::size_t(warnings[1].index)].name, "lwrist");
    // buildFigure reports the same messages.
    for (const FigureWarning& w : warnings) EXPECT_NE(r.formatDiagnostics().find(w.message), std::string::npos) << w.message;
}

TEST(FigureWarnings, JointNoBodyContains) {
    DeclAF d = test::humanoidDecl();
    body(d, "lhand").containedJoints = "lhand";
    const std::string text = diagnosticsOf(d);
    EXPECT_NE(text.find("warning: no body's containedJoints holds these joints: lfingers"), std::string::npos) << text;
}

TEST(FigureErrors, DirectionThatVanishesOnTheSkeleton) {
    DeclAF d = test::humanoidDecl();
    AFConstraint& elbow = constraint(d, "lelbow");
    elbow.axis = AFVector{AFVector::Kind::BoneDir, false, {}, "lloarm", "LLOARM", {3, 7}};
    const FigureResult r = buildFigure(d, test::humanoidPose(), "broken.af");
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.formatDiagnostics(), "broken.af:3:7: error: hinge \"lelbow\": the axis is a zero vector on this skeleton, so the joint cannot be simulated\n");
}

TEST(FigureErrors, CustomModelsCannotBeBuilt) {
    DeclAF d = test::humanoidDecl();
    AFBody& head = body(d, "head");
    head.shape.type = ShapeType::Custom;
    const FigureResult r = buildFigure(d, test::humanoidPose(), "broken.af");
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.formatDiagnostics().find(at(head.where) + "error: body \"head\": custom models are not supported"),
              std::string::npos);
}

}  // namespace
}  // namespace af
