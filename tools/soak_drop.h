#pragma once
// One drop of af-soak: a world on the default map, figures made hostile from the drop's seed, and
// what stepping it until it rests (or the time runs out) showed. A drop is a function of its
// seed and the shared inputs (map, sample figures, time limit): `af-soak --replay SEED` reruns it
// to the same bits.

#include "soak_figures.h"

#include "af/dynamics/world.h"
#include "af/geometry/polytope.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace af::soak {

// What every drop shares, read-only (so drops may run on several threads).
struct SoakInputs {
    std::vector<Polytope> brushes;        // the map's worldspawn brushes, world space
    std::vector<SampleFigure> samples;    // the mod folders' figures
    Real seconds = 5;                     // simulated time limit per drop
    // Wall-clock budget per drop, seconds (0: none): a drop still running after it stops after
    // its current step and counts as too slow. A pile that costs seconds per step is a finding
    // of its own, and would otherwise hold a soak of thousands of drops up for hours. Whether a
    // drop hits it depends on the machine, so runs that must replay exactly turn it off.
    Real wallBudget = 0;
};

// An explosion: at some step, the kinetic energy exceeded kExplosionRatio times what the start
// and gravity could have supplied so far (see DropResult::energyRatio).
inline constexpr Real kExplosionRatio = 10;

struct DropResult {
    std::uint64_t seed = 0;
    std::string figure;   // label and pile size: "humanoid*3"
    int bodies = 0;
    Real timeStep = 0;
    std::vector<std::string> details;  // how the drop was made hostile, for --replay

    // The library refused something the soak made on purpose to be valid: the figure's text or
    // build (rejected), or a call threw (threw). Either ends the drop.
    std::string rejected;
    std::string threw;

    // Figures the world's guard put back (StepReport::restored): a NaN or an explosion inside a
    // step, caught there and undone; the drop goes on, but it counts as one.
    int restored = 0;
    // Figures the world found stuck (StepReport::stuck): still, with a joint open or a contact
    // deep, and so kept awake rather than rested. Not a failure: the world says so.
    int stuck = 0;
    bool nonFinite = false;        // a NaN or an infinity in a body's pose or velocity
    Real nonFiniteTime = 0;        // s, when first seen (the drop stops there)
    // max over steps of KE / (supply + slack), where supply = start KE + the springs' start energy
    // + Σ m·|g|·(start height − lowest height reached so far) per body, slack = total mass·|g|·1
    // unit. Above kExplosionRatio: an explosion.
    Real energyRatio = 0;
    Real peakKinetic = 0;
    Real startJointError = 0;      // as the hostile start left the joints
    Real peakJointError = 0;       // after each step, over the run
    Real endJointError = 0;
    Real peakPenetration = 0;      // after each step, over the run
    Real endPenetration = 0;
    std::optional<Real> restTime;  // s; none when the figures were still moving at the limit
    Real simulated = 0;            // s
    int steps = 0;
    int solverFailures = 0;
    Real wallSeconds = 0;
    Real slowestStep = 0;          // wall seconds of the dearest step
    bool tooSlow = false;          // stopped by SoakInputs::wallBudget

    bool exploded() const { return energyRatio > kExplosionRatio; }
    // Every figure rested, yet with a joint open or a contact deep (beyond World::kStuckJointError
    // or kStuckPenetration): the world should have called such a figure stuck, not resting.
    bool restedOpen() const {
        return restTime && (endJointError > kStuckJointError || endPenetration > kStuckPenetration);
    }
};

DropResult runDrop(const SoakInputs& inputs, std::uint64_t seed);

}  // namespace af::soak
