// `body "NAME" { ... }` blocks (docs/formats.md §1.6).

#include "af/text/number_format.h"
#include "af/text/strings.h"
#include "af_parser_impl.h"

namespace af {

void AFParser::parseBody(DeclAF& decl) {
    const Token name = in_.expectString("a body name");
    in_.expectPunctuation("{", "after the body name");

    AFBody body;
    body.name = name.text;
    body.where = name.where;
    body.linearFriction = current_.linearFriction;
    body.angularFriction = current_.angularFriction;
    body.contactFriction = current_.contactFriction;
    body.contents = current_.contents;
    body.clipMask = current_.clipMask;
    body.unknownContents = current_.unknownContents;
    body.unknownClipMask = current_.unknownClipMask;
    body.selfCollision = current_.selfCollision;
    if (equalsIgnoreCase(body.name, "world") || equalsIgnoreCase(body.name, "origin"))
        diagnostics().error(name.where, "a body may not be named '" + body.name +
                                            "'; the name is reserved for the world");

    bool hasJoint = false;
    for (;;) {
        const Token key = in_.next();
        if (key.isPunctuation("}")) break;
        if (key.isKeyword("joint")) {
            body.joint = in_.expectString("a joint name").text;
            hasJoint = true;
        } else {
            parseBodyKey(body, key);
        }
    }
    // Doom forces the moveable clip bit into every body's clip mask; the writer leaves it out.
    body.clipMask |= contents::MoveableClip;
    if (!hasJoint) diagnostics().error(name.where, "body \"" + body.name + "\" has no joint; add joint \"NAME\"");
    if (firstBodyName_.empty()) firstBodyName_ = body.name;
    decl.bodies.push_back(std::move(body));
}

void AFParser::parseBodyKey(AFBody& body, const Token& key) {
    if (key.isKeyword("mod")) {
        const Token mod = in_.next();
        if (mod.isKeyword("orientation")) body.mod = JointMod::Orientation;
        else if (mod.isKeyword("position")) body.mod = JointMod::Position;
        else if (mod.isKeyword("both")) body.mod = JointMod::Both;
        else if (mod.type != TokenType::Punctuation && mod.type != TokenType::End && mod.type != TokenType::Invalid) {
            // Doom takes any token here; a number or a quoted word means orientation too.
            body.mod = JointMod::Orientation;
            diagnostics().warning(mod.where, "unknown mod '" + printableExcerpt(mod.text) +
                                                 "' (orientation, position or both); orientation is used, as in Doom 3");
        } else {
            in_.fail(mod, "orientation, position or both after mod");
        }
    } else if (key.isKeyword("model")) {
        body.shape = parseShape();
    } else if (key.isKeyword("origin")) {
        body.origin = parseVector("the body origin");
    } else if (key.isKeyword("angles")) {
        const AFVector angles = parseVector("angles");
        // Doom reads angles before any vector is resolved: a symbolic form counts as zero.
        if (angles.kind != AFVector::Kind::Coordinates)
            diagnostics().warning(angles.where, "angles written as joint(), bonecenter() or bonedir() read as "
                                                "( 0, 0, 0 ), as in Doom 3; write ( pitch, yaw, roll ) in degrees");
        else if (angles.negated)
            diagnostics().warning(angles.where, "a '-' before angles is ignored, as in Doom 3");
        body.angles = angles.coordinates;
    } else if (key.isKeyword("density")) {
        body.density = in_.readFloat("density", &body.densityWhere);
        if (body.density <= 0)
            diagnostics().error(body.densityWhere, "density must be greater than 0, found " + formatDeclFloat(body.density) +
                                                      " (a body without mass cannot be simulated)");
    } else if (key.isKeyword("inertiaScale")) {
        body.inertiaScaleWhere = in_.peek().where;
        in_.expectPunctuation("(", "before the nine inertiaScale values");
        for (Real& v : body.inertiaScale) v = in_.readFloat("inertiaScale");
        in_.expectPunctuation(")", "after the nine inertiaScale values (they take no commas)");
    } else if (key.isKeyword("friction")) {
        body.linearFriction = readNonNegative("linear friction", kDoomIgnoresFriction);
        in_.expectPunctuation(",", "after the linear friction");
        body.angularFriction = readNonNegative("angular friction", kDoomIgnoresFriction);
        in_.expectPunctuation(",", "after the angular friction");
        body.contactFriction = readNonNegative("contact friction", kDoomIgnoresFriction);
    } else if (key.isKeyword("contents")) {
        body.contents = parseContents("contents", body.unknownContents);
    } else if (key.isKeyword("clipMask")) {
        body.clipMask = parseContents("clipMask", body.unknownClipMask);
    } else if (key.isKeyword("selfCollision")) {
        body.selfCollision = in_.readBool("selfCollision");
    } else if (key.isKeyword("containedJoints")) {
        body.containedJoints = in_.expectString("a joint list").text;
    } else if (key.isKeyword("frictionDirection")) {
        body.frictionDirection = parseVector("frictionDirection");
    } else if (key.isKeyword("contactMotorDirection")) {
        body.contactMotorDirection = parseVector("contactMotorDirection");
    } else {
        in_.fail(key, "a body key (joint, mod, model, origin, angles, density, inertiaScale, friction, contents, "
                      "clipMask, selfCollision, containedJoints, frictionDirection, contactMotorDirection) or '}'");
    }
}

AFShape AFParser::parseShape() {
    AFShape shape;
    const Token word = in_.next();
    shape.where = word.where;
    if (word.isKeyword("box")) shape.type = ShapeType::Box;
    else if (word.isKeyword("octahedron")) shape.type = ShapeType::Octahedron;
    else if (word.isKeyword("dodecahedron")) shape.type = ShapeType::Dodecahedron;
    else if (word.isKeyword("cylinder")) shape.type = ShapeType::Cylinder;
    else if (word.isKeyword("cone")) shape.type = ShapeType::Cone;
    else if (word.isKeyword("bone")) shape.type = ShapeType::Bone;
    else if (word.isKeyword("custom")) shape.type = ShapeType::Custom;
    else in_.fail(word, "a shape (box, octahedron, dodecahedron, cylinder, cone, bone or custom)");

    in_.expectPunctuation("(", "after the shape name");
    if (shape.type == ShapeType::Custom) {
        shape.customName = in_.expectString("a custom model name").text;
        in_.expectPunctuation(")", "after the custom model name");
        diagnostics().warning(word.where, "custom models are not implemented (Doom 3 rejects them too); the body "
                                          "cannot be built");
        return shape;
    }
    shape.v1 = parseVector("the first shape vector");
    in_.expectPunctuation(",", "after the first shape vector");
    shape.v2 = parseVector("the second shape vector");
    if (shape.type == ShapeType::Cylinder || shape.type == ShapeType::Cone) {
        in_.expectPunctuation(",", "before the number of sides");
        shape.numSides = in_.readInt("the number of sides");
    } else if (shape.type == ShapeType::Bone) {
        in_.expectPunctuation(",", "before the bone width");
        SourceLocation where;
        shape.width = in_.readFloat("the bone width", &where);
        if (shape.width <= 0)
            diagnostics().error(where, "the bone width must be greater than 0, found " + formatDeclFloat(shape.width) +
                                          " (a bone without volume cannot be simulated)");
    }
    in_.expectPunctuation(")", "after the shape arguments");
    return shape;
}

}  // namespace af
