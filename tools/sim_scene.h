#pragma once
// af-sim's scene: figures spawned from an entityDef or a bare .af decl, dropped above a world
// built from a .map (or an infinite floor), ready to step.

#include "af/dynamics/world.h"
#include "af/figure/figure.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace af::sim {

// Bad input (an unknown entity, a broken .map): the message says what and where.
struct SceneError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct SceneOptions {
    std::string entity = "ragdoll_humanoid";  // an entityDef with an `articulatedFigure`
    std::string figure;                       // or a bare .af decl (with its settings' model)
    std::vector<std::filesystem::path> roots; // lowest priority first
    std::filesystem::path map;                // empty: an infinite floor at z = 0
    int count = 1;                            // figures dropped in a pile
    std::optional<unsigned> seed;             // a small deterministic push per figure
    Real dropHeight = 32;                     // units between the floor and the figure's lowest point
    WorldSettings world;
};

struct Scene {
    World world;
    std::shared_ptr<const Figure> definition;  // built once, in model space
    std::vector<FigureId> figures;              // its instances, in the order dropped
    std::vector<Polytope> statics;  // world space: the map's brushes
    std::optional<Real> floorZ;  // the infinite floor, when there is no map
    std::string description;     // what was loaded, for the summary
    Real lifted = 0;  // units the most lifted figure rose above its drop height to clear the brushes
};

Scene buildScene(const SceneOptions& options);

}  // namespace af::sim
