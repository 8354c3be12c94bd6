// Drops a ragdoll onto a floor, steps it until it rests, and reads its skeleton back: the smallest
// complete use of the library. Usage: drop_ragdoll MOD_FOLDER [ENTITYDEF]
//
// MOD_FOLDER is laid out like Doom 3's base/: af/*.af, def/*.def, models/**.md5mesh|md5anim.

#include <af/collision/collision_world.h>
#include <af/dynamics/world.h>
#include <af/figure/figure.h>
#include <af/figure/skeleton.h>
#include <af/geometry/math.h>
#include <af/text/resource_index.h>

#include <cstdio>
#include <memory>

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s MOD_FOLDER [ENTITYDEF]\n", argv[0]);
        return 2;
    }
    const std::string entityDef = argc > 2 ? argv[2] : "ragdoll_humanoid";

    // Find the entityDef, its .af decl, its model decl and the model's md5 files, by name.
    const af::ResourceIndex index({argv[1]});
    const af::AFResources found = index.resolveAFEntity(entityDef);
    if (!found.ok()) {
        std::fprintf(stderr, "%s", found.formatDiagnostics().c_str());
        return 1;
    }

    // The figure is built once, in model space, on the model's af_pose skeleton; every instance
    // of it shares that definition.
    af::FigureResult built = af::buildFigure(found);
    if (!built.ok()) {
        std::fprintf(stderr, "%s", built.formatDiagnostics().c_str());
        return 1;
    }
    const auto ragdoll = std::make_shared<const af::Figure>(std::move(*built.figure));

    // A world with a floor at z = 0; Doom's gravity and 60 Hz steps are the defaults. The ragdoll
    // is spawned 40 units up, lying down (pitch, yaw, roll in degrees).
    af::World world;
    world.addStaticPlane(af::Plane{af::Vec3::UnitZ(), 0});
    const af::FigureId id = world.spawn(ragdoll, {af::Vec3(0, 0, 40), af::rotationFromAngles(80, 0, 0)});
    while (!world.atRest() && world.time() < 10) world.step();

    // The bodies drive the skeleton: every joint of the md5 skeleton, in world space.
    const af::Skeleton pose = world.skeleton(id);
    std::printf("%s %s after %.2f s, largest joint error %.1e units\n", entityDef.c_str(),
                world.atRest() ? "at rest" : "still moving", world.time(), world.maxJointError());
    for (std::size_t j = 0; j < pose.size(); ++j) {
        const af::Vec3& p = pose.joints[j].position;
        std::printf("  %-12s %8.2f %8.2f %8.2f\n", pose.names[j].c_str(), p.x(), p.y(), p.z());
    }
    return world.atRest() ? 0 : 1;
}
