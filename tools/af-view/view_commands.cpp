// The viewer's console commands: the camera, and a virtual mouse so that a script can drag a
// body exactly as the hand does (window pixels, x right, y down), e.g. for tests and pictures.

#include "viewer.h"

#include "console/cvars.h"

#include <cstdio>

namespace af::view {

namespace {

using console::CommandArgs;
using console::Output;
using Status = console::CommandStatus;

std::string format(const Vec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "(%.3f %.3f %.3f)", v.x(), v.y(), v.z());
    return text;
}

}  // namespace

void Viewer::registerViewCommands() {
    console::CommandSystem& c = *console_;
    c.addCVar(console::boolCVar("view_skeleton", true, "draw the skeleton the bodies drive"));
    c.addCVar(console::boolCVar("view_rest", false, "grey out the figures at rest"));
    c.addCVar(console::boolCVar("view_fly", false,
                                "fly camera: WASD to move, Q and E down and up, Shift faster, mouse look with the right button held; "
                                "0: orbit the target"));
    c.addCommand({"view_camera", "[EX EY EZ TX TY TZ [FOVY]]", "print the camera (eye, target, vertical field of view), or place it", 0, 7,
                  [this](const CommandArgs& a, const Output& out) {
                      if (a.argc() == 1) {
                          OrbitCamera& cam = camera();
                          char fov[32];
                          std::snprintf(fov, sizeof fov, "%.3f", cam.fovYDegrees());
                          out.info("camera eye " + format(cam.eye()) + " target " + format(cam.target()) + " fovY " + fov);
                          return Status::success();
                      }
                      std::vector<Real> v;
                      for (std::size_t i = 1; i < a.argc(); ++i) {
                          const auto x = a.number(i);
                          if (!x) return Status::failure("view_camera: every argument must be a number");
                          v.push_back(*x);
                      }
                      if (v.size() < 6) return Status::failure("usage: view_camera EX EY EZ TX TY TZ [FOVY]");
                      const Vec3 eye(v[0], v[1], v[2]), target(v[3], v[4], v[5]);
                      const Real fov = v.size() == 7 ? v[6] : 30;
                      if ((eye - target).norm() < 1e-6) return Status::failure("view_camera: the eye and the target must differ");
                      if (fov <= 1 || fov >= 170) return Status::failure("view_camera: FOVY must be between 1 and 170 degrees");
                      camera_.emplace();
                      camera_->lookAt(eye, target, fov);
                      return Status::success();
                  },
                  {}});
    c.addCommand({"view_fit", "", "frame every body again", 0, 0,
                  [this](const CommandArgs&, const Output&) {
                      camera_.reset();
                      camera();
                      return Status::success();
                  },
                  {}});
    const auto pixel = [](const CommandArgs& a) -> std::optional<std::pair<Real, Real>> {
        const auto x = a.number(1), y = a.number(2);
        if (!x || !y) return std::nullopt;
        return std::pair{*x, *y};
    };
    c.addCommand({"view_mouseDown", "X Y", "press the left button at window pixel X Y: grab the body under it", 2, 2,
                  [this, pixel](const CommandArgs& a, const Output&) {
                      const auto p = pixel(a);
                      if (!p) return Status::failure("view_mouseDown: X Y must be numbers");
                      camera();
                      if (!press(rayAt(p->first, p->second)))
                          return Status::failure("view_mouseDown: no body under " + a.argv(1) + " " + a.argv(2));
                      return Status::success();
                  },
                  {}});
    c.addCommand({"view_mouseMove", "X Y", "move the mouse to window pixel X Y (drags what is grabbed)", 2, 2,
                  [this, pixel](const CommandArgs& a, const Output&) {
                      const auto p = pixel(a);
                      if (!p) return Status::failure("view_mouseMove: X Y must be numbers");
                      camera();
                      drag_->move(rayAt(p->first, p->second));
                      return Status::success();
                  },
                  {}});
    c.addCommand({"view_mouseUp", "", "release the left button: let go of what is dragged", 0, 0,
                  [this](const CommandArgs&, const Output&) {
                      drag_->release();
                      return Status::success();
                  },
                  {}});
    c.addCommand({"view_dragInfo", "", "print the dragged point, where it is pulled, and how far it has to go", 0, 0,
                  [this](const CommandArgs&, const Output& out) {
                      const auto pull = drag_->pull();
                      if (!pull) return Status::failure("view_dragInfo: nothing is dragged");
                      char distance[32];
                      std::snprintf(distance, sizeof distance, "%.3f", (pull->second - pull->first).norm());
                      out.info("drag point " + format(pull->first) + " target " + format(pull->second) + " distance " + distance);
                      return Status::success();
                  },
                  {}});
    c.addCommand({"view_selection", "", "print what the figure panel has selected: the entity, and a body or constraint", 0, 0,
                  [this](const CommandArgs&, const Output& out) {
                      out.info("selected " + figurePanel_.selection());
                      return Status::success();
                  },
                  {}});
    for (const char* name : {"quit", "exit"})
        c.addCommand({name, "", "close af-view", 0, 0,
                      [this](const CommandArgs&, const Output&) {
                          window_.requestClose();
                          return Status::success();
                      },
                      {}});
}

}  // namespace af::view
