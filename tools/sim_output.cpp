#include "sim_output.h"

#include <algorithm>
#include <cstdio>

namespace af::sim {

namespace {

std::string fixed(Real value, int decimals) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return buffer;
}

std::string general(Real value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.3g", value);
    return buffer;
}

Real microsecondsPerStep(const RunResult& r) { return r.steps > 0 ? 1e6 * r.wallSeconds / r.steps : 0; }

// The figure body behind world body i.
const FigureBody& figureBody(const Scene& scene, std::size_t worldBody) {
    const FigureId id = scene.world.figureOf(static_cast<int>(worldBody));
    const int first = scene.world.range(id).firstBody;
    return scene.world.definition(id).bodies[worldBody - static_cast<std::size_t>(first)];
}

std::string bodyName(const Scene& scene, std::size_t worldBody) {
    const std::string& name = figureBody(scene, worldBody).name;
    if (scene.figures.size() == 1) return name;
    return name + "#" + std::to_string(scene.world.figureOf(static_cast<int>(worldBody)).value);
}

std::string figureName(const Scene& scene, FigureId figure) {
    const auto at = std::find(scene.figures.begin(), scene.figures.end(), figure);
    const std::string number = std::to_string(at - scene.figures.begin() + 1);
    return scene.figures.size() == 1 ? "the figure" : "figure " + number;
}

std::string reasonText(const RestoredFigure& r) {
    if (r.reason == InvalidMotion::NonFinite) return "a NaN or an infinity";
    return "kinetic energy " + general(r.energy) + " where at most " + general(r.budget) + " could be supplied";
}

}  // namespace

std::string summaryText(const Scene& scene, const RunResult& r) {
    std::string out = "af-sim: " + scene.description + "\n";
    out += r.restTime ? "  at rest after       " + fixed(*r.restTime, 2) + " s simulated\n"
                      : "  not at rest after   " + fixed(r.simulatedSeconds, 2) + " s simulated (time limit)\n";
    if (scene.lifted > 0)
        out += "  lifted              " + fixed(scene.lifted, 2) + " units above the drop height, clear of the map's brushes\n";
    out += "  steps               " + std::to_string(r.steps) + " of " + fixed(scene.world.settings().timeStep * 1000, 2) +
           " ms\n";
    out += "  wall time           " + fixed(r.wallSeconds, 3) + " s, " + fixed(microsecondsPerStep(r), 1) + " us per step\n";
    out += "  max joint error     " + general(r.maxJointError) + " units\n";
    out += "  max penetration     " + general(r.maxPenetration) + " units\n";
    out += "  max limit violation " + general(r.maxLimitViolationDeg) + " deg\n";
    out += "  final kinetic energy " + general(r.finalKineticEnergy) + "\n";
    out += "  solver failures     " + std::to_string(r.solverFailures) + "\n";
    for (const RunResult::Restore& e : r.restored)
        out += "  invalid motion      " + figureName(scene, e.figure.figure) + " at " + fixed(e.time, 3) + " s: " +
               reasonText(e.figure) + "; put back where it was before the step, at rest\n";
    for (const RunResult::Stuck& e : r.stuck)
        out += "  stuck               " + figureName(scene, e.figure.figure) + " at " + fixed(e.time, 3) +
               " s: still, with a joint open " + general(e.figure.jointError) + " units and a contact " +
               general(e.figure.penetration) + " units deep; not at rest\n";
    return out;
}

nlohmann::ordered_json summaryJson(const Scene& scene, const RunResult& r) {
    nlohmann::ordered_json j;
    j["scene"] = scene.description;
    j["rest_time_s"] = r.restTime ? nlohmann::ordered_json(*r.restTime) : nlohmann::ordered_json(nullptr);
    j["simulated_s"] = r.simulatedSeconds;
    j["lifted"] = scene.lifted;
    j["steps"] = r.steps;
    j["wall_s"] = r.wallSeconds;
    j["us_per_step"] = microsecondsPerStep(r);
    j["max_joint_error"] = r.maxJointError;
    j["max_penetration"] = r.maxPenetration;
    j["max_limit_violation_deg"] = r.maxLimitViolationDeg;
    j["final_kinetic_energy"] = r.finalKineticEnergy;
    j["solver_failures"] = r.solverFailures;
    nlohmann::ordered_json restored = nlohmann::ordered_json::array();
    for (const RunResult::Restore& e : r.restored)
        restored.push_back({{"figure", figureName(scene, e.figure.figure)},
                            {"time_s", e.time},
                            {"reason", e.figure.reason == InvalidMotion::NonFinite ? "non-finite" : "energy gain"}});
    j["invalid_motion"] = restored;
    nlohmann::ordered_json stuck = nlohmann::ordered_json::array();
    for (const RunResult::Stuck& e : r.stuck)
        stuck.push_back({{"figure", figureName(scene, e.figure.figure)},
                         {"time_s", e.time},
                         {"joint_error", e.figure.jointError},
                         {"penetration", e.figure.penetration}});
    j["stuck"] = stuck;
    nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < scene.world.bodies().size(); ++i) {
        const RigidBody& b = scene.world.bodies()[i];
        bodies.push_back({{"name", bodyName(scene, i)},
                          {"figure", scene.world.figureOf(static_cast<int>(i)).value},
                          {"mass", b.mass()},
                          {"position", {b.position.x(), b.position.y(), b.position.z()}}});
    }
    j["bodies"] = bodies;
    return j;
}

render::RenderScene renderScene(const Scene& scene, const std::vector<RigidPose>& poses) {
    render::RenderScene out;
    for (std::size_t i = 0; i < poses.size(); ++i) out.bodies.push_back({figureBody(scene, i).shape, poses[i], {}});
    for (const Polytope& p : scene.statics) out.statics.push_back({p, RigidPose{}, {}});
    out.floorZ = scene.floorZ;
    return out;
}

void writeFinalPng(const Scene& scene, const std::string& path) {
    const render::RenderScene picture = renderScene(scene, scene.world.bodyPoses());
    render::writePng(picture, render::fitCamera(picture, 4.0 / 3.0), 1024, 768, path);
}

void writeFramesPng(const Scene& scene, const RunResult& r, const std::string& path) {
    std::vector<render::RenderScene> frames;
    std::vector<std::string> labels;
    for (std::size_t i = 0; i < r.frames.size(); ++i) {
        frames.push_back(renderScene(scene, r.frames[i]));
        labels.push_back("t = " + fixed(r.frameTimes[i], 2) + " s");
    }
    render::writeContactSheet(frames, labels, 4, path);
}

void writePlotPng(const Scene& scene, const RunResult& r, const std::string& path) {
    render::PlotData data;
    for (const Sample& s : r.history) {
        data.time.push_back(s.time);
        data.kineticEnergy.push_back(s.kineticEnergy);
        data.maxJointError.push_back(s.maxJointError);
    }
    data.restTime = r.restTime;
    data.title = scene.description;
    render::writePlot(data, path);
}

void writeTrajectoryLine(const Scene& scene, const World& world, std::ostream& out) {
    nlohmann::ordered_json line;
    line["t"] = world.time();
    nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < world.bodies().size(); ++i) {
        const RigidBody& b = world.bodies()[i];
        bodies.push_back({{"name", bodyName(scene, i)},
                          {"p", {b.position.x(), b.position.y(), b.position.z()}},
                          {"q", {b.orientation.x(), b.orientation.y(), b.orientation.z(), b.orientation.w()}}});
    }
    line["bodies"] = bodies;
    out << line.dump() << '\n';
}

}  // namespace af::sim
