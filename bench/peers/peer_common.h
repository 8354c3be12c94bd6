#pragma once
// What the ODE and Bullet peer programs of docs/bench-scene.md §5 share: the command line, the joint
// frames of §2 expressed as engine-neutral rotations, the start-up sign probe's report and the
// run loop that feeds benchscene::RunMetrics. Frames: model/body-local axes as in §2, SI units.

#include "scene_def.h"

#include <Eigen/Geometry>

#include <array>
#include <functional>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace peers {

using benchscene::JointDef;
using benchscene::Quat;
using benchscene::Vec3;

using benchscene::kBodiesPerRagdoll;
inline constexpr double kDt = benchscene::kTimeStep;

struct Options {
    std::string scene = "single";
    int count = 0;  // the pile's ragdolls; 0: the scene's own
    std::string variant;
    int steps = 600;
    double maxSeconds = 0.0;  // 0 = no limit
    bool sleep = false;
    bool selftest = false;
};

// Prints the usage to stderr and returns nullopt on a bad command line.
std::optional<Options> parseOptions(int argc, char** argv, std::initializer_list<std::string_view> variants);

// Hinge frame: z = the hinge axis (Bullet's convention), x and y any right-handed completion.
Eigen::Matrix3d hingeBasis(const Vec3& axis);
// Universal frame: x = axis 1, y = axis 2, z = axis 1 × axis 2 (the locked rotation).
Eigen::Matrix3d universalBasis(const JointDef& j);

// Swing and twist of a cone+twist joint with the world unit axes along which they grow:
// d(swing)/dt = (ω_B − ω_A)·swingAxis, d(twist)/dt = (ω_B − ω_A)·twistAxis / cos(swing/2).
struct ConeState {
    double swing, twist;
    Vec3 swingAxis, twistAxis;
};
// frames: benchscene::coneTwistFrames(j).
ConeState coneState(const JointDef& j, const std::array<Quat, 2>& frames, const Quat& qA, const Quat& qB);

// One joint of the start-up sign probe: the §2 angles of a known relative rotation and what the
// engine reports for it. sign[k] = +1 if the engine's angle k has the §2 sign, −1 if it is negated.
struct ProbeRow {
    std::string joint;
    std::vector<double> scene, engine;
    std::array<int, 2> sign{1, 1};
    bool ok = false;  // |engine| equals |scene| for every angle (same convention up to sign)
};
// Relative rotation the probe applies to the child: hinge 0.3 rad; universal θ1 = 0.3, θ2 = 0.5.
Quat probeRotation(const JointDef& j);
// Fills sign/ok from scene and engine angles (tolerance suits single-precision engines).
void judgeProbe(ProbeRow& row);
std::string probeReport(std::string_view engine, std::span<const ProbeRow> rows, std::string_view extraJsonFields);
bool probeOk(std::span<const ProbeRow> rows);

// Limits [lo, hi] of a §2 angle for an engine whose angle has the given sign.
inline std::array<double, 2> engineLimits(double lo, double hi, int sign) {
    return sign > 0 ? std::array<double, 2>{lo, hi} : std::array<double, 2>{-hi, -lo};
}

// The run of §6: only `step` is timed (steady_clock). After it, `contactDepth` gives the deepest
// penetration among the engine's contacts of that step, `read` fills the states (ragdoll-major)
// and `asleep` says whether every body sleeps by the engine's own criterion (asked only when
// sleeping is on). Prints the metrics' JSON to stdout.
struct RunHooks {
    std::function<void()> step;
    std::function<double()> contactDepth;
    std::function<void(std::span<benchscene::BodyState>)> read;
    std::function<bool()> asleep;
    std::function<std::string()> extraJson;  // further fields, e.g. "\"mlcp_fallbacks\": 3"
};
void runScene(const Options& o, std::string_view engine, int ragdolls, const RunHooks& hooks);

}  // namespace peers
