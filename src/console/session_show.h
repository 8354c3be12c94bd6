#pragma once
// Doom's debug display cvars (docs/doom-physics.md §5.3): af_showBodies, af_showBodyNames,
// af_showMass, af_showTotalMass, af_showInertia, af_showVelocity, af_showConstraints,
// af_showConstraintNames, af_showLimits, af_showTrees, af_showActive, af_highlightBody,
// af_highlightConstraint and af_showTimings; and af_showContacts, which Doom lacks. Our console
// has no frame to draw into, so each prints what it shows after every command that moves the
// clock, and af-console's screenshot draws those that have a picture.

#include "console/command_system.h"
#include "console/session.h"

#include <string>

namespace af::console {

// The cvars' values, read at once.
struct ShowFlags {
    bool bodies = false, bodyNames = false, mass = false, totalMass = false, inertia = false, velocity = false;
    bool constraints = false, constraintNames = false, limits = false, trees = false, contacts = false;
    bool active = false;   // the others only for figures not at rest
    bool timings = false;
    std::string highlightBody, highlightConstraint;  // a body's or a constraint's name, or empty
};

// Registers the cvars, all off and empty.
void addShowCVars(CommandSystem& console);
// Their values in `cvars`; one not registered reads as off.
ShowFlags showFlags(const CVarSystem& cvars);

// What the clock commands (step, run, waitRest) print: they step the world through step(),
// which times each step and keeps the figures the world's guard put back, and call print() when
// done, which names those first.
class ShowReport {
public:
    // Registers the cvars into `console`, where print() reads them.
    void attach(CommandSystem& console);
    void step(World& world);
    // One block per enabled cvar, describing the world as it is now; the timing since the last
    // print (af_showTimings) as one summary line.
    void print(const Session::State& session, const Output& out);

private:
    const CVarSystem* cvars_ = nullptr;
    long steps_ = 0;
    double totalMs_ = 0, longestMs_ = 0;
    struct Restore {
        Real time = 0;
        RestoredFigure figure;
    };
    std::vector<Restore> restored_;
};

}  // namespace af::console
