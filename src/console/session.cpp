// The session's scene (session.h): maps, AF entities and saving their poses. A map's worldspawn
// brushes are the static world (an infinite floor at z = 0 when it has none); every entity whose
// classname is an AF entityDef is spawned at its origin and angles and then posed by its saved
// `body` keys (docs/formats.md §5.5, docs/figures.md §3.9).

#include "console/console_text.h"
#include "console/session_state.h"

#include "af/dynamics/placement.h"
#include "af/figure/saved_pose.h"
#include "af/geometry/brush.h"
#include "af/text/af_writer.h"
#include "af/text/strings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

namespace af::console {

namespace {

constexpr Real kDropHeight = 32;  // units between the ground and a spawn's lowest point, without `origin`

// `count` numbers separated by white space, all finite.
std::optional<std::vector<Real>> numbers(std::string_view text, std::size_t count) {
    std::vector<Real> out;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        if (i == text.size()) break;
        double v = 0;
        const auto [end, ec] = std::from_chars(text.data() + i, text.data() + text.size(), v);
        if (ec != std::errc() || !std::isfinite(v)) return std::nullopt;
        out.push_back(v);
        i = static_cast<std::size_t>(end - text.data());
    }
    if (out.size() != count) return std::nullopt;
    return out;
}

}  // namespace

Session::Session(std::vector<std::filesystem::path> roots, CommandSystem& console) : state_(std::make_unique<State>()) {
    state_->roots = std::move(roots);
    state_->index = std::make_unique<ResourceIndex>(state_->roots);
    state_->resetWorld();
    state_->world.addStaticPlane(Plane{Vec3::UnitZ(), 0});  // until a map is loaded
    state_->floorZ = 0;
    registerSessionCommands(*state_, console);
}

Session::~Session() = default;
const World& Session::world() const { return state_->world; }
const std::vector<Polytope>& Session::statics() const { return state_->statics; }
std::optional<Real> Session::floorZ() const { return state_->floorZ; }
std::string Session::entityName(FigureId figure) const {
    for (const Entity& e : state_->entities)
        if (e.figure == figure) return e.name;
    return {};
}
std::vector<std::string> Session::entityNames() const {
    std::vector<std::string> names;
    for (const Entity& e : state_->entities) names.push_back(e.name);
    return names;
}
const DeclAF* Session::decl(std::string_view entity) const {
    const Entity* e = state_->find(entity);
    return e ? &e->source.decl : nullptr;
}
std::vector<FigureWarning> Session::warnings(std::string_view entity) const {
    const Entity* e = state_->find(entity);
    return e ? figureWarnings(state_->world.definition(e->figure)) : std::vector<FigureWarning>{};
}
std::vector<std::string> Session::bodyNames(std::string_view entity) const {
    std::vector<std::string> names;
    for (const Entity& e : state_->entities)
        if (equalsIgnoreCase(e.name, entity))
            for (const FigureBody& b : state_->world.definition(e.figure).bodies) names.push_back(b.name);
    return names;
}
void Session::setWriteFaultHook(WriteFaultHook hook) { state_->writeHook = std::move(hook); }

void Session::State::resetWorld() {
    world = World(worldSettings);
    statics.clear();
    floorZ.reset();
    entities.clear();
    selected.clear();
}

Entity* Session::State::find(std::string_view name) {
    for (Entity& e : entities)
        if (equalsIgnoreCase(e.name, name)) return &e;
    return nullptr;
}
const Entity* Session::State::find(std::string_view name) const { return const_cast<State*>(this)->find(name); }

Real Session::State::groundHeight(Real x, Real y) const {
    const std::optional<Real> top = highestTopAt(statics, x, y);
    if (top && floorZ) return std::max(*top, *floorZ);
    return top ? *top : floorZ.value_or(0);
}

// Doom names a spawned entity after its class and a number; ours takes the first number free.
std::string Session::State::unusedName(const std::string& entityDef) const {
    for (int n = 1;; ++n) {
        const std::string name = entityDef + "_" + std::to_string(n);
        const bool taken = std::any_of(entities.begin(), entities.end(), [&](const Entity& e) { return equalsIgnoreCase(e.name, name); }) ||
                           (map && map->findEntity(name));
        if (!taken) return name;
    }
}

AFResources Session::State::resources(const std::string& entityDef) const {
    AFResources found = index->resolveAFEntity(entityDef);
    if (found.figure)
        if (const auto edited = editedDecls.find(found.figure->decl.name); edited != editedDecls.end())
            found.figure = std::make_shared<const FigureEntry>(FigureEntry{edited->second, found.figure->file});
    return found;
}

