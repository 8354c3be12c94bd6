#pragma once
// The per-run measurements of docs/bench-scene.md §6, computed from body states only (never from an
// engine's own joint errors), so that every engine is judged by the same formulas.
// Feed addStep once per step, after the step, with the states of all bodies, ragdoll-major
// (ragdoll r's body i at r*16+i), and the wall time of the step call alone.

#include "scene_def.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace benchscene {

// What one set of states shows; the pieces RunMetrics accumulates.
struct StateMeasures {
    double jointErr = 0;     // m, largest anchor separation
    double jointAngErr = 0;  // rad, largest drift of a locked rotation
    double limitViol = 0;    // rad, largest excursion beyond a limit
    double groundPen = 0;    // m, deepest box corner below z = 0 (0 if none)
    double kinetic = 0;      // J
    double potential = 0;    // J, Σ m g z of the centres
    bool atRest = false;     // every body slower than the rest speeds
    bool exploded = false;   // NaN/inf, a body faster than 50 m/s, or a centre below z = −0.5 m
};
StateMeasures measureStates(std::span<const BodyState> states, int ragdolls);

class RunMetrics {
public:
    explicit RunMetrics(int ragdolls);

    // Optional, before the first step: the initial states, which then give energy_initial_J
    // (otherwise the energy after the first step does).
    void setInitial(std::span<const BodyState> states);
    // engineContactDepth: deepest penetration among the engine's own contacts this step (m);
    // negative or NaN when the engine does not report one.
    void addStep(std::span<const BodyState> states, double stepSeconds, double engineContactDepth);
    // Optional, sleeping runs: after addStep, whether every body is asleep by the engine's own
    // criterion. Once called, the JSON carries sleep_step.
    void addSleep(bool everyBodyAsleep);

    int stepsDone() const { return static_cast<int>(stepSeconds_.size()); }
    double jointErrMax() const { return jointErrMax_; }
    double jointAngErrMax() const { return jointAngErrMax_; }
    double limitViolMax() const { return limitViolMax_; }
    double groundPenMax() const { return groundPenMax_; }
    double energyGainMax() const { return energyGainMax_; }
    std::optional<int> restStep() const;
    bool exploded() const { return exploded_; }
    const StateMeasures& last() const { return last_; }

    // One JSON object with the fields of §6; extraJsonFields, if given, is inserted verbatim
    // as further members (e.g. "\"twist_limited\": false").
    std::string json(std::string_view engine, std::string_view variant, std::string_view scene, bool partial,
                     std::string_view extraJsonFields = {}) const;

private:
    int ragdolls_;
    std::vector<double> stepSeconds_;
    double jointErrMax_ = 0, jointAngErrMax_ = 0, limitViolMax_ = 0, groundPenMax_ = 0;
    double contactDepthMax_ = -1;  // negative: never reported
    std::optional<double> energyInitial_;
    double energyMin_ = 0, energyGainMax_ = 0;
    int lastNotAtRest_ = -1;
    bool exploded_ = false;
    StateMeasures last_;
    bool sleepReported_ = false;
    int lastAwake_ = -1;
};

}  // namespace benchscene
