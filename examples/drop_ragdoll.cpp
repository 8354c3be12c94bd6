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

    // The figure is built on the model's af_pose skeleton and placed 40 units up, lying down.
    const af::Skeleton afPose = af::skeletonFromMd5Anim(*found.afPose.anim, 0);
    af::RigidPose placement;
    placement.position = af::Vec3(0, 0, 40);
    placement.rotation = af::rotationFromAngles(80, 0, 0);  // pitch, yaw, roll in degrees
    const af::FigureResult built = af::buildFigure(found.figure->decl, afPose, found.figure->file, placement);
    if (!built.ok()) {
        std::fprintf(stderr, "%s", built.formatDiagnostics().c_str());
        return 1;
    }

    // A world with a floor at z = 0; Doom's gravity and 60 Hz steps are the defaults.
    af::World world;
    world.collision().addPlane(af::Plane{af::Vec3::UnitZ(), 0});
    world.addFigure(*built.figure);
    while (!world.atRest() && world.time() < 10) world.step();

    // The bodies drive the skeleton: every joint of the md5 skeleton, in world space.
    const af::Skeleton pose = af::poseSkeleton(*built.figure, world.bodyPoses());
    std::printf("%s %s after %.2f s, largest joint error %.1e units\n", entityDef.c_str(),
                world.atRest() ? "at rest" : "still moving", world.time(), world.maxJointError());
    for (std::size_t j = 0; j < pose.size(); ++j) {
        const af::Vec3& p = pose.joints[j].position;
        std::printf("  %-12s %8.2f %8.2f %8.2f\n", pose.names[j].c_str(), p.x(), p.y(), p.z());
    }
    return world.atRest() ? 0 : 1;
}
