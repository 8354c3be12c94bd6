#pragma once
// The figure editor's panel: an entity's bodies and constraints, the selected one's .af keys in
// fields, the figure checks beside the items they concern, and the Save .af and saveRagdolls
// buttons. A thin view: every change it makes is a console command (editBody, editConstraint,
// saveAF, saveRagdolls; docs/console-editing.md), so what a hand
// does here a script does in af-console alike, and errors print in the console panel.

#include "console/command_system.h"
#include "console/session.h"

#include <string>
#include <vector>

namespace af::view {

class FigurePanel {
public:
    // Selects a body of an entity (a click on it in the 3D view).
    void selectBody(const std::string& entity, const std::string& body);
    // "ENTITY body NAME", "ENTITY constraint NAME", "ENTITY" or "nothing" (view_selection).
    std::string selection() const;

    // Draws the panel in the rectangle given (pixels).
    void draw(console::CommandSystem& console, const console::Session& session, float x, float y, float width, float height);

private:
    enum class Kind { None, Body, Constraint };
    void drawItems(const DeclAF& decl);
    void drawBody(console::CommandSystem& console, const AFBody& body);
    void drawConstraint(console::CommandSystem& console, const AFConstraint& constraint);
    void drawWarnings(Kind kind, int index) const;
    void drawKeyLine(console::CommandSystem& console, const std::string& prefix);
    void run(console::CommandSystem& console, const std::string& command);

    std::string entity_;
    Kind kind_ = Kind::None;
    std::string item_;  // the body's or constraint's name
    std::string key_, value_;  // the free key line
    // The decl drawn, and its checks, recomputed when the session's decl changes (each costs a
    // few thousand point tests per constraint: too many for every frame).
    DeclAF checkedDecl_;
    std::string checkedEntity_;
    std::vector<FigureWarning> warnings_;
    std::vector<std::string> bodyOrder_, constraintOrder_;  // the figure's names, by the warnings' indices
};

}  // namespace af::view
