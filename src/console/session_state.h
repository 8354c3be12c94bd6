#pragma once
// Session's state, shared by session.cpp (the scene: maps, entities, saving) and
// session_commands.cpp (the commands that drive it).

#include "console/session.h"
#include "console/session_show.h"

#include "af/figure/figure.h"
#include "af/text/map_file.h"
#include "af/text/resource_index.h"

#include <map>
#include <optional>
#include <string>

namespace af::console {

// The .af decl an entity was built from: as read, or as edited (session_edit.cpp).
struct DeclSource {
    DeclAF decl;
    std::string file;  // the .af file it was read from (saveAF writes there)
    std::string text;  // as the canonical writer spells it, to see edits
};

// An AF entity: a figure instance with the name and keys it was spawned with.
struct Entity {
    std::string name;
    std::string entityDef;
    FigureId figure;
    RigidPose placement;  // where it was spawned (reloadDecls and edits respawn it there)
    DeclSource source;
};

struct Session::State {
    std::vector<std::filesystem::path> roots;
    std::unique_ptr<ResourceIndex> index;
    World world;
    WorldSettings worldSettings;  // the simulation cvars' (session_cvars.cpp); every world is built with them
    std::vector<Polytope> statics;  // world space, for placing spawns
    std::optional<Real> floorZ;     // the infinite floor, when the map has no brushes
    std::optional<MapFile> map;
    std::filesystem::path mapPath;
    std::vector<Entity> entities;
    std::string selected;  // the entity last spawned or dragged (saveSelected, deleteSelected)
    std::map<std::string, std::shared_ptr<const Figure>> definitions;  // by entityDef, lower case
    // Decls edited by editBody/editConstraint and not yet re-read, by decl name: they stand in for
    // the files' decls until reloadDecls (docs/console-editing.md).
    std::map<std::string, DeclAF> editedDecls;
    WriteFaultHook writeHook;
    Real dragDamping = 0.5;
    ShowReport show;  // the af_show* cvars: steps are timed and described through it

    // Each returns an error message, or nothing when it worked.
    std::optional<std::string> loadMap(const std::filesystem::path& path, const Output& out);
    std::optional<std::string> spawn(const std::string& entityDef, const MapKeyValues& keys, const Output& out,
                                     const MapEntity* saved = nullptr);
    std::optional<std::string> save(const std::filesystem::path& file, bool selectedOnly, const Output& out);
    void reload(const Output& out);
    // Respawns, at its spawn placement, every entity whose decl now reads differently (all of
    // them with `all`); the number respawned.
    int respawn(bool all, const Output& out);
    void remove(const std::string& name);

    Entity* find(std::string_view name);
    const Entity* find(std::string_view name) const;
    void resetWorld();
    // The entityDef's resources, an edited decl standing in for the file's.
    AFResources resources(const std::string& entityDef) const;
    std::shared_ptr<const Figure> definition(const std::string& entityDef, std::string& error, DeclSource* source);
    Real groundHeight(Real x, Real y) const;
    std::string unusedName(const std::string& entityDef) const;
};

// Registers the session's commands and cvars (session_commands.cpp), and the simulation cvars
// among them (session_cvars.cpp).
void registerSessionCommands(Session::State& state, CommandSystem& console);
void registerSimulationCvars(Session::State& state, CommandSystem& console);
// editBody, editConstraint, saveAF, respawnRagdolls, checkFigure (session_edit.cpp).
void registerEditCommands(Session::State& state, CommandSystem& console);

}  // namespace af::console
