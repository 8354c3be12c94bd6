#pragma once
// Doom's rest (suspend) test of a whole figure, TestIfAtRest (docs/doom-physics.md §4.11), as a
// runtime object that knows nothing of the World: the caller hands it every body's motion after
// a step, and when it says "at rest" the caller zeroes the velocities and stops solving.
//
// One monitor watches ALL bodies of one figure and answers for all of them: a figure sleeps and
// wakes as a whole, so no limb is left hanging in the air because a neighbour fell asleep, and
// one moving body keeps the whole figure awake (engines that sleep body by body leave limbs
// hanging in the air).
//
// Units: lengths in file units, time in s, angular velocity in rad/s, accelerations in units/s²
// and rad/s², the windowed rotation tolerance in degrees; world frame throughout.

#include "af/geometry/math.h"
#include "af/text/decl_af.h"

#include <span>
#include <vector>

namespace af {

// The thresholds. The defaults are those of Doom's physics object before a decl overrides them
// (docs/doom-physics.md §4.12); a figure from an .af uses restSettingsFrom(decl settings), whose defaults are
// the decl's (20, 30, 40, 60). Doom's constructor takes the linear acceleration constant for the
// angular one; here it is its own constant, 30.
struct RestSettings {
    Real suspendLinearVelocity = 10;       // units/s
    Real suspendAngularVelocity = 15;      // rad/s
    Real suspendLinearAcceleration = 20;   // units/s²
    Real suspendAngularAcceleration = 30;  // rad/s²
    Real noMoveTime = 1;                   // s: length of the movement window
    Real noMoveTranslation = 10;           // units
    Real noMoveRotation = 10;              // degrees
    Real minMoveTime = -1;                 // s awake before any test may pass; <= 0 disables
    Real maxMoveTime = -1;                 // s awake after which the figure rests; <= 0 disables
};

// The .af `settings` block's suspendSpeed, noMove* and min/maxMoveTime, as they are.
RestSettings restSettingsFrom(const AFSettings& settings);

// One body after a step. The accelerations are what the step did to its velocities,
// M⁻¹·F_total with gravity, constraint and contact forces included (Doom's body.acceleration),
// not only the external forces: a body resting on the ground has a small one, a falling body g.
struct BodyMotion {
    Vec3 linearVelocity = Vec3::Zero();       // units/s
    Vec3 angularVelocity = Vec3::Zero();      // rad/s
    Vec3 linearAcceleration = Vec3::Zero();   // units/s²
    Vec3 angularAcceleration = Vec3::Zero();  // rad/s²
    RigidPose pose;                           // body → world
};

class RestMonitor {
public:
    explicit RestMonitor(const RestSettings& settings = {}) : settings_(settings) {}

    // Called once after every step of `dt` seconds with every body of the figure, always in the
    // same order and number; returns whether the figure is (now) at rest. Doom's TestIfAtRest:
    //  1. already at rest: true;
    //  2. the awake time grows by dt; before minMoveTime (if > 0) has passed: false, nothing else
    //     is looked at;
    //  3. past maxMoveTime (if > 0): rest;
    //  4. the movement window: its first step records every pose; once more than noMoveTime has
    //     gone by, the window closes (the next step opens a new one) and the figure rests if no
    //     body moved noMoveTranslation or turned noMoveRotation from its recorded pose;
    //  5. otherwise it rests only if every body is within all four suspend thresholds this step.
    // Contact jitter that makes the speeds flicker over the thresholds cannot keep a figure awake
    // for ever: step 4 looks at positions only. A figure at the top of a ballistic arc has a
    // speed near 0 but the acceleration g, so step 5 keeps it awake.
    //
    // One change to Doom, in step 4: the window takes the largest move from the recorded pose
    // over every step of the window, not only the move between its first and last step. Doom's
    // endpoint test freezes a figure whose motion happens to bring it back after one window, such
    // as a limb swinging with a 1 s period (a pendulum of about 27 units) or a bounce, in
    // mid-air.
    //
    // A step of no time (dt <= 0 or NaN) changes nothing. A speed, acceleration or move that is
    // NaN counts as moving. Throws std::invalid_argument if the number of bodies changes while a
    // window is open (a figure's bodies are fixed; wake() first if they really change).
    // Allocates only when the body count grows.
    bool update(Real dt, std::span<const BodyMotion> bodies);

    // Something moved the figure (an impulse, a force, a drag, a pose change): awake, the awake
    // time back to 0 and the window closed. Doom resets the awake time only when waking a resting
    // figure; here every wake resets it, so a figure pushed or dragged for longer than
    // maxMoveTime is not put to rest under the user's hand only to wake on the next push
    // (a figure put to sleep under a steady force wakes and sleeps again and again, and jitters).
    void wake();

    // Rest at once (Doom's PutToRest: a collision callback, a figure leaving the world).
    void putToRest() { atRest_ = true; }

    bool atRest() const { return atRest_; }
    Real activateTime() const { return activateTime_; }  // s awake since the last wake()
    const RestSettings& settings() const { return settings_; }

private:
    bool windowAllowsRest(Real dt, std::span<const BodyMotion> bodies);
    bool allBelowSuspendThresholds(std::span<const BodyMotion> bodies) const;

    RestSettings settings_;
    bool atRest_ = false;
    Real activateTime_ = 0;
    bool windowOpen_ = false;
    Real windowTime_ = 0;             // Doom's noMoveTime accumulator
    Real windowTranslation_ = 0;      // largest move from the recorded poses so far, units
    Real windowRotation_ = 0;         // largest turn from the recorded poses so far, degrees
    std::vector<RigidPose> recorded_;
};

}  // namespace af
