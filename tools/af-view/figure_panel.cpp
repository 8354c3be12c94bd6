// The figure editor's panel (figure_panel.h): ImGui widgets over the session's decl, each change sent
// as a console command, so the panel holds no figure data of its own beyond its selection.

#include "figure_panel.h"

#include "af/text/strings.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <cstdio>

namespace af::view {

namespace {

const ImVec4 kWarningColour(1.0f, 0.8f, 0.2f, 1.0f);

std::string num(Real v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", double(v));
    return text;
}

// A vector as the .af file writes it; joint names without quotes, which editBody puts back.
std::string vectorText(const AFVector& v) {
    std::string s = v.negated ? "-" : "";
    switch (v.kind) {
    case AFVector::Kind::Coordinates:
        return s + "( " + num(v.coordinates[0]) + ", " + num(v.coordinates[1]) + ", " + num(v.coordinates[2]) + " )";
    case AFVector::Kind::Joint: return s + "joint( " + v.joint1 + " )";
    case AFVector::Kind::BoneCenter: return s + "bonecenter( " + v.joint1 + ", " + v.joint2 + " )";
    case AFVector::Kind::BoneDir: return s + "bonedir( " + v.joint1 + ", " + v.joint2 + " )";
    }
    return s;
}

bool literal(const AFVector& v) { return v.kind == AFVector::Kind::Coordinates && !v.negated; }

// Fields are read back from the decl every frame and send their command when Enter is pressed:
// the decl, not the field, holds the value, so a refused edit shows the value still in force.
constexpr ImGuiInputTextFlags kOnEnter = ImGuiInputTextFlags_EnterReturnsTrue;

// Three numbers in fields; true when they were entered.
bool edit3(const char* label, const Real3& value, float out[3]) {
    for (int i = 0; i < 3; ++i) out[i] = float(value[std::size_t(i)]);
    return ImGui::InputFloat3(label, out, "%.3f", kOnEnter);
}

bool edit1(const char* label, Real value, float& out) {
    out = float(value);
    return ImGui::InputFloat(label, &out, 0, 0, "%.6g", kOnEnter);
}

// What follows a constraint's limit angles: the ball-and-socket's limited shaft (docs/formats.md
// §1.7); the universal joint limits its own first shaft.
std::string limitShaft(const AFConstraint& c) {
    return c.type == ConstraintType::BallAndSocket ? ", " + vectorText(c.shafts[0]) : std::string();
}

std::string triple(const float v[3]) { return num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]); }

// A vector key: numbers in fields when the file gives numbers, else its text to edit.
bool editVector(const char* label, const AFVector& v, std::string& value) {
    if (literal(v)) {
        float f[3];
        if (!edit3(label, v.coordinates, f)) return false;
        value = "( " + triple(f) + " )";
        return true;
    }
    std::string text = vectorText(v);
    if (!ImGui::InputText(label, &text, kOnEnter)) return false;
    value = text;
    return true;
}

const char* const kShapes[] = {"box", "octahedron", "dodecahedron", "cylinder", "cone"};

}  // namespace

void FigurePanel::selectBody(const std::string& entity, const std::string& body) {
    entity_ = entity;
    kind_ = Kind::Body;
    item_ = body;
}

std::string FigurePanel::selection() const {
    if (entity_.empty()) return "nothing";
    if (kind_ == Kind::None) return entity_;
    return entity_ + (kind_ == Kind::Body ? " body " : " constraint ") + item_;
}

void FigurePanel::run(console::CommandSystem& console, const std::string& command) { console.execute(command, "figure panel"); }

