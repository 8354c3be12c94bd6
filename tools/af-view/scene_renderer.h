#pragma once
// Draws the viewer's 3D view with OpenGL 3.3 core: the statics and the floor (a grid) in neutral
// greys, every body as a lit hull in its colour with its edges outlined, then, over everything,
// the skeleton, the drag's pull and the af_show* overlays (render::Overlay, the same marks
// af-console's screenshot draws). Labels are left to the caller (ImGui draws text).

#include "orbit_camera.h"

#include "render/render.h"

#include <utility>
#include <vector>

namespace af::view {

// What the 3D view shows besides a render::RenderScene.
struct ViewMarks {
    std::vector<std::pair<Vec3, Vec3>> skeleton;  // bone segments, world space
    std::vector<std::pair<Vec3, Vec3>> dragPull;  // grabbed point → cursor target
};

// The sky's colour: what a pixel shows where nothing is drawn.
inline constexpr render::Colour kSkyColour = {0.80f, 0.82f, 0.85f};

class SceneRenderer {
public:
    SceneRenderer();  // needs the current OpenGL context
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    // Draws into the current framebuffer's width × height rectangle whose lower left corner is
    // (0, bottom) in OpenGL's window coordinates, clearing the framebuffer first.
    void draw(const render::RenderScene& scene, const ViewMarks& marks, const OrbitCamera& camera, int width, int height, int bottom = 0);

private:
    void upload(const std::vector<float>& data);

    unsigned litProgram_ = 0, flatProgram_ = 0;
    unsigned litVao_ = 0, flatVao_ = 0, buffer_ = 0;
};

}  // namespace af::view
