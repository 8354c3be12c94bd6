#include "figure_report.h"

#include "af/geometry/mass_properties.h"
#include "af_json.h"

#include <cstdio>

namespace af {

namespace {

using Json = nlohmann::ordered_json;

std::string num(Real v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", std::abs(v) < 5e-7 ? 0.0 : v);
    return buffer;
}

std::string vec(const Vec3& v) { return "( " + num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]) + " )"; }

Json vecJson(const Vec3& v) { return Json::array({v[0], v[1], v[2]}); }

std::string bodyName(const Figure& f, int b) {
    return b == kWorld ? std::string("world") : f.bodies[static_cast<std::size_t>(b)].name;
}

std::string shapeText(const FigureBody& b) {
    std::string s = toString(b.shapeKind);
    if (b.sides > 0) s += "(" + std::to_string(b.sides) + ")";
    return s;
}

std::string limitText(const FigureConstraint& c) {
    switch (c.limit) {
    case LimitType::None: return "";
    case LimitType::Cone:
        if (c.type == ConstraintType::Hinge)
            return "  limit " + num(c.limitAngles[0]) + ", " + num(c.limitAngles[1]) + ", " + num(c.limitAngles[2]);
        return "  cone " + num(c.limitAngles[0]) + " about " + vec(c.limitAxis);
    case LimitType::Pyramid:
        return "  pyramid " + num(c.limitAngles[0]) + " x " + num(c.limitAngles[1]) + " roll " + num(c.limitAngles[2]) +
               " about " + vec(c.limitAxis);
    }
    return "";
}

}  // namespace

std::string figureReportText(const Figure& f, const AFResources& r) {
    std::string out = "figure \"" + f.name + "\" from " + r.figure->file + "\n";
    out += "skeleton " + r.mesh.path + ", af_pose " + r.afPose.path + " (" + std::to_string(f.afPose.size()) +
           " joints)\n";
    out += "total mass " + num(f.totalMass());
    if (f.settings.totalMass > 0) out += " (totalMass " + num(f.settings.totalMass) + ")";
    out += "\n\nbodies (" + std::to_string(f.bodies.size()) + "): shape, volume, mass, centre of mass, "
           "principal inertia, angles (pitch, yaw, roll), driven joint\n";
    for (const FigureBody& b : f.bodies) {
        const Vec3 moments = principalInertia(b.inertia).moments;
        const std::string joint = b.joint >= 0 ? f.afPose.names[static_cast<std::size_t>(b.joint)] : "-";
        out += "  " + b.name + "  " + shapeText(b) + "  " + num(b.volume) + "  " + num(b.mass) + "  " +
               vec(b.pose.position) + "  " + vec(moments) + "  " + vec(anglesFromRotation(b.pose.rotation)) + "  " +
               joint + " (" + toString(b.mod) + ")\n";
    }
    out += "\nconstraints (" + std::to_string(f.constraints.size()) + ")\n";
    for (const FigureConstraint& c : f.constraints) {
        out += "  " + std::string(toString(c.type)) + " \"" + c.name + "\"  " + bodyName(f, c.body1) + " -> " +
               bodyName(f, c.body2);
        switch (c.type) {
        case ConstraintType::Fixed: break;
        case ConstraintType::BallAndSocket: out += "  anchor " + vec(c.anchor); break;
        case ConstraintType::Universal:
            out += "  anchor " + vec(c.anchor) + "  shafts " + vec(c.shafts[0]) + ", " + vec(c.shafts[1]);
            break;
        case ConstraintType::Hinge: out += "  anchor " + vec(c.anchor) + "  axis " + vec(c.axis); break;
        case ConstraintType::Slider: out += "  axis " + vec(c.axis); break;
        case ConstraintType::Spring:
            out += "  anchors " + vec(c.anchor) + ", " + vec(c.anchor2) + "  rest " + num(c.restLength);
            break;
        }
        out += limitText(c) + "\n";
    }
    const auto trees = bodyTrees(f);
    out += "\ntrees (" + std::to_string(trees.size()) + ")\n";
    for (const auto& t : trees) {
        out += " ";
        for (int b : t) out += " " + bodyName(f, b);
        out += "\n";
    }
    return out;
}

Json figureReportJson(const Figure* f, const AFResources& r, const std::vector<Diagnostic>& diagnostics) {
    Json out = {{"figure", r.figure ? r.figure->decl.name : std::string()},
                {"file", r.figure ? r.figure->file : std::string()},
                {"mesh", r.mesh.path},
                {"afPose", r.afPose.path},
                {"ok", f != nullptr}};
    if (f) {
        out["totalMass"] = f->totalMass();
        Json bodies = Json::array();
        for (const FigureBody& b : f->bodies) {
            const PrincipalInertia pi = principalInertia(b.inertia);
            bodies.push_back({{"name", b.name},
                              {"shape", toString(b.shapeKind)},
                              {"sides", b.sides},
                              {"volume", b.volume},
                              {"mass", b.mass},
                              {"centreOfMass", vecJson(b.pose.position)},
                              {"principalInertia", vecJson(pi.moments)},
                              {"angles", vecJson(anglesFromRotation(b.pose.rotation))},
                              {"joint", b.joint >= 0 ? Json(f->afPose.names[static_cast<std::size_t>(b.joint)]) : Json()},
                              {"mod", toString(b.mod)}});
        }
        out["bodies"] = bodies;
        Json constraints = Json::array();
        for (const FigureConstraint& c : f->constraints) {
            Json j = {{"type", toString(c.type)},
                      {"name", c.name},
                      {"body1", bodyName(*f, c.body1)},
                      {"body2", bodyName(*f, c.body2)},
                      {"anchor", vecJson(c.anchor)}};
            if (c.type == ConstraintType::Spring) j["anchor2"] = vecJson(c.anchor2);
            if (c.type == ConstraintType::Hinge || c.type == ConstraintType::Slider) j["axis"] = vecJson(c.axis);
            if (c.type == ConstraintType::Universal) j["shafts"] = {vecJson(c.shafts[0]), vecJson(c.shafts[1])};
            j["limit"] = toString(c.limit);
            if (c.limit != LimitType::None) {
                j["limitAngles"] = {c.limitAngles[0], c.limitAngles[1], c.limitAngles[2]};
                if (c.type != ConstraintType::Hinge) j["limitAxis"] = vecJson(c.limitAxis);
            }
            constraints.push_back(j);
        }
        out["constraints"] = constraints;
        Json trees = Json::array();
        for (const auto& t : bodyTrees(*f)) {
            Json names = Json::array();
            for (int b : t) names.push_back(bodyName(*f, b));
            trees.push_back(names);
        }
        out["trees"] = trees;
    }
    Json list = Json::array();
    for (const Diagnostic& d : diagnostics) {
        Json j = toJson(d);
        j["file"] = d.file;
        list.push_back(j);
    }
    out["diagnostics"] = list;
    return out;
}

}  // namespace af
