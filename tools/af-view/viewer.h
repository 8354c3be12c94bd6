#pragma once
// af-view's program state: the console session (the same Session and CommandSystem as
// af-console), the camera, the mouse drag and the panels, and one frame of the window at a time.

#include "console_panel.h"
#include "figure_panel.h"
#include "mouse_drag.h"
#include "orbit_camera.h"
#include "scene_renderer.h"
#include "window.h"

#include "console/command_system.h"
#include "console/session.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace af::view {

// What the viewer starts with (and what Reset runs again).
struct Startup {
    std::vector<std::filesystem::path> roots;
    std::string map, entity, figure;  // at most one of them
    std::string exec;                 // a script of console commands
};

class Viewer {
public:
    // With `panels`, the console panel takes the bottom of the window and the 3D view the rest.
    Viewer(Window& window, Startup startup, bool panels);
    ~Viewer();

    // A new session: the map or spawn asked for, then the script. The number of errors printed.
    std::size_t start();
    // One frame: input, the clock when playing, the 3D view, labels, and the panels when shown.
    void frame();

    // The clock runs while playing (the Play button); Reset keeps it running or paused.
    void setPlaying(bool playing) { playing_ = playing; }
    // The scene as it is now, the body colours the view gives them included.
    render::RenderScene scene() const;
    OrbitCamera& camera();

private:
    void registerViewCommands();  // view_commands.cpp
    bool cvarOn(std::string_view name) const;
    // The viewer's own overlay: figures at rest greyed (view_rest).
    void addViewOverlays(render::RenderScene& scene) const;
    void handleMouse();
    // The left button pressed on the ray: grab the body under it, which the figure panel selects.
    bool press(const Ray& ray);
    // The fly camera's keys (view_fly): WASD, Q and E down and up, Shift faster.
    void handleFlyKeys();
    void advanceClock();
    void drawControls();
    void drawLabels(const render::RenderScene& scene);
    ViewMarks marks() const;
    // The 3D view: the window's width, and its height above the console panel (pixels, from the
    // top, where view and window pixels coincide).
    int viewHeight() const;
    // The ray under window pixel (x, y).
    Ray rayAt(Real x, Real y) const;

    Window& window_;
    Startup startup_;
    ConsolePanel panel_;
    FigurePanel figurePanel_;
    SceneRenderer renderer_;
    std::unique_ptr<console::CommandSystem> console_;
    std::unique_ptr<console::Session> session_;
    std::unique_ptr<MouseDrag> drag_;
    std::optional<OrbitCamera> camera_;  // none until first needed: then framed on the scene
    bool panels_;
    bool playing_ = false;
    double stepDebt_ = 0;    // steps owed to the wall clock while playing
    double lastTime_ = 0;
    bool orbiting_ = false;  // the left button went down on no body
    bool looking_ = false;   // fly mode: the right button went down in the view
};

}  // namespace af::view
