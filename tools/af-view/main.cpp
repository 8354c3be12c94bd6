// af-view: a window onto the ragdoll console's world. It shows the map's brushes (or the floor),
// every figure's bodies as lit hulls and the skeletons they drive; the mouse orbits, pans and
// zooms the camera and drags bodies as Doom's g_dragEntity does; panels hold the clock (play,
// pause, step, reset, slow motion) and the console of af-console with its every command and cvar.
//
// With --screenshot FILE it draws one frame after the startup (and the --exec script), writes it
// as a PNG and exits: pictures for bug reports, and how the tests look at the viewer.
//
// Exit status: 0; 1 when a command of the startup or the script failed (the picture is still
// written); 2 for bad usage, no display or no OpenGL 3.3, or a picture that cannot be written.

#include "command_line_usage.h"
#include "framebuffer_png.h"
#include "viewer.h"
#include "window.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <sstream>

namespace {

struct Options {
    af::view::Startup startup;
    std::vector<std::string> roots;
    std::string screenshot;
    std::string size;
    bool panels = false;
};

bool parseSize(const std::string& text, int& width, int& height) {
    char x = 0;
    std::istringstream in(text);
    if (!(in >> width >> x >> height) || x != 'x' || !in.eof() || width < 64 || height < 64 || width > 8192 || height > 8192) return false;
    return true;
}

int run(Options& o) {
    int width = o.screenshot.empty() ? 1280 : 640, height = o.screenshot.empty() ? 800 : 480;
    if (!o.size.empty() && !parseSize(o.size, width, height)) {
        std::cerr << "af-view: error: --size wants WIDTHxHEIGHT, 64 to 8192 pixels each (e.g. 640x480)\n";
        return 2;
    }
    for (const std::string& r : o.roots) o.startup.roots.emplace_back(r);
    if (o.startup.roots.empty()) o.startup.roots.emplace_back(AF_DATA_DIR);

    af::view::Window window(width, height, "af-view");
    af::view::Viewer viewer(window, o.startup, o.screenshot.empty() || o.panels);
    const std::size_t errors = viewer.start();
    if (!o.screenshot.empty()) {
        // ImGui sizes a new panel to its content in its first frame and draws it from the second.
        for (int i = 0; i < (o.panels ? 2 : 1); ++i) viewer.frame();
        af::view::writeFramebufferPng(window.width(), window.height(), o.screenshot);
        std::cout << "screenshot " << o.screenshot << '\n';
        return errors > 0 ? 1 : 0;
    }
    viewer.setPlaying(true);  // a window, like Doom, shows the world running
    while (!window.closeRequested()) {
        viewer.frame();
        window.present();
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"A window onto the ragdoll console's world: look, play, drag bodies with the mouse."};
    app.name("af-view");
    auto* map = app.add_option("map", o.startup.map, "a .map to load (its brushes and AF entities)")->type_name("FILE.map");
    auto* entity = app.add_option("--entity", o.startup.entity, "spawn this AF entityDef")->type_name("NAME")->excludes(map);
    app.add_option("--figure", o.startup.figure, "spawn the entityDef whose articulatedFigure is this .af decl")
        ->type_name("NAME")->excludes(map)->excludes(entity);
    app.add_option("--root", o.roots, "a mod folder laid out like Doom's base/ (repeat: lowest priority first)")->type_name("DIR");
    app.add_option("--exec", o.startup.exec, "run this script's console commands after the startup")->type_name("SCRIPT");
    app.add_option("--screenshot", o.screenshot, "draw one frame, write it as a PNG, and exit")->type_name("FILE.png");
    app.add_option("--size", o.size, "the window's size (default 1280x800; 640x480 with --screenshot)")->type_name("WxH");
    app.add_flag("--panels", o.panels, "with --screenshot: draw the panels too");
    if (const auto exitStatus = af::tools::parseCommandLine(app, argc, argv, "af-view")) return *exitStatus;
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::cerr << "af-view: " << e.what() << '\n';
        return 2;
    }
}
