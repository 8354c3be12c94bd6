#pragma once
// The ragdoll console's world: a map (or an infinite floor), the AF entities spawned into it, and
// the commands a modder uses on them, after Doom's (docs/doom-physics.md §5): map, spawn, list,
// step/run/waitRest (a clock that moves only when told, so a script is deterministic), drag,
// bindRagdoll/unbindRagdoll, saveRagdolls/saveSelected, deleteSelected, killRagdolls,
// reloadDecls; and the figure editor's editBody, editConstraint, saveAF, respawnRagdolls. A user of the library's public API like any engine; no terminal code.

#include "console/command_system.h"

#include "af/dynamics/world.h"
#include "af/text/atomic_write.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

namespace af::console {

class Session {
public:
    // Mod folders lowest priority first; registers its commands and cvars into `console`.
    Session(std::vector<std::filesystem::path> roots, CommandSystem& console);
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    const World& world() const;
    // The static world as placed: the map's brushes (world space), or the infinite floor's height.
    const std::vector<Polytope>& statics() const;
    std::optional<Real> floorZ() const;
    // The body names of the entity called `entity` (ignoring case), in body order; none when
    // there is no such entity (tab completion).
    std::vector<std::string> bodyNames(std::string_view entity) const;
    // The name of the entity whose figure is `figure`; empty when none is (a viewer's pick).
    std::string entityName(FigureId figure) const;
    // Every entity's name, in spawn order.
    std::vector<std::string> entityNames() const;
    // The .af decl the entity's figure was built from, edits included; null when there is no such
    // entity. Valid until the next command.
    const DeclAF* decl(std::string_view entity) const;
    // The figure checks (figureWarnings) of the entity's figure, for an editor to show beside the
    // body or constraint each concerns; none when there is no such entity.
    std::vector<FigureWarning> warnings(std::string_view entity) const;
    // Every later write of a map goes through this hook (tests: a save cut short).
    void setWriteFaultHook(WriteFaultHook hook);

    struct State;

private:
    std::unique_ptr<State> state_;
};

}  // namespace af::console