std::shared_ptr<const Figure> Session::State::definition(const std::string& entityDef, std::string& error,
                                                        DeclSource* source) {
    const AFResources found = resources(entityDef);
    if (!found.ok()) {
        error = found.formatDiagnostics();
        if (!error.empty() && error.back() == '\n') error.pop_back();
        return nullptr;
    }
    if (source) *source = {found.figure->decl, found.figure->file, writeDecl(found.figure->decl)};
    // Built once per entityDef and shared by its entities; reloadDecls and edits empty the cache.
    const std::string key = toLower(entityDef);
    if (const auto it = definitions.find(key); it != definitions.end()) return it->second;
    FigureResult built = buildFigure(found);
    if (!built.ok()) {
        error = built.formatDiagnostics();
        if (!error.empty() && error.back() == '\n') error.pop_back();
        return nullptr;
    }
    auto figure = std::make_shared<const Figure>(std::move(*built.figure));
    definitions[key] = figure;
    return figure;
}

std::optional<std::string> Session::State::loadMap(const std::filesystem::path& path, const Output& out) {
    MapParseResult parsed = loadMapFile(path.string());
    if (!parsed.ok()) {
        std::string message = parsed.diagnostics.formatAll();
        if (!message.empty() && message.back() == '\n') message.pop_back();
        return message;
    }
    const MapEntity* worldspawn = parsed.map.worldspawn();
    if (!worldspawn) return path.string() + ": error: the map has no worldspawn entity";
    std::vector<Polytope> brushes;
    for (const MapPrimitive& primitive : worldspawn->primitives) {
        const BrushDef3* brush = primitive.brush();
        if (!brush) continue;
        const BrushPolytope solid = polytopeFromBrush(*brush);
        if (!solid.ok())
            return path.string() + ":" + std::to_string(primitive.where.line) + ":" + std::to_string(primitive.where.column) +
                   ": error: " + solid.message;
        brushes.push_back(*solid.polytope);
    }
    // Everything is checked: from here the old scene goes.
    resetWorld();
    for (const Polytope& p : brushes) world.addStaticBrush(p);
    statics = std::move(brushes);
    if (statics.empty()) {
        world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
        floorZ = 0;
    }
    map = std::move(parsed.map);
    mapPath = path;
    int spawned = 0;
    for (std::size_t i = 1; i < map->entities.size(); ++i) {
        const MapEntity& entity = map->entities[i];
        const std::string classname(entity.value("classname"));
        if (classname.empty() || !index->resolveAFEntity(classname).ok()) continue;
        if (const auto error = spawn(classname, entity.keys, out, &entity)) out.error(*error);
        else ++spawned;
    }
    out.info("map " + path.string() + ": " + std::to_string(statics.size()) + " brushes, " + std::to_string(spawned) +
             " ragdolls");
    return std::nullopt;
}

// Keys as Doom's spawn reads them: origin "x y z", angle (yaw) or angles "pitch yaw roll", name.
std::optional<std::string> Session::State::spawn(const std::string& entityDef, const MapKeyValues& keys, const Output& out,
                                                 const MapEntity* saved) {
    std::string error;
    DeclSource source;
    auto figure = definition(entityDef, error, &source);
    if (!figure) return error;

    RigidPose placement;
    if (const MapKeyValue* angles = keys.find("angles")) {
        const auto v = numbers(angles->value, 3);
        if (!v) return "spawn " + entityDef + ": angles must be three numbers, found '" + angles->value + "'";
        placement.rotation = rotationFromAngles((*v)[0], (*v)[1], (*v)[2]);
    } else if (const MapKeyValue* angle = keys.find("angle")) {
        const auto v = numbers(angle->value, 1);
        if (!v) return "spawn " + entityDef + ": angle must be a number, found '" + angle->value + "'";
        placement.rotation = rotationFromAngles(0, (*v)[0], 0);
    }
    const MapKeyValue* origin = keys.find("origin");
    if (origin) {
        const auto v = numbers(origin->value, 3);
        if (!v) return "spawn " + entityDef + ": origin must be three numbers, found '" + origin->value + "'";
        placement.position = Vec3((*v)[0], (*v)[1], (*v)[2]);
    } else if (!saved) {
        // Dropped above the ground under (0, 0), then lifted clear of any brush it would reach
        // into (a wide figure beside a step), as af-sim drops it (placement.h).
        placement.position.z() = groundHeight(0, 0) + kDropHeight - heightRange(*figure, placement).lowest;
        const std::optional<RigidPose> clear = liftedClear(*figure, placement, statics);
        if (!clear) return "spawn " + entityDef + ": no height above (0, 0) clears the map's brushes; give an origin";
        placement = *clear;
    }
    std::string name(keys.value("name"));
    if (name.empty()) name = unusedName(entityDef);
    else if (find(name)) return "spawn " + entityDef + ": an entity named " + name + " exists";
    // Where the user or the map says is where it goes, as in Doom (whose af_testSolid warns too).
    if (origin && !saved) {
        const Real depth = staticOverlap(*figure, placement, statics);
        if (depth > kStuckPenetration)
            out.info("warning: " + name + " starts " + fixed(depth) +
                     " units inside the map's brushes: the first steps push it out, and may pull its joints open");
    }

    std::optional<std::vector<RigidPose>> poses;
    if (saved) {
        const SavedPoses read = readSavedPoses(*saved, *figure, mapPath.string());
        for (const Diagnostic& d : read.diagnostics.all()) (d.severity == Severity::Error ? out.error(d.format()) : out.info(d.format()));
        if (!read.ok()) return name + ": its saved poses are not read";
        const bool any = std::any_of(read.poses.begin(), read.poses.end(), [](const auto& p) { return p.has_value(); });
        if (any) {
            const Figure placed = placeFigure(*figure, placement);
            poses.emplace();
            for (std::size_t b = 0; b < placed.bodies.size(); ++b) poses->push_back(read.poses[b].value_or(placed.bodies[b].pose));
        }
    }
    const FigureId id = world.spawn(figure, placement);
    if (poses) world.setPose(id, *poses);
    // docs/figures.md §3.9: a map's figure is put to rest and woken unless it has `nodrop`.
    if (saved && keys.value("nodrop") == "1") world.putToRest(id);
    entities.push_back({name, entityDef, id, placement, std::move(source)});
    selected = name;
    if (!saved) out.info("spawned " + name);
    return std::nullopt;
}

