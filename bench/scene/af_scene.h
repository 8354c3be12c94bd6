#pragma once
// Our engine on the benchmark scene (docs/bench-scene.md): the ragdolls as af::Figures in SI units,
// dropped on the plane z = 0, and the read-out of their bodies' states for RunMetrics.
//
// Joint mapping (§2 → af, figure.h / joints.h; body1 = the §2 child, body2 = the §2 parent, so
// that limits carried by the parent constrain a shaft carried by the child, as in Doom's files):
//  * fixed → Fixed.
//  * hinge [lo, hi] → Hinge with a V limit of the same interval: the af hinge angle is the
//    right-handed rotation of body1 relative to body2 about the axis, the §2 angle.
//  * universal → Universal as our Cardan cross (FigureConstraint::cardan, joint_cardan.cpp):
//    body1's arm a2, body2's arm a1, kept ⟂ (a1 ⟂ q a2), each §2 angle within its own range.
//  * ball, cone + twist → BallAndSocket with a cone limit (bone axis b on the child within the
//    cone angle of the cone axis c on the parent) and our twist limit (FigureConstraint::
//    twistLimit, not in Doom's decl) of ±twist about the bone: the JSON says "twist_limited": true.

#include "metrics.h"
#include "scene_def.h"

#include "af/dynamics/world.h"
#include "af/figure/figure.h"

#include <string_view>
#include <vector>

namespace benchscene {

inline constexpr double kMetresPerUnit = 0.0254;  // Doom's inch

// WorldSettings in SI: g = 9.81 m/s² down, every length-bearing setting (contact margin and
// slop, restitution threshold, impulse threshold, speed cap) scaled from Doom inches to metres.
af::WorldSettings afWorldSettings(af::SolverKind solver, bool comeToRest);

// One ragdoll placed as §3 says (velocities are not part of a Figure: see buildAfWorld).
af::Figure afRagdoll(const Placement& placement);

// The whole scene: the ground plane, one figure per placement, initial velocities of §3.
af::World buildAfWorld(std::string_view scene, af::SolverKind solver, bool comeToRest, int count = 0);

// Every body's state, ragdoll-major as RunMetrics wants it (out is resized, not reallocated once
// large enough).
void readStates(const af::World& world, std::vector<BodyState>& out);

}  // namespace benchscene
