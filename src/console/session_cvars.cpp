// The simulation cvars of Doom's §4.13 that mean something without a renderer (docs/doom-physics.md
// §4.13), each written into the session's WorldSettings and handed to the world at once
// (World::setSettings, which wakes every figure). A map load builds its world from the same
// settings, so a cvar set before `map` holds after it.

#include "console/session_state.h"

namespace af::console {

namespace {

using State = Session::State;

// The step a `step` takes: Doom's frame of 1/60 s, scaled by af_timeScale (slow motion below 1).
constexpr Real kFrame = Real(1) / 60;

void apply(State& s) { s.world.setSettings(s.worldSettings); }

void addSimulationCvar(CommandSystem& console, State& s, CVarDefinition definition,
                       std::function<void(WorldSettings&, const CVar&)> write) {
    definition.flags = definition.flags | CVarFlags::Simulation;
    definition.onChange = [&s, write = std::move(write)](const CVar& v) {
        write(s.worldSettings, v);
        apply(s);
    };
    console.addCVar(std::move(definition));
}

// Doom's caps are per step; ours are rates, so they follow the (scaled) step. (At the defaults
// they equal WorldSettings' own, which the world keeps until a cvar changes.)
void writeCaps(WorldSettings& w, const CVarSystem& cvars) {
    w.integration.maxLinearSpeed = cvars.find("af_maxLinearVelocity")->asReal() / w.timeStep;
    w.integration.maxAngularSpeed = cvars.find("af_maxAngularVelocity")->asReal() / w.timeStep;
}

}  // namespace

void registerSimulationCvars(State& s, CommandSystem& console) {
    CVarSystem& cvars = console.cvars();
    addSimulationCvar(console, s, boolCVar("af_useLinearTime", true, "solve each figure's joints through its tree factorisation; 0: the dense pivoting solve of every row"),
                      [](WorldSettings& w, const CVar& v) { w.solver = v.asBool() ? SolverKind::Tree : SolverKind::Exact; });
    addSimulationCvar(console, s, boolCVar("af_skipSelfCollision", false, "a figure's bodies pass through each other"),
                      [](WorldSettings& w, const CVar& v) { w.collision.skipSelfCollision = v.asBool(); });
    addSimulationCvar(console, s, boolCVar("af_skipLimits", false, "ignore cone, pyramid and hinge limits"),
                      [](WorldSettings& w, const CVar& v) { w.rows.limits = !v.asBool(); });
    addSimulationCvar(console, s, boolCVar("af_skipFriction", false, "no joint and no contact friction"),
                      [](WorldSettings& w, const CVar& v) { w.rows.friction = w.contact.friction = !v.asBool(); });
    addSimulationCvar(console, s, realCVar("af_forceFriction", -1, {-1, 100}, "> 0: every joint's friction coefficient, instead of its own"),
                      [](WorldSettings& w, const CVar& v) { w.rows.forcedFriction = v.asReal() > 0 ? v.asReal() : 0; });
    addSimulationCvar(console, s, realCVar("af_maxLinearVelocity", 128, {0, 1e6}, "largest linear velocity, units per step"),
                      [&cvars](WorldSettings& w, const CVar&) { writeCaps(w, cvars); });
    addSimulationCvar(console, s, realCVar("af_maxAngularVelocity", 1.57, {0, 1e4}, "largest angular velocity, radians per step"),
                      [&cvars](WorldSettings& w, const CVar&) { writeCaps(w, cvars); });
    addSimulationCvar(console, s, realCVar("af_timeScale", 1, {0.01, 10}, "simulated time per step, in 1/60 s (below 1: slow motion)"),
                      [&cvars](WorldSettings& w, const CVar& v) {
                          w.timeStep = kFrame * v.asReal();
                          writeCaps(w, cvars);
                      });
    addSimulationCvar(console, s, realCVar("g_gravity", 1066, {-1e5, 1e5}, "gravity, units/s² downwards"),
                      [](WorldSettings& w, const CVar& v) { w.gravity = Vec3(0, 0, -v.asReal()); });
}

}  // namespace af::console