void FigurePanel::draw(console::CommandSystem& console, const console::Session& session, float x, float y, float width, float height) {
    ImGui::SetNextWindowPos({x, y}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({width, height}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("Figure");
    const std::vector<std::string> entities = session.entityNames();
    if (!session.decl(entity_)) {
        entity_ = entities.empty() ? std::string() : entities.front();
        kind_ = Kind::None;
    }
    if (ImGui::BeginCombo("entity", entity_.c_str())) {
        for (const std::string& e : entities)
            if (ImGui::Selectable(e.c_str(), e == entity_)) {
                entity_ = e;
                kind_ = Kind::None;
            }
        ImGui::EndCombo();
    }
    const bool any = session.decl(entity_) != nullptr;
    if (any && ImGui::Button("Save .af")) run(console, "saveAF " + entity_);
    if (any && ImGui::IsItemHovered()) ImGui::SetTooltip("write this figure's decl, edits included, into its .af file");
    if (any) ImGui::SameLine();
    if (ImGui::Button("saveRagdolls")) run(console, "saveRagdolls");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("write every ragdoll's pose into the map");

    const DeclAF* decl = session.decl(entity_);  // after the buttons: a command may respawn
    if (decl) {
        if (entity_ != checkedEntity_ || !(*decl == checkedDecl_)) {
            checkedEntity_ = entity_;
            checkedDecl_ = *decl;
            warnings_ = session.warnings(entity_);
            bodyOrder_.clear();
            constraintOrder_.clear();
            const World& world = session.world();
            for (const FigureId id : world.figureIds())
                if (equalsIgnoreCase(session.entityName(id), entity_)) {
                    for (const FigureBody& b : world.definition(id).bodies) bodyOrder_.push_back(b.name);
                    for (const FigureConstraint& c : world.definition(id).constraints) constraintOrder_.push_back(c.name);
                }
        }
        // Drawn from the panel's copy: a field's command respawns the figure and replaces the
        // session's decl while the rest of the item is still being drawn.
        const DeclAF& shown = checkedDecl_;
        drawWarnings(Kind::None, -1);
        drawItems(shown);
        ImGui::Separator();
        if (kind_ == Kind::Body)
            if (const AFBody* b = shown.findBody(item_)) drawBody(console, *b);
        if (kind_ == Kind::Constraint)
            if (const AFConstraint* c = shown.findConstraint(item_)) drawConstraint(console, *c);
    }
    ImGui::End();
}

// The figure's warnings about one item (Kind::None: the whole figure's), in the warning colour.
void FigurePanel::drawWarnings(Kind kind, int index) const {
    for (const FigureWarning& w : warnings_) {
        const bool match = kind == Kind::None   ? w.subject == FigureWarning::Subject::Figure
                           : kind == Kind::Body ? w.subject == FigureWarning::Subject::Body && w.index == index
                                                : w.subject == FigureWarning::Subject::Constraint && w.index == index;
        if (!match) continue;
        ImGui::PushStyleColor(ImGuiCol_Text, kWarningColour);
        ImGui::TextWrapped("warning: %s", w.message.c_str());
        ImGui::PopStyleColor();
    }
}

void FigurePanel::drawItems(const DeclAF& decl) {
    const auto warned = [this](Kind kind, const std::string& name) {
        const std::vector<std::string>& order = kind == Kind::Body ? bodyOrder_ : constraintOrder_;
        for (const FigureWarning& w : warnings_) {
            const bool same = kind == Kind::Body ? w.subject == FigureWarning::Subject::Body : w.subject == FigureWarning::Subject::Constraint;
            if (same && w.index >= 0 && std::size_t(w.index) < order.size() && order[std::size_t(w.index)] == name) return w.index;
        }
        return -1;
    };
    const auto list = [&](const char* title, Kind kind, const std::vector<std::string>& names) {
        ImGui::TextUnformatted(title);
        if (!ImGui::BeginListBox((std::string("##") + title).c_str(), {-1, ImGui::GetTextLineHeightWithSpacing() * std::min<float>(8, float(names.size()) + 0.5f)}))
            return;
        for (const std::string& name : names) {
            const int w = warned(kind, name);
            if (w >= 0) ImGui::PushStyleColor(ImGuiCol_Text, kWarningColour);
            if (ImGui::Selectable((name + (w >= 0 ? "  (!)" : "")).c_str(), kind_ == kind && item_ == name)) {
                kind_ = kind;
                item_ = name;
            }
            if (w >= 0) ImGui::PopStyleColor();
        }
        ImGui::EndListBox();
    };
    std::vector<std::string> bodies, constraints;
    for (const AFBody& b : decl.bodies) bodies.push_back(b.name);
    for (const AFConstraint& c : decl.constraints) constraints.push_back(c.name);
    list("bodies", Kind::Body, bodies);
    list("constraints", Kind::Constraint, constraints);
}

// Any key of the item, as the .af file spells it, for what the fields do not show.
void FigurePanel::drawKeyLine(console::CommandSystem& console, const std::string& prefix) {
    ImGui::Separator();
    ImGui::TextUnformatted("any key, as in the .af file:");
    ImGui::SetNextItemWidth(110);
    ImGui::InputTextWithHint("##key", "key", &key_);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(-60);
    const bool entered = ImGui::InputTextWithHint("##value", "value", &value_, kOnEnter);
    ImGui::SameLine();
    if ((ImGui::Button("Set") || entered) && !key_.empty()) run(console, prefix + key_ + " " + value_);
}

void FigurePanel::drawBody(console::CommandSystem& console, const AFBody& b) {
    const std::string prefix = "editBody " + entity_ + " " + b.name + " ";
    ImGui::Text("body \"%s\"  joint \"%s\"", b.name.c_str(), b.joint.c_str());
    for (std::size_t i = 0; i < bodyOrder_.size(); ++i)
        if (bodyOrder_[i] == b.name) drawWarnings(Kind::Body, int(i));
    for (std::size_t i = 0; i < constraintOrder_.size(); ++i) {
        const AFConstraint* c = checkedDecl_.findConstraint(constraintOrder_[i]);
        if (c && (c->body1 == b.name || c->body2 == b.name)) drawWarnings(Kind::Constraint, int(i));
    }
    // The shape: its kind, its corners (in the body's frame) and, for cylinders and cones, sides.
    const AFShape& s = b.shape;
    if (s.type != ShapeType::Bone && s.type != ShapeType::Custom && literal(s.v1) && literal(s.v2)) {
        int shape = int(s.type);
        float lo[3], hi[3];
        int sides = s.numSides;
        bool changed = ImGui::Combo("shape", &shape, kShapes, IM_ARRAYSIZE(kShapes));
        changed |= edit3("min", s.v1.coordinates, lo);
        changed |= edit3("max", s.v2.coordinates, hi);
        if (shape == int(ShapeType::Cylinder) || shape == int(ShapeType::Cone)) changed |= ImGui::InputInt("sides", &sides, 1, 1, kOnEnter);
        if (changed) {
            std::string model = std::string(kShapes[shape]) + "( ( " + triple(lo) + " ), ( " + triple(hi) + " )";
            if (shape == int(ShapeType::Cylinder) || shape == int(ShapeType::Cone)) model += ", " + std::to_string(sides);
            run(console, prefix + "model \"" + model + " )\"");
        }
    } else {
        ImGui::Text("model %s (edit it as a key below)", toString(s.type));
    }
    std::string value;
    if (editVector("origin", b.origin, value)) run(console, prefix + "origin \"" + value + "\"");
    float density = 0;
    if (edit1("density", b.density, density)) run(console, prefix + "density " + num(density));
    float friction[3];
    if (edit3("friction", {b.linearFriction, b.angularFriction, b.contactFriction}, friction))
        run(console, prefix + "friction " + triple(friction));
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("linear, angular, contact");
    drawKeyLine(console, prefix);
}

void FigurePanel::drawConstraint(console::CommandSystem& console, const AFConstraint& c) {
    const std::string prefix = "editConstraint " + entity_ + " " + c.name + " ";
    ImGui::Text("%s \"%s\"  %s -> %s", toString(c.type), c.name.c_str(), c.body1.c_str(), c.body2.c_str());
    for (std::size_t i = 0; i < constraintOrder_.size(); ++i)
        if (constraintOrder_[i] == c.name) drawWarnings(Kind::Constraint, int(i));
    std::string value;
    const bool anchored = c.type == ConstraintType::BallAndSocket || c.type == ConstraintType::Universal || c.type == ConstraintType::Hinge;
    if (anchored && editVector("anchor", c.anchor, value)) run(console, prefix + "anchor \"" + value + "\"");
    if ((c.type == ConstraintType::Hinge || c.type == ConstraintType::Slider) && editVector("axis", c.axis, value))
        run(console, prefix + "axis \"" + value + "\"");
    if (c.type == ConstraintType::Universal) {
        std::string shaft0, shaft1;
        const bool a = editVector("shaft 1", c.shafts[0], shaft0), b = editVector("shaft 2", c.shafts[1], shaft1);
        if (a || b)
            run(console, prefix + "shafts \"" + (a ? shaft0 : vectorText(c.shafts[0])) + ", " + (b ? shaft1 : vectorText(c.shafts[1])) + "\"");
    }
    float angles[3];
    if (c.type == ConstraintType::Hinge && c.limit != LimitType::None) {
        if (edit3("limit", c.limitAngles, angles)) run(console, prefix + "limit " + triple(angles));
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("centre, width, shaft angle (degrees)");
    } else if (c.limit == LimitType::Cone) {
        float angle = 0;
        if (edit1("cone angle", c.limitAngles[0], angle))
            run(console, prefix + "coneLimit \"" + vectorText(c.limitAxis) + ", " + num(angle) + limitShaft(c) + "\"");
        if (editVector("limit axis", c.limitAxis, value))
            run(console, prefix + "coneLimit \"" + value + ", " + num(c.limitAngles[0]) + limitShaft(c) + "\"");
    } else if (c.limit == LimitType::Pyramid) {
        if (edit3("pyramid angles", c.limitAngles, angles))
            run(console, prefix + "pyramidLimit \"" + vectorText(c.limitAxis) + ", " + triple(angles) + limitShaft(c) + "\"");
        if (editVector("limit axis", c.limitAxis, value))
            run(console, prefix + "pyramidLimit \"" + value + ", " + num(c.limitAngles[0]) + ", " + num(c.limitAngles[1]) + ", " +
                             num(c.limitAngles[2]) + limitShaft(c) + "\"");
    }
    if (c.type != ConstraintType::Fixed) {
        float friction = 0;
        if (edit1("friction", c.friction, friction)) run(console, prefix + "friction " + num(friction));
    }
    drawKeyLine(console, prefix);
}

}  // namespace af::view
