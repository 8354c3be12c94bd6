#pragma once
// What af-sim writes: the summary (text or JSON), pictures, per-step trajectories and the
// baked .md5anim.

#include "render/render.h"
#include "sim_run.h"

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>

namespace af::sim {

std::string summaryText(const Scene& scene, const RunResult& result);
nlohmann::ordered_json summaryJson(const Scene& scene, const RunResult& result);

// The scene's bodies at `poses` (one per world body), with its statics and floor.
render::RenderScene renderScene(const Scene& scene, const std::vector<RigidPose>& poses);

void writeFinalPng(const Scene& scene, const std::string& path);
void writeFramesPng(const Scene& scene, const RunResult& result, const std::string& path);
void writePlotPng(const Scene& scene, const RunResult& result, const std::string& path);

// One JSON object per line: {"t": seconds, "bodies": [{"name", "p": [x,y,z], "q": [x,y,z,w]}]},
// q the body → world rotation as a unit quaternion (our convention, not md5's).
void writeTrajectoryLine(const Scene& scene, const World& world, std::ostream& out);

}  // namespace af::sim