void Session::State::remove(const std::string& name) {
    const auto it = std::find_if(entities.begin(), entities.end(), [&](const Entity& e) { return equalsIgnoreCase(e.name, name); });
    if (it == entities.end()) return;
    world.remove(it->figure);
    if (equalsIgnoreCase(selected, name)) selected.clear();
    entities.erase(it);
}

// docs/formats.md §5.5: every body's pose into the map entity of the same name, or a new entity
// `classname` + `name`; the rest of the map as it was read; written through a temporary file.
std::optional<std::string> Session::State::save(const std::filesystem::path& file, bool selectedOnly, const Output& out) {
    const std::filesystem::path target = file.empty() ? mapPath : file;
    if (target.empty()) return "no map is loaded: name the file to write";
    if (selectedOnly && !find(selected)) return "no entity is selected (spawn or drag one)";
    MapFile written = map.value_or(MapFile{});
    if (written.entities.empty()) {
        MapEntity worldspawn;
        worldspawn.set("classname", "worldspawn");
        written.entities.push_back(std::move(worldspawn));
    }
    int saved = 0;
    for (const Entity& e : entities) {
        if (selectedOnly && !equalsIgnoreCase(e.name, selected)) continue;
        if (!world.figureAtRest(e.figure)) out.info("warning: " + e.name + " is not at rest");
        MapEntity* entity = written.findEntity(e.name);
        if (!entity) {
            MapEntity added;
            added.set("classname", e.entityDef);
            added.set("name", e.name);
            written.entities.push_back(std::move(added));
            entity = &written.entities.back();
        }
        const SavedPosesWrite w = writeSavedPoses(*entity, world.definition(e.figure), world.bodyPoses(e.figure));
        if (!w.ok()) return e.name + ": " + w.error;
        ++saved;
    }
    const WriteResult result = writeFileAtomically(target, writeMapFile(written), writeHook);
    if (!result.ok()) return result.error;
    map = std::move(written);
    mapPath = target;
    out.info("saved " + std::to_string(saved) + " ragdoll" + (saved == 1 ? "" : "s") + " to " + target.string());
    return std::nullopt;
}

// Re-reads every decl; an entity whose .af decl now reads differently is spawned anew, where it
// was first spawned, with the new figure. Edits not saved are dropped: the files say again.
void Session::State::reload(const Output& out) {
    index = std::make_unique<ResourceIndex>(roots);
    editedDecls.clear();
    const int respawned = respawn(false, out);
    out.info("reloaded decls: " + std::to_string(respawned) + " ragdoll" + (respawned == 1 ? "" : "s") + " respawned");
}

// Decls that no longer load leave their entities as they are.
int Session::State::respawn(bool all, const Output& out) {
    definitions.clear();
    int respawned = 0;
    for (Entity& e : entities) {
        std::string error;
        DeclSource source;
        auto figure = definition(e.entityDef, error, &source);
        if (!figure) {
            out.error(e.name + ": " + error);
            continue;
        }
        if (!all && source.text == e.source.text) continue;
        world.remove(e.figure);
        e.figure = world.spawn(figure, e.placement);
        e.source = std::move(source);
        ++respawned;
    }
    return respawned;
}

}  // namespace af::console
