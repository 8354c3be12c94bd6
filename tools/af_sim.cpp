// af-sim: drops ragdolls into a world, simulates until they rest, and reports what happened —
// as a summary (text or JSON), pictures, trajectories and a baked .md5anim.
//
// With no arguments: our humanoid ragdoll (entityDef ragdoll_humanoid from def/) dropped onto
// maps/default.map of this source tree.
//
// Exit status: 0 when the run finished (rested or not: the summary says which), 1 when a step
// made a figure's motion invalid (a NaN, an infinity or an explosion: the world put the figure
// back and the run went on; the summary says which and when) or a figure stood stuck (still with
// a joint open or a contact deep: World::kStuckJointError), 2 for bad usage or bad input (an unknown option or
// value, an unknown entity, a file that does not load or cannot be written).

#include "command_line_usage.h"
#include "sim_bake.h"
#include "sim_output.h"

#include <CLI/CLI.hpp>

#include <fstream>
#include <iostream>

namespace {

struct Options {
    af::sim::SceneOptions scene;
    af::sim::RunOptions run;
    std::string solver = "tree";
    std::vector<std::string> roots;
    std::string map;
    bool noMap = false;
    bool json = false;
    std::string png, frames, plot, trajectory, md5anim;
};

int simulate(Options& o) {
    using namespace af::sim;
    for (const std::string& r : o.roots) o.scene.roots.emplace_back(r);
    if (o.scene.roots.empty()) o.scene.roots.emplace_back(AF_DATA_DIR);
    if (!o.noMap) o.scene.map = o.map.empty() ? std::filesystem::path(AF_DATA_DIR) / "maps/default.map" : std::filesystem::path(o.map);
    o.scene.world.solver = o.solver == "pgs"    ? af::SolverKind::Pgs
                           : o.solver == "tree" ? af::SolverKind::Tree
                                                : af::SolverKind::Exact;
    if (!o.frames.empty()) o.run.framesWanted = 12;

    Scene scene = buildScene(o.scene);
    std::ofstream trajectory;
    if (!o.trajectory.empty()) {
        trajectory.open(o.trajectory);
        if (!trajectory) throw SceneError("cannot write the trajectory file " + o.trajectory);
    }
    std::optional<Baker> baker;
    if (!o.md5anim.empty()) baker.emplace(scene, 0);
    const RunResult result = run(scene, o.run, [&](const af::World& world) {
        if (trajectory.is_open()) writeTrajectoryLine(scene, world, trajectory);
        if (baker) baker->addFrame(world);
    });

    if (!o.png.empty()) writeFinalPng(scene, o.png);
    if (!o.frames.empty()) writeFramesPng(scene, result, o.frames);
    if (!o.plot.empty()) writePlotPng(scene, result, o.plot);
    if (baker) baker->write(o.md5anim);
    if (o.json) {
        std::cout << summaryJson(scene, result).dump(2) << '\n';
    } else {
        std::cout << summaryText(scene, result);
        for (const auto& [what, path] : {std::pair{"picture", o.png}, {"frames", o.frames}, {"plot", o.plot},
                                         {"trajectory", o.trajectory}, {"md5anim", o.md5anim}})
            if (!path.empty()) std::cout << "  " << what << ": " << path << '\n';
    }
    return result.restored.empty() && result.stuck.empty() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Drops Doom 3-style ragdolls into a world, simulates them until they rest and reports what happened."};
    CLI::Option* entity = app.add_option("--entity", o.scene.entity, "entityDef to spawn (one with an articulatedFigure)")->capture_default_str();
    app.add_option("--figure", o.scene.figure, "a bare .af decl to spawn instead, with its settings' model")->excludes(entity);
    app.add_option("--root", o.roots, "a mod folder laid out like Doom's base/ (repeat: lowest priority first)");
    CLI::Option* map = app.add_option("--map", o.map, ".map file whose worldspawn brushes are the world (default: maps/default.map)");
    CLI::Option* noMap = app.add_flag("--no-map", o.noMap, "drop onto an infinite floor at z = 0 instead of a map");
    app.add_option("--count", o.scene.count, "figures dropped in a pile")->check(CLI::Range(1, 1000))->capture_default_str();
    app.add_option("--seconds", o.run.seconds, "simulated time limit, seconds")->check(CLI::Range(0.001, 86400.0))->capture_default_str();
    app.add_option("--solver", o.solver, "constraint solver")->check(CLI::IsMember({"exact", "tree", "pgs"}))->capture_default_str();
    app.add_option("--threads", o.scene.world.threads, "threads that step figures apart side by side (same results on any count)")
        ->check(CLI::Range(1, 256))->capture_default_str();
    app.add_option("--seed", o.scene.seed, "a small deterministic initial push, from this seed");
    app.add_flag("--json", o.json, "print the summary as one JSON object");
    app.add_option("--png", o.png, "write a picture of the final pose");
    app.add_option("--frames", o.frames, "write a contact sheet of poses over time");
    app.add_option("--plot", o.plot, "write a plot of kinetic energy and joint error over time");
    app.add_option("--trajectory", o.trajectory, "write every body's pose per step (JSON lines)");
    app.add_option("--md5anim", o.md5anim, "bake the first figure's skeleton motion into an .md5anim");
    noMap->excludes(map);
    o.scene.world.timeStep = 1.0 / 60;
    if (const auto exitStatus = af::tools::parseCommandLine(app, argc, argv, "af-sim")) return *exitStatus;
    if (!o.scene.figure.empty()) o.scene.entity.clear();
    try {
        return simulate(o);
    } catch (const std::exception& e) {
        std::cerr << "af-sim: " << e.what() << '\n';
        return 2;
    }
}
