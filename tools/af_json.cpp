#include "af_json.h"

#include "af/text/contents.h"

#include <charconv>

namespace af {

namespace {

using Json = nlohmann::ordered_json;

// 0.2f is 0.20000000298...; JSON readers are better served by the 0.2 it was written as.
double number(Real v) {
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(v));
    (void)ec;
    double shortest = 0;
    std::from_chars(buffer, end, shortest);
    return shortest;
}

Json triple(const Real3& t) { return Json::array({number(t[0]), number(t[1]), number(t[2])}); }

// The mask as its names, in the writer's order, then the names of later games kept as written.
Json contentsJson(ContentsMask mask, const std::vector<std::string>& unknown) {
    Json names = Json::array();
    if (mask == 0 && unknown.empty()) return names;
    const std::string text = contentsToString(mask, unknown);
    for (std::size_t start = 0; start < text.size();) {
        const std::size_t comma = text.find(", ", start);
        names.push_back(text.substr(start, comma - start));
        start = comma == std::string::npos ? text.size() : comma + 2;
    }
    return names;
}

Json settingsJson(const AFSettings& s) {
    return {{"model", s.model},
            {"skin", s.skin},
            {"friction", {{"linear", number(s.linearFriction)},
                          {"angular", number(s.angularFriction)},
                          {"contact", number(s.contactFriction)},
                          {"constraint", number(s.constraintFriction)}}},
            {"suspendSpeed", {{"linearVelocity", number(s.suspendLinearVelocity)},
                              {"angularVelocity", number(s.suspendAngularVelocity)},
                              {"linearAcceleration", number(s.suspendLinearAcceleration)},
                              {"angularAcceleration", number(s.suspendAngularAcceleration)}}},
            {"noMoveTime", number(s.noMoveTime)},
            {"noMoveTranslation", number(s.noMoveTranslation)},
            {"noMoveRotation", number(s.noMoveRotation)},
            {"minMoveTime", number(s.minMoveTime)},
            {"maxMoveTime", number(s.maxMoveTime)},
            {"totalMass", number(s.totalMass)},
            {"contents", contentsJson(s.contents, s.unknownContents)},
            {"clipMask", contentsJson(s.clipMask, s.unknownClipMask)},
            {"selfCollision", s.selfCollision},
            {"fastEval", s.extensions.fastEval}};
}

Json shapeJson(const AFShape& s) {
    Json j = {{"type", toString(s.type)}};
    if (s.type == ShapeType::Custom) {
        j["name"] = s.customName;
        return j;
    }
    j["v1"] = toJson(s.v1);
    j["v2"] = toJson(s.v2);
    if (s.type == ShapeType::Cylinder || s.type == ShapeType::Cone) j["numSides"] = s.numSides;
    if (s.type == ShapeType::Bone) j["width"] = number(s.width);
    return j;
}

Json bodyJson(const AFBody& b) {
    Json inertia = Json::array();
    for (Real v : b.inertiaScale) inertia.push_back(number(v));
    Json j = {{"name", b.name},
              {"joint", b.joint},
              {"mod", toString(b.mod)},
              {"model", shapeJson(b.shape)},
              {"origin", toJson(b.origin)},
              {"angles", triple(b.angles)},
              {"density", number(b.density)},
              {"inertiaScale", inertia},
              {"friction", {{"linear", number(b.linearFriction)},
                            {"angular", number(b.angularFriction)},
                            {"contact", number(b.contactFriction)}}},
              {"contents", contentsJson(b.contents, b.unknownContents)},
              {"clipMask", contentsJson(b.clipMask, b.unknownClipMask)},
              {"selfCollision", b.selfCollision},
              {"containedJoints", b.containedJoints}};
    j["frictionDirection"] = b.frictionDirection ? toJson(*b.frictionDirection) : Json();
    j["contactMotorDirection"] = b.contactMotorDirection ? toJson(*b.contactMotorDirection) : Json();
    return j;
}

Json constraintJson(const AFConstraint& c) {
    Json j = {{"type", toString(c.type)}, {"name", c.name}, {"body1", c.body1}, {"body2", c.body2}};
    switch (c.type) {
    case ConstraintType::Fixed: break;
    case ConstraintType::BallAndSocket:
    case ConstraintType::Universal:
    case ConstraintType::Hinge:
        j["anchor"] = toJson(c.anchor);
        if (c.type == ConstraintType::Universal) j["shafts"] = {toJson(c.shafts[0]), toJson(c.shafts[1])};
        if (c.type == ConstraintType::Hinge) j["axis"] = toJson(c.axis);
        j["friction"] = number(c.friction);
        j["limit"] = toString(c.limit);
        if (c.limit != LimitType::None) {
            if (c.type != ConstraintType::Hinge) j["limitAxis"] = toJson(c.limitAxis);
            j["limitAngles"] = triple(c.limitAngles);
            if (c.type == ConstraintType::BallAndSocket) j["limitShaft"] = toJson(c.shafts[0]);
        }
        break;
    case ConstraintType::Slider:
        j["axis"] = toJson(c.axis);
        j["friction"] = number(c.friction);
        break;
    case ConstraintType::Spring:
        j["anchor1"] = toJson(c.anchor);
        j["anchor2"] = toJson(c.anchor2);
        j["friction"] = number(c.friction);
        j["stretch"] = number(c.stretch);
        j["compress"] = number(c.compress);
        j["damping"] = number(c.damping);
        j["restLength"] = number(c.restLength);
        j["minLength"] = number(c.minLength);
        j["maxLength"] = number(c.maxLength);
        break;
    }
    return j;
}

}  // namespace

Json toJson(const AFVector& v) {
    Json j;
    switch (v.kind) {
    case AFVector::Kind::Coordinates: j = {{"kind", "coordinates"}, {"value", triple(v.coordinates)}}; break;
    case AFVector::Kind::Joint: j = {{"kind", "joint"}, {"joint", v.joint1}}; break;
    case AFVector::Kind::BoneCenter: j = {{"kind", "bonecenter"}, {"joints", {v.joint1, v.joint2}}}; break;
    case AFVector::Kind::BoneDir: j = {{"kind", "bonedir"}, {"joints", {v.joint1, v.joint2}}}; break;
    }
    j["negated"] = v.negated;
    return j;
}

Json toJson(const DeclAF& decl) {
    Json bodies = Json::array();
    for (const AFBody& b : decl.bodies) bodies.push_back(bodyJson(b));
    Json constraints = Json::array();
    for (const AFConstraint& c : decl.constraints) constraints.push_back(constraintJson(c));
    return {{"name", decl.name}, {"settings", settingsJson(decl.settings)}, {"bodies", bodies},
            {"constraints", constraints}};
}

Json toJson(const Diagnostic& d) {
    return {{"line", d.where.line},
            {"col", d.where.column},
            {"severity", d.severity == Severity::Error ? "error" : "warning"},
            {"message", d.message}};
}

}  // namespace af
