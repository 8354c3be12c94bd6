#pragma once
// The figures af-soak drops: those of the mod folders (every figure whose model resolves), with
// hostile mass and spring edits, and chains it writes itself as .af text. Every figure goes
// through the text stage (written, then parsed), so the soak exercises the parser and the figure
// builder on the values it makes up as well as the solver.

#include "soak_random.h"

#include "af/figure/figure.h"
#include "af/text/resource_index.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace af::soak {

// printf into a string, for the soak's notes and table: `pattern` takes up to four doubles.
inline std::string format(const char* pattern, double a, double b = 0, double c = 0, double d = 0) {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, pattern, a, b, c, d);
    return buffer;
}

// A figure of the mod folders, resolved once and shared by every drop (read-only).
struct SampleFigure {
    std::string name;
    std::shared_ptr<const FigureEntry> entry;
    Skeleton afPose;
};

// Every figure of `index` that resolves (its model, mesh and af_pose found), in reading order.
std::vector<SampleFigure> sampleFigures(const ResourceIndex& index);

// A figure made for one drop, or why it could not be made.
struct MadeFigure {
    std::shared_ptr<const Figure> figure;  // null when parsing or building refused it
    std::string label;                     // short: "humanoid", "chain5"
    std::string text;                      // the .af text that was built
    std::string error;                     // the diagnostics when refused
    std::vector<std::string> notes;        // what was made hostile, for --replay
};

// A sample figure with hostile edits drawn from `random`: densities spread up to 1:1000 across
// joints, a random totalMass, springs stiffened up to a million times.
MadeFigure editedSample(const SampleFigure& sample, Random& random);

// A chain of 2 to 8 bodies of random shapes, sizes and densities (up to 1:1000 between
// neighbours), each joined to the one before by a random kind of constraint (ball and socket with
// or without a cone or pyramid limit, universal, hinge with or without a limit, fixed, slider,
// spring with stiffness up to 1e8), sometimes hooked to the world.
MadeFigure generatedChain(Random& random);

}  // namespace af::soak
