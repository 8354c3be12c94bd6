#include "af/text/contents.h"

#include "af/text/strings.h"

namespace af {

namespace {

// Doom 3's AF names first, in the order its writer prints them; then the rest of Doom 3's
// contents flags, which later games of the engine family write in .af files too.
constexpr ContentsName kNames[] = {
    {"solid", contents::Solid, true},
    {"body", contents::Body, true},
    {"corpse", contents::Corpse, true},
    {"playerclip", contents::PlayerClip, true},
    {"monsterclip", contents::MonsterClip, true},
    {"opaque", contents::Opaque, false},
    {"water", contents::Water, false},
    {"moveableclip", contents::MoveableClip, false},
    {"ikclip", contents::IkClip, false},
    {"blood", contents::Blood, false},
    {"projectile", contents::Projectile, false},
    {"rendermodel", contents::RenderModel, false},
    {"trigger", contents::Trigger, false},
    {"aas_solid", contents::AasSolid, false},
    {"aas_obstacle", contents::AasObstacle, false},
    {"flashlight_trigger", contents::FlashlightTrigger, false},
};

}  // namespace

std::optional<ContentsMask> contentsBitFromName(std::string_view name) {
    if (equalsIgnoreCase(name, "none")) return ContentsMask{0};
    for (const ContentsName& n : kNames)
        if (equalsIgnoreCase(name, n.name)) return n.bit;
    return std::nullopt;
}

bool isDoom3AfContentsName(std::string_view name) {
    if (equalsIgnoreCase(name, "none")) return true;
    for (const ContentsName& n : kNames)
        if (n.doom3Af && equalsIgnoreCase(name, n.name)) return true;
    return false;
}

std::string contentsToString(ContentsMask mask) {
    std::string out;
    for (const ContentsName& n : kNames) {
        if ((mask & n.bit) == 0) continue;
        if (!out.empty()) out += ", ";
        out += n.name;
    }
    return out.empty() ? std::string("none") : out;
}

std::string contentsToString(ContentsMask mask, const std::vector<std::string>& unknown) {
    std::string out = mask == 0 && !unknown.empty() ? std::string() : contentsToString(mask);
    for (const std::string& name : unknown) {
        if (!out.empty()) out += ", ";
        out += name;
    }
    return out;
}

std::string contentsNameList() {
    std::string out = "none";
    for (const ContentsName& n : kNames) {
        out += ", ";
        out += n.name;
    }
    return out;
}

}  // namespace af
