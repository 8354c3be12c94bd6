// The af_show* cvars' printed blocks (session_show.h): one block per enabled cvar, entities in
// spawn order, each heading named by the cvar and the entity, so a script's log says what it is.

#include "console/session_show.h"
#include "console/console_text.h"

#include "console/session_state.h"
#include "console/show_geometry.h"

#include "af/text/strings.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

namespace af::console {

namespace {

struct ShowCVar {
    const char* name;
    bool ShowFlags::*flag;
    const char* help;
};

constexpr ShowCVar kShowCVars[] = {
    {"af_showBodies", &ShowFlags::bodies, "print each body's shape and position after a step (step, run, waitRest)"},
    {"af_showBodyNames", &ShowFlags::bodyNames, "print the body names after a step; screenshot labels the bodies"},
    {"af_showMass", &ShowFlags::mass, "print each body's mass after a step"},
    {"af_showTotalMass", &ShowFlags::totalMass, "print each ragdoll's total mass after a step"},
    {"af_showInertia", &ShowFlags::inertia, "print each body's inertia tensor (body frame) after a step"},
    {"af_showVelocity", &ShowFlags::velocity, "print each body's velocities after a step; screenshot draws them as arrows"},
    {"af_showConstraints", &ShowFlags::constraints,
     "print the constraints (kind, bodies, anchor) after a step; screenshot draws anchors and axes"},
    {"af_showConstraintNames", &ShowFlags::constraintNames, "print the constraint names after a step; screenshot labels the anchors"},
    {"af_showLimits", &ShowFlags::limits, "print each limited joint's angles against its limits after a step; screenshot draws the limits"},
    {"af_showTrees", &ShowFlags::trees, "print each ragdoll's body tree after a step; screenshot draws parent to child lines"},
    {"af_showContacts", &ShowFlags::contacts,
     "print each contact point with the impulse the last step's velocity solve applied there (mass units * units/s) after a "
     "step; screenshot draws the points, their normals (red) and the normal impulses along them (orange, 1 unit per 50)"},
    {"af_showActive", &ShowFlags::active, "the other af_show* and af_highlight* only for ragdolls not at rest"},
    {"af_showTimings", &ShowFlags::timings, "print the steps' wall-clock cost after step, run and waitRest"},
};


std::string vec(const Vec3& v) { return "(" + fixed(v.x()) + " " + fixed(v.y()) + " " + fixed(v.z()) + ")"; }


// One entity as the blocks see it.
struct Shown {
    const Entity& entity;
    const World& world;
    const Figure& figure;
    World::FigureRange range;
    std::size_t nameWidth = 0;  // the longest body name, for a column

