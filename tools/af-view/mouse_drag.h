#pragma once
// Doom's g_dragEntity with a mouse: press on a body grabs the point under the cursor; moving the
// cursor moves the drag's target to where the cursor's ray meets the plane that faces the camera
// through the grabbed point (as the grab was made); release lets go. It drives the console's
// `drag` command, so a drag made with the mouse is the drag a script makes, and prints as one.

#include "orbit_camera.h"

#include "console/command_system.h"
#include "console/session.h"
#include "render/render.h"

#include <optional>
#include <string>

namespace af::view {

class MouseDrag {
public:
    MouseDrag(console::CommandSystem& console, const console::Session& session) : console_(console), session_(session) {}

    // Grabs the body `ray` hits first among `scene`'s (the world's bodies in order); false, and
    // nothing changes, when it hits none. `viewForward` is the camera's direction.
    bool press(const render::RenderScene& scene, const Ray& ray, const Vec3& viewForward);
    // Moves the target under the cursor; nothing when no body is grabbed or the ray runs
    // parallel to the plane or away from it.
    void move(const Ray& ray);
    void release();

    bool active() const { return grab_.has_value(); }
    // The grabbed point where its body carries it now, and the target; none when not dragging.
    std::optional<std::pair<Vec3, Vec3>> pull() const;

private:
    struct Grab {
        std::string entity, body;
        Vec3 planePoint, planeNormal;
        Vec3 target;
    };

    console::CommandSystem& console_;
    const console::Session& session_;
    std::optional<Grab> grab_;
};

}  // namespace af::view
