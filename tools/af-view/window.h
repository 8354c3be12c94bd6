#pragma once
// af-view's window: a GLFW window with an OpenGL 3.3 core context and Dear ImGui bound to both.
// One per program; it owns GLFW and ImGui from construction to destruction.

#include <stdexcept>
#include <string>

struct GLFWwindow;

namespace af::view {

class Window {
public:
    // Throws std::runtime_error when there is no display or no OpenGL 3.3 context.
    Window(int width, int height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    bool closeRequested() const;
    void requestClose();
    // Polls events and starts an ImGui frame.
    void beginFrame();
    // Draws ImGui's frame over what was drawn since beginFrame; does not present it.
    void renderImGui();
    void present();

    // The framebuffer's size in pixels (what glViewport and glReadPixels see).
    int width() const;
    int height() const;
    // Whether a key is held: a letter by its capital ('W'), or one of the keys below.
    bool keyDown(int key) const;
    static constexpr int kLeftShift = -1;
    // Seconds since the window was made.
    double time() const;

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace af::view