    std::string bodyName(int worldBody) const {
        return worldBody == kWorldBody ? "world" : figure.bodies[std::size_t(worldBody - range.firstBody)].name;
    }
    const RigidBody& body(int b) const { return world.bodies()[std::size_t(range.firstBody + b)]; }
    // Body B of a contact of ours: the world, one of our bodies, or another figure's body.
    std::string contactPartner(const BodyContact& c) const {
        if (c.bodyB == kStaticWorld) return "world";
        const FigureId other = world.figureOf(c.bodyB);
        if (other.value < 0) return "body " + std::to_string(c.bodyB);
        return world.definition(other).bodies[std::size_t(c.bodyB - world.range(other).firstBody)].name;
    }
};

// `kindWidth` lines up the bodies of a list (the longest kind, ballAndSocketJoint, is 18 letters).
std::string constraintLine(const Shown& e, const Joint& j, std::size_t kindWidth = 0) {
    return padded(toString(j.type), kindWidth) + "  " + e.bodyName(j.bodyA) + " - " + e.bodyName(j.bodyB) + "  at " +
           vec(jointAnchor(j, e.world.bodies()));
}

std::string limitText(const std::vector<LimitReading>& readings) {
    std::string out;
    for (const LimitReading& r : readings) {
        out += (out.empty() ? "" : "; ") + r.name;
        for (std::size_t i = 0; i < r.angles.size(); ++i) {
            const LimitReading::Angle& a = r.angles[i];
            out += (i ? ", " : " ") + fixed(a.value, 1) + " in [" + fixed(a.lower, 1) + ", " + fixed(a.upper, 1) + "]";
        }
        if (r.past() > 0.05) out += " PAST by " + fixed(r.past(), 1);
    }
    return out;
}

void printTree(const Shown& e, const std::vector<std::pair<int, int>>& edges, int body, int depth, const Output& out) {
    out.info(std::string(std::size_t(2 + 2 * depth), ' ') + e.figure.bodies[std::size_t(body)].name);
    for (const auto& [parent, child] : edges)
        if (parent == body) printTree(e, edges, child, depth + 1, out);
}

// Each block: the cvar's name and the entity's as its heading, then its lines (or the heading
// alone holding them, for a one-line block).
using Block = std::function<void(const Shown&, const Output&)>;

void perBody(const Shown& e, const Output& out, const std::function<std::string(int)>& line) {
    for (int b = 0; b < e.range.bodyCount; ++b) out.info("  " + padded(e.figure.bodies[std::size_t(b)].name, e.nameWidth) + "  " + line(b));
}

std::vector<std::pair<bool ShowFlags::*, Block>> blocks() {
    return {
        {&ShowFlags::bodies, [](const Shown& e, const Output& out) {
             out.info("af_showBodies " + e.entity.name + ":");
             perBody(e, out, [&](int b) { return padded(toString(e.figure.bodies[std::size_t(b)].shapeKind), 12) + vec(e.body(b).position); });
         }},
        {&ShowFlags::bodyNames, [](const Shown& e, const Output& out) {
             std::string line = "af_showBodyNames " + e.entity.name + ":";
             for (const FigureBody& b : e.figure.bodies) line += " " + b.name;
             out.info(line);
         }},
        {&ShowFlags::mass, [](const Shown& e, const Output& out) {
             out.info("af_showMass " + e.entity.name + ":");
             perBody(e, out, [&](int b) { return fixed(e.body(b).mass()); });
         }},
        {&ShowFlags::totalMass, [](const Shown& e, const Output& out) {
             Real total = 0;
             for (int b = 0; b < e.range.bodyCount; ++b) total += e.body(b).mass();
             out.info("af_showTotalMass " + e.entity.name + ": " + fixed(total));
         }},
        {&ShowFlags::inertia, [](const Shown& e, const Output& out) {
             out.info("af_showInertia " + e.entity.name + " (xx yy zz  xy xz yz, body frame):");
             perBody(e, out, [&](int b) {
                 const Mat3& i = e.body(b).inertia;
                 return fixed(i(0, 0)) + " " + fixed(i(1, 1)) + " " + fixed(i(2, 2)) + "  " + fixed(i(0, 1)) + " " + fixed(i(0, 2)) + " " +
                        fixed(i(1, 2));
             });
         }},
        {&ShowFlags::velocity, [](const Shown& e, const Output& out) {
             out.info("af_showVelocity " + e.entity.name + " (linear units/s, angular rad/s):");
             perBody(e, out, [&](int b) { return "v " + vec(e.body(b).linearVelocity) + "  w " + vec(e.body(b).angularVelocity); });
         }},
        {&ShowFlags::constraints, [](const Shown& e, const Output& out) {
             out.info("af_showConstraints " + e.entity.name + ":");
             const std::vector<const Joint*> joints = figureJoints(e.world, e.entity.figure);
             std::size_t width = 0;
             for (const Joint* j : joints) width = std::max(width, j->name.size());
             for (const Joint* j : joints) out.info("  " + padded(j->name, width) + "  " + constraintLine(e, *j, 18));
         }},
        {&ShowFlags::constraintNames, [](const Shown& e, const Output& out) {
             std::string line = "af_showConstraintNames " + e.entity.name + ":";
             for (const Joint* j : figureJoints(e.world, e.entity.figure)) line += " " + j->name;
             out.info(line);
         }},
        {&ShowFlags::limits, [](const Shown& e, const Output& out) {
             out.info("af_showLimits " + e.entity.name + " (degrees):");
             const std::vector<const Joint*> joints = figureJoints(e.world, e.entity.figure);
             std::size_t width = 0;
             for (const Joint* j : joints) width = std::max(width, j->name.size());
             for (const Joint* j : joints)
                 if (const auto readings = limitReadings(*j, e.world.bodies()); !readings.empty())
                     out.info("  " + padded(j->name, width) + "  " + limitText(readings));
         }},
        {&ShowFlags::contacts, [](const Shown& e, const Output& out) {
             out.info("af_showContacts " + e.entity.name + " (normal impulse, friction impulse; mass units * units/s):");
             const std::vector<ContactImpulse> impulses = e.world.contactImpulses();
             std::size_t i = 0;
             for (const BodyContact& c : e.world.contacts())
                 for (int k = 0; k < c.manifold.count; ++k, ++i)
                     if (e.world.figureOf(c.bodyA) == e.entity.figure)
                         out.info("  " + padded(e.bodyName(c.bodyA), e.nameWidth) + " - " + e.contactPartner(c) + "  at " +
                                  vec(c.manifold.points[std::size_t(k)].point) + "  " + fixed(impulses[i].normal) + ", " +
                                  fixed(impulses[i].friction.norm()));
         }},
        {&ShowFlags::trees, [](const Shown& e, const Output& out) {
             out.info("af_showTrees " + e.entity.name + ":");
             const std::vector<std::pair<int, int>> edges = treeEdges(e.figure);
             for (int b = 0; b < e.range.bodyCount; ++b)
                 if (std::none_of(edges.begin(), edges.end(), [&](const auto& edge) { return edge.second == b; })) printTree(e, edges, b, 0, out);
         }},
    };
}

void printHighlights(const ShowFlags& flags, const std::vector<Shown>& shown, const Output& out) {
    if (!flags.highlightBody.empty()) {
        bool found = false;
        for (const Shown& e : shown) {
            const int b = e.figure.findBody(flags.highlightBody);
            if (b < 0) continue;
            found = true;
            const RigidBody& body = e.body(b);
            out.info("af_highlightBody " + e.entity.name + " " + e.figure.bodies[std::size_t(b)].name + ": " +
                     toString(e.figure.bodies[std::size_t(b)].shapeKind) + " at " + vec(body.position) + ", mass " + fixed(body.mass()) +
                     ", v " + vec(body.linearVelocity));
        }
        if (!found) out.info("af_highlightBody: no ragdoll shown has a body named " + flags.highlightBody);
    }
    if (!flags.highlightConstraint.empty()) {
        bool found = false;
        for (const Shown& e : shown)
            for (const Joint* j : figureJoints(e.world, e.entity.figure)) {
                if (!equalsIgnoreCase(j->name, flags.highlightConstraint)) continue;
                found = true;
                const std::string limits = limitText(limitReadings(*j, e.world.bodies()));
                out.info("af_highlightConstraint " + e.entity.name + " " + j->name + ": " + constraintLine(e, *j) +
                         (limits.empty() ? "" : "; " + limits));
            }
        if (!found) out.info("af_highlightConstraint: no ragdoll shown has a constraint named " + flags.highlightConstraint);
    }
}

}  // namespace

void addShowCVars(CommandSystem& console) {
    for (const ShowCVar& c : kShowCVars) console.addCVar(boolCVar(c.name, false, c.help));
    console.addCVar(stringCVar("af_highlightBody", "", "print this body (of every ragdoll that has one) after a step; screenshot draws it highlighted"));
    console.addCVar(stringCVar("af_highlightConstraint", "",
                               "print this constraint after a step; screenshot draws its anchor, axes and limits highlighted"));
}

ShowFlags showFlags(const CVarSystem& cvars) {
    ShowFlags flags;
    for (const ShowCVar& c : kShowCVars)
        if (const CVar* v = cvars.find(c.name)) flags.*c.flag = v->asBool();
    if (const CVar* v = cvars.find("af_highlightBody")) flags.highlightBody = v->asString();
    if (const CVar* v = cvars.find("af_highlightConstraint")) flags.highlightConstraint = v->asString();
    return flags;
}

void ShowReport::attach(CommandSystem& console) {
    addShowCVars(console);
    cvars_ = &console.cvars();
}

void ShowReport::step(World& world) {
    const auto start = std::chrono::steady_clock::now();
    world.step();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ++steps_;
    totalMs_ += ms;
    longestMs_ = std::max(longestMs_, ms);
    for (const RestoredFigure& r : world.lastStep().restored) restored_.push_back({world.time(), r});
}

void ShowReport::print(const Session::State& s, const Output& out) {
    for (const Restore& r : restored_) {
        const auto e = std::find_if(s.entities.begin(), s.entities.end(), [&](const Entity& x) { return x.figure == r.figure.figure; });
        const std::string why = r.figure.reason == InvalidMotion::NonFinite
                                    ? "a NaN or an infinity"
                                    : "kinetic energy " + general(r.figure.energy) + " where at most " + general(r.figure.budget) + " could be supplied";
        out.info("warning: " + (e != s.entities.end() ? e->name : std::string("a body of no entity")) + ": invalid motion at " +
                 fixed(r.time) + " s (" + why + "): put back where it was before the step, at rest");
    }
    restored_.clear();
    const ShowFlags flags = cvars_ ? showFlags(*cvars_) : ShowFlags{};
    if (flags.timings)
        out.info("af_showTimings: " + std::to_string(steps_) + (steps_ == 1 ? " step, " : " steps, ") + fixed(totalMs_) + " ms" +
                 (steps_ ? " (" + fixed(totalMs_ / double(steps_)) + " ms a step, longest " + fixed(longestMs_) + ")" : ""));
    steps_ = 0;
    totalMs_ = longestMs_ = 0;

    std::vector<Shown> shown;
    for (const Entity& e : s.entities) {
        if (flags.active && s.world.figureAtRest(e.figure)) continue;
        Shown view{e, s.world, s.world.definition(e.figure), s.world.range(e.figure)};
        for (const FigureBody& b : view.figure.bodies) view.nameWidth = std::max(view.nameWidth, b.name.size());
        shown.push_back(view);
    }
    for (const auto& [flag, block] : blocks())
        if (flags.*flag)
            for (const Shown& e : shown) block(e, out);
    printHighlights(flags, shown, out);
}

}  // namespace af::console
