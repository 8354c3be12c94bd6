// `screenshot FILE`: every body of the session as a lit hull over its brushes or floor, framed by
// af-sim's camera, with the overlays the af_show* cvars ask for (console_overlays.h), written as a
// PNG through a temporary file renamed into place (a picture cut short never replaces a good one).

#include "console_screenshot.h"

#include "console_overlays.h"

#include <filesystem>
#include <system_error>

namespace af::console {

render::RenderScene screenshotScene(const Session& session, const ShowFlags& flags) {
    const World& world = session.world();
    render::RenderScene scene;
    scene.floorZ = session.floorZ();
    for (const Polytope& p : session.statics()) scene.statics.push_back({p, RigidPose{}, std::nullopt});
    const std::vector<RigidPose> poses = world.bodyPoses();
    for (std::size_t i = 0; i < poses.size(); ++i)
        scene.bodies.push_back({world.collision().bodyShape(static_cast<int>(i)), poses[i], std::nullopt});
    addShowOverlays(scene, world, flags);
    return scene;
}

void addScreenshotCommand(CommandSystem& console, const Session& session) {
    console.addCommand({"screenshot", "FILE", "draw the world into a PNG file, with the overlays of the af_show* cvars", 1, 1,
                        [&console, &session](const CommandArgs& args, const Output& out) {
                            const render::RenderScene scene = screenshotScene(session, showFlags(console.cvars()));
                            const std::filesystem::path target(args.argv(1));
                            std::filesystem::path temporary = target;
                            temporary += ".partial";
                            try {
                                render::writePng(scene, render::fitCamera(scene, 4.0 / 3.0), 1024, 768, temporary.string());
                            } catch (const std::exception& e) {
                                std::error_code ignored;
                                std::filesystem::remove(temporary, ignored);
                                return Status::failure(std::string("screenshot: ") + e.what());
                            }
                            std::error_code ec;
                            std::filesystem::rename(temporary, target, ec);
                            if (ec) {
                                std::filesystem::remove(temporary, ec);
                                return Status::failure("screenshot: cannot write " + target.string());
                            }
                            out.info("screenshot " + target.string());
                            return Status::success();
                        },
                        {}});
}

}  // namespace af::console
