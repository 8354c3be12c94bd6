#pragma once
// Ragdoll poses saved in a .map, as the game's `saveRagdolls` writes them (docs/formats.md §5.5):
// one key per body on the figure's map entity,
//
//     "body <bodyName>" "<x> <y> <z> <pitch> <yaw> <roll>"
//
// x y z the body's centre of mass in world space, pitch yaw roll its world orientation in degrees
// (docs/conventions.md §0.2). Spawning a figure builds it and then sets each listed body exactly
// to its saved pose (docs/figures.md §3.9); these functions turn keys into poses and back, and
// leave the building and the setting to the caller.

#include "af/figure/figure.h"
#include "af/geometry/math.h"
#include "af/text/diagnostics.h"
#include "af/text/map_file.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace af {

// The value of a `body` key: the six numbers printed as the game prints them, `%.8f` with
// trailing zeros and then a trailing `.` removed ("0", "-12.5", "0.33333333"; where the game
// would write "-0", for a value that rounds to zero from below, this writes "0"). The angles rebuild the rotation to
// rounding, gimbal lock included (anglesFromRotationPrecise); eight decimals of a degree keep it
// to about 1e-8°.
std::string formatSavedBodyPose(const RigidPose& pose);

// The pose of a `body` key's value: exactly six finite numbers separated by white space, each
// held as the float the game reads (docs/conventions.md §0.2), then widened. Anything else gives
// nothing and, when `error` is given, says what is wrong.
std::optional<RigidPose> parseSavedBodyPose(std::string_view value, std::string* error = nullptr);

struct SavedPosesWrite {
    std::string error;  // empty on success; otherwise the entity was not changed

    bool ok() const { return error.empty(); }
};

// Sets `body <name>` to formatSavedBodyPose(bodyPoses[b]) for every body b of `figure` (a key
// already present keeps its place, in any case of spelling) and removes the `origin` key, as the
// game does: the bodies' world poses stand on their own. `bodyPoses` holds one world pose per
// body, in the figure's body order. Refused, with the entity unchanged: a pose count that is not
// the body count, a pose that is not finite or whose rotation is not one, and a body name that a
// map key cannot carry back unchanged (empty, with a `"`, a line break or another control
// character, or with white space at either end, which the reader strips).
SavedPosesWrite writeSavedPoses(MapEntity& entity, const Figure& figure, std::span<const RigidPose> bodyPoses);

struct SavedPoses {
    std::vector<std::optional<RigidPose>> poses;  // per body of the figure; empty when no key set it
    Diagnostics diagnostics;                       // located at the keys that caused them

    bool ok() const { return !diagnostics.hasErrors(); }
};

// The `body` keys of `entity` (the prefix `body ` and body names compared ignoring case, as the
// map's keys are) read against `figure`. A key naming no body of the figure is a warning, as in
// the game; a malformed value is an error naming the key. Diagnostics carry `mapFile` and the
// key's position where the entity was read from a file. The other keys are still read, but a
// caller applies none of them unless ok(), as a file with an error does not load.
SavedPoses readSavedPoses(const MapEntity& entity, const Figure& figure, std::string mapFile = {});

}  // namespace af
