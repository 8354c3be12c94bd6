// Saved ragdoll poses as `body` keys of a map entity (docs/formats.md §5.5): the value spelled as
// the game's saveRagdolls spells it, read back strictly, and the keys of a whole figure written
// and read with every problem said.

#include "af/figure/saved_pose.h"
#include "af/text/strings.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace af {

namespace {

// A body's rotation comes from the solver, orthonormal to rounding (about 1e-15); this only
// refuses what is no rotation at all (a zero matrix, a scale, a mirror), which angles would
// silently turn into some other rotation.
constexpr Real kRotationTolerance = 1e-6;

constexpr std::string_view kBodyPrefix = "body ";

// `%.8f`, then trailing zeros and a trailing `.` removed, as idStr::FloatArrayToString does
// with precision 8 (docs/formats.md §5.5). One difference: where the game writes `-0` (a value
// that rounds to zero from below, or the −0 its angle reading gives an unturned body's pitch),
// we write `0`; both read back as zero.
std::string formatEightDecimals(Real v) {
    char buffer[400];  // %.8f of the largest double is 309 digits and 9 more
    const int n = std::snprintf(buffer, sizeof buffer, "%.8f", v);
    std::string text(buffer, static_cast<std::size_t>(n));
    while (!text.empty() && text.back() == '0') text.pop_back();
    if (!text.empty() && text.back() == '.') text.pop_back();
    return text == "-0" ? "0" : text;
}

bool isBlank(char c) { return c == ' ' || c == '\t'; }

// One number as the game's sscanf("%f") takes it, strictly: the whole word, a finite float.
std::optional<Real> parseNumber(std::string_view word, std::string& error) {
    std::string_view digits = word;
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
    float value = 0;
    const auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (status == std::errc::result_out_of_range) {
        error = "`" + std::string(word) + "` is beyond the range of a float";
        return std::nullopt;
    }
    if (status != std::errc() || end != digits.data() + digits.size()) {
        error = "`" + std::string(word) + "` is not a number";
        return std::nullopt;
    }
    if (!std::isfinite(value)) {
        error = "`" + std::string(word) + "` is not a finite number";
        return std::nullopt;
    }
    return static_cast<Real>(value);
}

// Why a body name cannot be part of a map key that reads back as written, or empty when it can
// (docs/formats.md §5.6: strings have no escapes, and the reader strips trailing white space).
std::string keyNameProblem(std::string_view name) {
    if (name.empty()) return "the name is empty";
    for (char c : name) {
        if (c == '"') return "a map key cannot hold a `\"` (the format has no escapes)";
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            return "a map key cannot hold a line break or another control character";
    }
    if (isBlank(name.front()) || isBlank(name.back())) return "white space at either end of a map key is lost on reading";
    return {};
}

bool isFinitePose(const RigidPose& pose) { return pose.position.allFinite() && pose.rotation.allFinite(); }

bool isRotation(const Mat3& r) {
    return (r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff() <= kRotationTolerance && r.determinant() > 0;
}

int findBodyIgnoringCase(const Figure& figure, std::string_view name) {
    for (std::size_t b = 0; b < figure.bodies.size(); ++b)
        if (equalsIgnoreCase(figure.bodies[b].name, name)) return static_cast<int>(b);
    return -1;
}

}  // namespace

std::string formatSavedBodyPose(const RigidPose& pose) {
    const Vec3 angles = anglesFromRotationPrecise(pose.rotation);
    std::string text;
    for (Real v : {pose.position.x(), pose.position.y(), pose.position.z(), angles[0], angles[1], angles[2]}) {
        if (!text.empty()) text += ' ';
        text += formatEightDecimals(v);
    }
    return text;
}

std::optional<RigidPose> parseSavedBodyPose(std::string_view value, std::string* error) {
    std::string problem;
    Real numbers[6] = {};
    std::size_t count = 0;
    std::size_t at = 0;
    while (true) {
        while (at < value.size() && isBlank(value[at])) ++at;
        if (at == value.size()) break;
        std::size_t end = at;
        while (end < value.size() && !isBlank(value[end])) ++end;
        if (count < 6) {
            const std::optional<Real> number = parseNumber(value.substr(at, end - at), problem);
            if (!number) break;
            numbers[count] = *number;
        }
        ++count;
        at = end;
    }
    if (problem.empty() && count != 6)
        problem = "expected six numbers `x y z pitch yaw roll`, found " + std::to_string(count);
    if (!problem.empty()) {
        if (error) *error = std::move(problem);
        return std::nullopt;
    }
    return RigidPose{Vec3(numbers[0], numbers[1], numbers[2]), rotationFromAngles(numbers[3], numbers[4], numbers[5])};
}

SavedPosesWrite writeSavedPoses(MapEntity& entity, const Figure& figure, std::span<const RigidPose> bodyPoses) {
    const std::string figureName = "figure `" + figure.name + "`";
    if (bodyPoses.size() != figure.bodies.size())
        return {"cannot save the poses of " + figureName + ": " + std::to_string(bodyPoses.size()) + " poses for " +
                std::to_string(figure.bodies.size()) + " bodies"};

    // Everything is checked and spelled before the entity changes, so a refusal changes nothing.
    std::vector<MapKeyValue> keys;
    for (std::size_t b = 0; b < figure.bodies.size(); ++b) {
        const std::string& name = figure.bodies[b].name;
        const std::string body = "cannot save body `" + name + "` of " + figureName + ": ";
        if (const std::string problem = keyNameProblem(name); !problem.empty()) return {body + problem};
        for (std::size_t other = 0; other < b; ++other)
            if (equalsIgnoreCase(figure.bodies[other].name, name))
                return {body + "body `" + figure.bodies[other].name + "` would share its key (map keys ignore case)"};
        if (!isFinitePose(bodyPoses[b])) return {body + "its pose is not finite"};
        if (!isRotation(bodyPoses[b].rotation)) return {body + "its rotation matrix is not a rotation"};
        keys.push_back({std::string(kBodyPrefix) + name, formatSavedBodyPose(bodyPoses[b]), {}});
    }

    for (const MapKeyValue& kv : keys) entity.set(kv.key, kv.value);
    // MapKeyValues can set but not remove: keep every other pair, in order, with its position.
    if (entity.keys.contains("origin")) {
        MapKeyValues kept;
        for (const MapKeyValue& kv : entity.keys)
            if (!equalsIgnoreCase(kv.key, "origin")) kept.set(kv.key, kv.value, kv.where);
        entity.keys = std::move(kept);
    }
    return {};
}

SavedPoses readSavedPoses(const MapEntity& entity, const Figure& figure, std::string mapFile) {
    SavedPoses out{std::vector<std::optional<RigidPose>>(figure.bodies.size()), Diagnostics(std::move(mapFile))};
    for (const MapKeyValue& kv : entity.keys) {
        if (kv.key.size() < kBodyPrefix.size() || !equalsIgnoreCase(kv.key.substr(0, kBodyPrefix.size()), kBodyPrefix))
            continue;
        const std::string_view name = std::string_view(kv.key).substr(kBodyPrefix.size());
        const int body = findBodyIgnoringCase(figure, name);
        if (body < 0) {
            // The game warns and goes on (idAF::LoadState); so do we.
            out.diagnostics.warning(kv.where, "key `" + kv.key + "`: figure `" + figure.name + "` has no body `" +
                                                  std::string(name) + "`; the saved pose is ignored");
            continue;
        }
        std::string error;
        if (const std::optional<RigidPose> pose = parseSavedBodyPose(kv.value, &error))
            out.poses[static_cast<std::size_t>(body)] = *pose;
        else
            out.diagnostics.error(kv.where, "key `" + kv.key + "`: " + error);
    }
    return out;
}

}  // namespace af
