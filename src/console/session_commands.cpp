// The session's commands and cvars (session.h), each a thin reader of its arguments over
// Session::State. Names and meanings follow Doom's console (docs/doom-physics.md §5.1, §5.2).

#include "console/console_text.h"
#include "console/session_state.h"

#include "af/text/strings.h"

#include <cmath>
#include <cstdio>

namespace af::console {

namespace {

using State = Session::State;

std::optional<Vec3> vector(const CommandArgs& args, std::size_t first) {
    const auto x = args.number(first), y = args.number(first + 1), z = args.number(first + 2);
    if (!x || !y || !z) return std::nullopt;
    return Vec3(*x, *y, *z);
}


Status failure(const std::optional<std::string>& error) { return error ? Status::failure(*error) : Status::success(); }

std::vector<std::string> entityNames(const State& s) {
    std::vector<std::string> out;
    for (const Entity& e : s.entities) out.push_back(e.name);
    return out;
}

// Steps the world n times; the clock moves only here.
void advance(State& s, int steps) {
    for (int i = 0; i < steps; ++i) s.show.step(s.world);
}

Status dragCommand(State& s, const CommandArgs& args, const Output& out) {
    if (args.argc() == 2 && equalsIgnoreCase(args.argv(1), "off")) {
        s.world.clearDrag();
        out.info("drag off");
        return Status::success();
    }
    if (args.argc() == 4) {
        if (!s.world.drag()) return Status::failure("nothing is dragged: drag ENTITY BODY X Y Z first");
        const auto target = vector(args, 1);
        if (!target) return Status::failure("drag: X Y Z must be numbers");
        Drag d = *s.world.drag();
        d.target = *target;
        d.damping = s.dragDamping;
        s.world.setDrag(d);
        return Status::success();
    }
    if (args.argc() != 6 && args.argc() != 9) return Status::failure("usage: drag ENTITY BODY X Y Z [LX LY LZ] | drag X Y Z | drag off");
    const Entity* e = s.find(args.argv(1));
    if (!e) return Status::failure("drag: no entity named " + args.argv(1));
    const int body = s.world.definition(e->figure).findBody(args.argv(2));
    if (body < 0) return Status::failure("drag: " + e->name + " has no body " + args.argv(2));
    const auto target = vector(args, 3);
    if (!target) return Status::failure("drag: X Y Z must be numbers");
    Vec3 local = Vec3::Zero();
    if (args.argc() == 9) {
        const auto l = vector(args, 6);
        if (!l) return Status::failure("drag: LX LY LZ must be numbers");
        local = *l;
    }
    s.world.setDrag(Drag{{e->figure, body}, local, *target, s.dragDamping});
    s.selected = e->name;
    out.info("dragging " + e->name + " " + args.argv(2));
    return Status::success();
}

}  // namespace

void registerSessionCommands(State& s, CommandSystem& console) {
    const auto completeEntities = [&s](const CommandArgs& typed, std::string_view) {
        return typed.argc() == 1 ? entityNames(s) : std::vector<std::string>{};
    };
    const auto completeEntityDefs = [&s](const CommandArgs& typed, std::string_view) {
        std::vector<std::string> out;
        if (typed.argc() == 1)
            for (const EntityDef& def : s.index->defs().entityDefs())
                if (!def.valueOr("articulatedFigure").empty()) out.push_back(def.name);
        return out;
    };

    CVarDefinition damping = realCVar("g_dragDamping", 0.5, {0, 0.99},
                                      "how much of its own velocity a dragged point keeps each step (docs/doom-physics.md §5.2)");
    damping.onChange = [&s](const CVar& v) { s.dragDamping = v.asReal(); };
    console.addCVar(std::move(damping));
    registerSimulationCvars(s, console);
    registerEditCommands(s, console);
    s.show.attach(console);
    console.addCommand({"map", "FILE", "load a .map: its brushes and its AF entities, posed by their saved body keys", 1, 1,
                        [&s](const CommandArgs& a, const Output& out) { return failure(s.loadMap(a.argv(1), out)); }, {}});
    console.addCommand({"spawn", "ENTITYDEF [KEY VALUE]...", "spawn an AF entityDef (keys: origin \"x y z\", angle, angles, name)", 1, {},
                        [&s](const CommandArgs& a, const Output& out) {
                            if (a.argc() % 2 != 0) return Status::failure("spawn: every key needs a value");
                            MapKeyValues keys;
                            for (std::size_t i = 2; i + 1 < a.argc(); i += 2) keys.set(a.argv(i), a.argv(i + 1));
                            return failure(s.spawn(a.argv(1), keys, out));
                        },
                        completeEntityDefs});
    console.addCommand({"list", "", "the entities: name, entityDef, active or resting, position of the root body", 0, 0,
                        [&s](const CommandArgs&, const Output& out) {
                            for (const Entity& e : s.entities) {
                                const Vec3 p = s.world.body({e.figure, 0}).position;
                                out.info(e.name + "  " + e.entityDef + "  " + (s.world.figureAtRest(e.figure) ? "resting" : "active") +
                                         "  (" + fixed(p.x()) + " " + fixed(p.y()) + " " + fixed(p.z()) + ")");
                            }
                            out.info(std::to_string(s.entities.size()) + " entities");
                            return Status::success();
                        },
                        {}});
    console.addCommand({"step", "[N]", "advance the world N steps (1)", 0, 1,
                        [&s](const CommandArgs& a, const Output& out) {
                            int n = 1;
                            if (a.argc() == 2) {
                                const auto v = a.number(1);
                                if (!v || *v < 0 || *v > 1e6 || *v != std::floor(*v)) return Status::failure("step: N must be a whole number of steps");
                                n = static_cast<int>(*v);
                            }
                            advance(s, n);
                            s.show.print(s, out);
                            return Status::success();
                        },
                        {}});
    console.addCommand({"run", "SECONDS", "advance the world this many seconds", 1, 1,
                        [&s](const CommandArgs& a, const Output& out) {
                            const auto v = a.number(1);
                            if (!v || *v < 0 || *v > 3600) return Status::failure("run: SECONDS must be a number from 0 to 3600");
                            advance(s, static_cast<int>(std::ceil(*v / s.world.settings().timeStep - 1e-9)));
                            s.show.print(s, out);
                            return Status::success();
                        },
                        {}});
    console.addCommand({"waitRest", "[MAX_SECONDS]", "advance until every ragdoll rests (at most 10 s, or MAX_SECONDS)", 0, 1,
                        [&s](const CommandArgs& a, const Output& out) {
                            Real most = 10;
                            if (a.argc() == 2) {
                                const auto v = a.number(1);
                                if (!v || *v < 0 || *v > 3600) return Status::failure("waitRest: MAX_SECONDS must be a number from 0 to 3600");
                                most = *v;
                            }
                            const Real start = s.world.time();
                            while (!s.world.atRest() && s.world.time() - start < most) s.show.step(s.world);
                            s.show.print(s, out);
                            if (!s.world.atRest()) return Status::failure("still moving after " + fixed(most) + " s");
                            out.info("at rest after " + fixed(s.world.time() - start) + " s");
                            return Status::success();
                        },
                        {}});
    console.addCommand({"drag", "ENTITY BODY X Y Z [LX LY LZ] | X Y Z | off",
                        "pull a body's point (its centre, or LX LY LZ in its frame) toward X Y Z every step; move the target; let go", 1, 8,
                        [&s](const CommandArgs& a, const Output& out) { return dragCommand(s, a, out); }, completeEntities});
    console.addCommand({"bindRagdoll", "", "hold the dragged point where it is now with a ball-and-socket to the world", 0, 0,
                        [&s](const CommandArgs&, const Output& out) {
                            if (!s.world.drag()) return Status::failure("bindRagdoll: nothing is dragged");
                            const Drag& d = *s.world.drag();
                            const RigidBody& b = s.world.body(d.body);
                            s.world.bind(d.body, b.position + b.rotation() * d.localPoint);
                            out.info("bound");
                            return Status::success();
                        },
                        {}});
    console.addCommand({"unbindRagdoll", "", "remove every bind to the world", 0, 0,
                        [&s](const CommandArgs&, const Output&) {
                            for (const Entity& e : s.entities) s.world.unbind(e.figure);
                            return Status::success();
                        },
                        {}});
    const auto save = [&s](bool selectedOnly) {
        return [&s, selectedOnly](const CommandArgs& a, const Output& out) {
            return failure(s.save(a.argc() == 2 ? std::filesystem::path(a.argv(1)) : std::filesystem::path(), selectedOnly, out));
        };
    };
    console.addCommand({"saveRagdolls", "[FILE]", "write every ragdoll's body poses into the map (or FILE)", 0, 1, save(false), {}});
    console.addCommand({"saveSelected", "[FILE]", "write the selected ragdoll's body poses into the map (or FILE)", 0, 1, save(true), {}});
    const auto deleteSelected = [&s](const CommandArgs&, const Output& out) {
        if (!s.find(s.selected)) return Status::failure("no entity is selected (spawn or drag one)");
        const std::string name = s.selected;
        s.remove(name);
        out.info("deleted " + name);
        return Status::success();
    };
    console.addCommand({"deleteSelected", "", "remove the entity last spawned or dragged", 0, 0, deleteSelected, {}});
    console.addCommand({"deleteRagdoll", "", "the same as deleteSelected", 0, 0, deleteSelected, {}});
    console.addCommand({"killRagdolls", "", "remove every ragdoll", 0, 0,
                        [&s](const CommandArgs&, const Output& out) {
                            const std::size_t n = s.entities.size();
                            while (!s.entities.empty()) s.remove(s.entities.back().name);
                            out.info("removed " + std::to_string(n));
                            return Status::success();
                        },
                        {}});
    const auto reload = [&s](const CommandArgs&, const Output& out) {
        s.reload(out);
        return Status::success();
    };
    console.addCommand({"reloadDecls", "", "re-read the .af and .def files and respawn the ragdolls whose figure changed", 0, 0, reload, {}});
    console.addCommand({"reloadAFs", "", "the same as reloadDecls", 0, 0, reload, {}});
}

}  // namespace af::console
