#pragma once
// How contacts behave (WorldSettings::contact): bounce, slop and softness of the rows every
// contact point writes (docs/doom-physics.md §4.3, §4.7; the rows are in
// src/dynamics/contact_rows.h).

#include "af/types.h"

namespace af {

struct ContactSettings {
    Real restitutionThreshold = 2;  // units/s of approach below which contacts do not bounce (Doom: 2)
    Real slop = 0.05;               // units of penetration left alone, so resting contacts stay touching
    // Softness of normal and friction rows, relative to the row's own J M⁻¹ Jᵀ (as joints.h):
    // four points under a box are one more than its three contact freedoms, and without some
    // softness that redundancy makes the exact solver's system singular.
    Real relativeCfm = 1e-9;
    bool friction = true;  // false: normal rows only (Doom's af_skipFriction)
};

}  // namespace af
