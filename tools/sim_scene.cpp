#include "sim_scene.h"

#include "af/dynamics/placement.h"
#include "af/geometry/brush.h"
#include "af/text/map_file.h"
#include "af/text/resource_index.h"
#include "figure_report.h"

#include <algorithm>
#include <limits>
#include <numbers>
#include <random>

namespace af::sim {

namespace {

constexpr Real kPileSpacing = 24;  // units between one figure's top and the next one's bottom
constexpr Real kTiltDegrees = 15;  // forward lean at spawn, so that a standing figure falls over

// Every worldspawn brush becomes a static convex shape; a brush that encloses nothing is an error
// that names its place in the file.
void addMapStatics(const std::filesystem::path& path, Scene& scene) {
    const MapParseResult parsed = loadMapFile(path.string());
    if (!parsed.ok()) throw SceneError(parsed.diagnostics.formatAll());
    const MapEntity* world = parsed.map.worldspawn();
    if (!world) throw SceneError(path.string() + ": error: the map has no worldspawn entity");
    for (const MapPrimitive& primitive : world->primitives) {
        const BrushDef3* brush = primitive.brush();
        if (!brush) continue;
        const BrushPolytope solid = polytopeFromBrush(*brush);
        if (!solid.ok())
            throw SceneError(path.string() + ":" + std::to_string(primitive.where.line) + ":" +
                             std::to_string(primitive.where.column) + ": error: " + solid.message);
        scene.world.addStaticBrush(*solid.polytope);
        scene.statics.push_back(*solid.polytope);
    }
    if (scene.statics.empty()) throw SceneError(path.string() + ": error: the worldspawn has no brushes to stand on");
}

// Height of the ground under (x, y): the highest static top there, or the floor.
Real groundHeight(const Scene& scene, Real x, Real y) {
    const std::optional<Real> top = highestTopAt(scene.statics, x, y);
    if (!top && !scene.floorZ) throw SceneError("nothing to drop the figures on at (0, 0): the map has no brush there");
    return std::max(top.value_or(-std::numeric_limits<Real>::infinity()),
                    scene.floorZ.value_or(-std::numeric_limits<Real>::infinity()));
}

// A rigid push: the same linear and angular velocity for every body, about the figure's centre.
void push(World& world, FigureId figure, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> speed(-60, 60), spin(-1.5, 1.5);
    // Drawn one statement at a time, last component first: as arguments of one call the draws
    // would be made in an order the compiler picks (GCC right to left, clang left to right), and
    // a seed would push differently under each. This is GCC's order, which earlier pushes used.
    const Real vy = speed(rng), vx = speed(rng);
    const Real wz = spin(rng), wy = spin(rng), wx = spin(rng);
    const Vec3 v(vx, vy, 0);
    const Vec3 w(wx, wy, wz);
    const int bodies = world.range(figure).bodyCount;
    Vec3 centre = Vec3::Zero();
    Real mass = 0;
    for (int i = 0; i < bodies; ++i) {
        const RigidBody& b = world.body({figure, i});
        centre += b.mass() * b.position;
        mass += b.mass();
    }
    centre /= mass;
    for (int i = 0; i < bodies; ++i) world.setVelocity({figure, i}, v + w.cross(world.body({figure, i}).position - centre), w);
}

// A figure wider than the ground under its centre, or hooked to the world beside a step, would
// start with a body inside a brush: it is lifted clear (placement.h), or refused.
RigidPose clearOfBrushes(const Scene& scene, const Figure& definition, const RigidPose& placement, int figureNumber) {
    if (const std::optional<RigidPose> clear = liftedClear(definition, placement, scene.statics)) return *clear;
    throw SceneError("figure " + std::to_string(figureNumber) + " cannot be placed clear of the map's brushes above (0, 0)");
}

}  // namespace

Scene buildScene(const SceneOptions& options) {
    if (options.count < 1) throw SceneError("--count must be at least 1");
    const ResourceIndex index(options.roots);
    const AFResources resources =
        options.figure.empty() ? index.resolveAFEntity(options.entity) : index.resolveFigure(options.figure);
    if (!resources.ok()) throw SceneError(resources.formatDiagnostics());
    FigureResult built = buildFigure(resources);
    if (!built.ok()) throw SceneError(built.formatDiagnostics());

    Scene scene{World(options.world), std::make_shared<const Figure>(std::move(*built.figure)), {}, {}, {}, {}, 0};
    const Figure& definition = *scene.definition;
    if (options.map.empty()) {
        scene.world.addStaticPlane(Plane{Vec3::UnitZ(), 0});
        scene.floorZ = 0;
    } else {
        addMapStatics(options.map, scene);
    }
    Real bottom = groundHeight(scene, 0, 0) + options.dropHeight;
    for (int i = 0; i < options.count; ++i) {
        RigidPose placement;
        placement.rotation = Eigen::AngleAxis<Real>(i * 0.5 * std::numbers::pi_v<Real>, Vec3::UnitZ()).toRotationMatrix() *
                             rotationFromAngles(kTiltDegrees, 0, 0);
        placement.position.z() = bottom - heightRange(definition, placement).lowest;
        const Real dropZ = placement.position.z();
        placement = clearOfBrushes(scene, definition, placement, i + 1);
        scene.lifted = std::max(scene.lifted, placement.position.z() - dropZ);
        bottom = heightRange(definition, placement).highest + kPileSpacing;
        const FigureId id = scene.world.spawn(scene.definition, placement);
        if (options.seed) push(scene.world, id, *options.seed + static_cast<unsigned>(i));
        scene.figures.push_back(id);
    }
    const std::string what = options.figure.empty() ? "entity " + options.entity : "figure " + options.figure;
    scene.description = what + (options.count > 1 ? " x" + std::to_string(options.count) : "") + " on " +
                        (options.map.empty() ? std::string("an infinite floor") : options.map.string());
    return scene;
}

}  // namespace af::sim
