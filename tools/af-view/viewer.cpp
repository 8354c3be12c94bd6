// af-view's frame: the 3D view of the session's world, the mouse (orbit, pan, zoom, drag), the
// clock while playing, and the panels.

#include "viewer.h"

#include "console_screenshot.h"

#include "af/text/resource_index.h"
#include "af/text/strings.h"
#include "text/text_file.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace af::view {

namespace {

constexpr int kMaxStepsPerFrame = 4;  // a slow frame drops time rather than falling further behind
constexpr double kStepsPerSecond = 60;  // Doom's frame; af_timeScale scales each step's length
constexpr double kConsoleHeight = 240;  // framebuffer pixels, at most 40 % of the window

constexpr Real kFlySpeed = 0.75;  // the fly camera's speed: distances to its target per second
constexpr float kFigurePanelWidth = 380;  // points

render::Colour brighter(const render::Colour& c) {
    return {std::min(1.0f, c[0] * 1.35f + 0.1f), std::min(1.0f, c[1] * 1.35f + 0.1f), std::min(1.0f, c[2] * 1.35f + 0.1f)};
}

// The AF entityDef that spawns the .af figure `figure`: the first whose articulatedFigure names it.
std::optional<std::string> entityDefOfFigure(const std::vector<std::filesystem::path>& roots, const std::string& figure) {
    const ResourceIndex index(roots);
    for (const EntityDef& def : index.defs().entityDefs())
        if (equalsIgnoreCase(def.valueOr("articulatedFigure"), figure)) return def.name;
    return std::nullopt;
}

}  // namespace

Viewer::Viewer(Window& window, Startup startup, bool panels) : window_(window), startup_(std::move(startup)), panels_(panels) {}

int Viewer::viewHeight() const {
    const int h = window_.height();
    return panels_ ? std::max(1, h - int(std::min(kConsoleHeight, 0.4 * h))) : h;
}

Viewer::~Viewer() {
    drag_.reset();
    session_.reset();
}

std::size_t Viewer::start() {
    drag_.reset();
    session_.reset();
    // What the console prints goes to the panel and to the terminal (a log of the session, line
    // by line as it happens, also when the terminal is a file).
    console_ = std::make_unique<console::CommandSystem>(console::Output(
        [this](std::string_view line) {
            panel_.info(line);
            std::cout << line << std::endl;
        },
        [this](std::string_view line) {
            panel_.error(line);
            std::cout.flush();
            std::cerr << line << '\n';
        }));
    session_ = std::make_unique<console::Session>(startup_.roots, *console_);
    drag_ = std::make_unique<MouseDrag>(*console_, *session_);
    registerViewCommands();

    std::size_t errors = 0;
    const auto run = [&](const std::string& text, std::string_view source) { errors += console_->execute(text, source).errors; };
    if (!startup_.map.empty()) run("map \"" + startup_.map + "\"", "command line");
    if (!startup_.entity.empty()) run("spawn \"" + startup_.entity + "\"", "command line");
    if (!startup_.figure.empty()) {
        if (const auto def = entityDefOfFigure(startup_.roots, startup_.figure)) run("spawn \"" + *def + "\"", "command line");
        else {
            console_->output().error("af-view: error: no entityDef has \"articulatedFigure\" \"" + startup_.figure + "\"");
            ++errors;
        }
    }
    if (!startup_.exec.empty()) {
        if (const auto text = readWholeFile(startup_.exec)) run(*text, startup_.exec);
        else {
            console_->output().error("af-view: error: cannot read the script '" + startup_.exec + "' given to --exec");
            ++errors;
        }
    }
    return errors;
}

render::RenderScene Viewer::scene() const {
    render::RenderScene scene = console::screenshotScene(*session_, console::showFlags(console_->cvars()));
    // Each figure in the palette from its first body on, so that instances of one figure match.
    const World& world = session_->world();
    std::size_t i = 0;
    for (const FigureId f : world.figureIds())
        for (std::size_t b = 0; b < world.definition(f).bodies.size() && i < scene.bodies.size(); ++b, ++i)
            scene.bodies[i].colour = render::bodyColour(int(b));
    if (const std::optional<Drag>& d = world.drag(); d && drag_->active()) {
        std::size_t first = 0;
        for (const FigureId f : world.figureIds()) {
            if (f == d->body.figure) break;
            first += world.definition(f).bodies.size();
        }
        if (first + std::size_t(d->body.body) < scene.bodies.size()) {
            render::RenderShape& grabbed = scene.bodies[first + std::size_t(d->body.body)];
            grabbed.colour = brighter(*grabbed.colour);
        }
    }
    addViewOverlays(scene);
    return scene;
}

bool Viewer::cvarOn(std::string_view name) const {
    const console::CVar* v = console_->cvars().find(name);
    return v && v->asBool();
}

void Viewer::addViewOverlays(render::RenderScene& scene) const {
    const World& world = session_->world();
    if (cvarOn("view_rest")) {
        // A figure at rest fades toward grey, so that what still moves stands out.
        std::size_t i = 0;
        for (const FigureId f : world.figureIds()) {
            const bool resting = world.figureAtRest(f);
            for (std::size_t b = 0; b < world.definition(f).bodies.size() && i < scene.bodies.size(); ++b, ++i)
                if (resting && scene.bodies[i].colour) {
                    render::Colour& c = *scene.bodies[i].colour;
                    const float grey = (c[0] + c[1] + c[2]) / 3;
                    for (float& channel : c) channel = 0.3f * channel + 0.7f * grey;
                }
        }
    }
}

OrbitCamera& Viewer::camera() {
    if (!camera_) {
        const render::Camera fit = render::fitCamera(scene(), double(window_.width()) / viewHeight());
        camera_.emplace();
        // af-sim's framing is tight for a picture; a window wants room to move the figure in.
        camera_->lookAt(fit.target + 1.15 * (fit.eye - fit.target), fit.target, fit.fovYDegrees);
    }
    return *camera_;
}

Ray Viewer::rayAt(Real x, Real y) const { return camera_->ray(x, y, window_.width(), viewHeight()); }

ViewMarks Viewer::marks() const {
    ViewMarks m;
    const World& world = session_->world();
    const console::CVar* skeleton = console_->cvars().find("view_skeleton");
    if (skeleton && skeleton->asBool())
        for (const FigureId f : world.figureIds()) {
            const Skeleton s = world.skeleton(f);
            // Bones from a root joint are left out: an md5's root is the model's origin (Doom's
            // "origin" joint), which no body drives and which stays where the figure was spawned.
            for (std::size_t j = 0; j < s.size(); ++j)
                if (const int parent = s.parents[j]; parent >= 0 && s.parents[std::size_t(parent)] >= 0)
                    m.skeleton.emplace_back(s.joints[std::size_t(parent)].position, s.joints[j].position);
        }
    if (const auto pull = drag_->pull()) m.dragPull.push_back(*pull);
    return m;
}

void Viewer::handleMouse() {
    const ImGuiIO& io = ImGui::GetIO();
    OrbitCamera& cam = camera();
    const bool fly = cvarOn("view_fly");
    // ImGui's mouse position is in window coordinates; the view is in framebuffer pixels.
    const float sx = io.DisplayFramebufferScale.x, sy = io.DisplayFramebufferScale.y;
    const Real x = io.MousePos.x * sx, y = io.MousePos.y * sy;
    if (!io.WantCaptureMouse) {
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
            orbiting_ = !press(rayAt(x, y));
        }
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Right)) looking_ = fly;
        if (io.MouseWheel != 0) {
            if (fly) cam.fly(0.1 * cam.distance() * io.MouseWheel, 0, 0);
            else cam.zoom(io.MouseWheel);
        }
    }
    if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        if (drag_->active() && (io.MouseDelta.x != 0 || io.MouseDelta.y != 0)) drag_->move(rayAt(x, y));
        else if (orbiting_ && fly) cam.look(io.MouseDelta.x, io.MouseDelta.y);
        else if (orbiting_) cam.rotate(io.MouseDelta.x, io.MouseDelta.y);
    }
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left)) {
        drag_->release();
        orbiting_ = false;
    }
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Right)) looking_ = false;
    if (looking_) cam.look(io.MouseDelta.x, io.MouseDelta.y);
    else if (!io.WantCaptureMouse && (ImGui::IsMouseDown(ImGuiMouseButton_Right) || ImGui::IsMouseDown(ImGuiMouseButton_Middle)))
        cam.pan(io.MouseDelta.x * sx, io.MouseDelta.y * sy, viewHeight());
}

bool Viewer::press(const Ray& ray) {
    if (!drag_->press(scene(), ray, camera().forward())) return false;
    // A body clicked is the figure panel's selection too.
    if (const std::optional<Drag>& d = session_->world().drag())
        figurePanel_.selectBody(session_->entityName(d->body.figure),
                                session_->world().definition(d->body.figure).bodies[std::size_t(d->body.body)].name);
    return true;
}

void Viewer::handleFlyKeys() {
    const ImGuiIO& io = ImGui::GetIO();
    if (!cvarOn("view_fly") || io.WantCaptureKeyboard) return;
    OrbitCamera& cam = camera();
    // Speeds scale with the distance to the target, so a figure and a whole map both fly well.
    const Real speed = kFlySpeed * cam.distance() * io.DeltaTime * (window_.keyDown(Window::kLeftShift) ? 4 : 1);
    const auto axis = [this](int plus, int minus) { return Real(window_.keyDown(plus)) - Real(window_.keyDown(minus)); };
    const Real forward = axis('W', 'S'), right = axis('D', 'A'), up = axis('E', 'Q');
    if (forward != 0 || right != 0 || up != 0) cam.fly(speed * forward, speed * right, speed * up);
}

void Viewer::advanceClock() {
    const double now = window_.time(), elapsed = now - lastTime_;
    lastTime_ = now;
    if (!playing_) return;
    stepDebt_ = std::min(stepDebt_ + elapsed * kStepsPerSecond, double(kMaxStepsPerFrame));
    const int steps = int(std::floor(stepDebt_));
    if (steps == 0) return;
    stepDebt_ -= steps;
    console_->execute("step " + std::to_string(steps), "play");
}

void Viewer::drawControls() {
    ImGui::SetNextWindowPos({8, 8}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("Simulation", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    if (ImGui::Button(playing_ ? "Pause" : "Play")) playing_ = !playing_;
    ImGui::SameLine();
    if (ImGui::Button("Step")) {
        playing_ = false;
        console_->execute("step", "button");
    }
    ImGui::SameLine();
    if (ImGui::Button("Respawn")) console_->execute("respawnRagdolls", "button");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("every ragdoll back at its spawn placement, in its spawn pose");
    ImGui::SameLine();
    if (ImGui::Button("Restart")) start();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("a new session: the map or figure and the script again");
    ImGui::SameLine();
    if (ImGui::Button("Frame")) camera_.reset();
    float scale = float(console_->cvars().find("af_timeScale")->asReal());
    ImGui::SetNextItemWidth(160);
    if (ImGui::SliderFloat("af_timeScale", &scale, 0.05f, 1.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
        console_->execute("set af_timeScale " + std::to_string(scale), "slider");
    // The switches are cvars, so the console and scripts set the same things.
    const auto toggle = [this](const char* label, const char* cvar) {
        bool on = cvarOn(cvar);
        if (ImGui::Checkbox(label, &on)) console_->execute(std::string("set ") + cvar + (on ? " 1" : " 0"), "checkbox");
    };
    toggle("skeleton", "view_skeleton");
    ImGui::SameLine();
    toggle("contacts", "af_showContacts");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("points, normals (red) and the last step's normal impulses (orange)");
    ImGui::SameLine();
    toggle("grey at rest", "view_rest");
    toggle("constraints", "af_showConstraints");
    ImGui::SameLine();
    toggle("limits", "af_showLimits");
    ImGui::SameLine();
    toggle("names", "af_showBodyNames");
    toggle("masses", "af_showMass");
    ImGui::SameLine();
    toggle("total mass", "af_showTotalMass");
    ImGui::SameLine();
    toggle("inertia", "af_showInertia");
    toggle("velocities", "af_showVelocity");
    ImGui::SameLine();
    toggle("trees", "af_showTrees");
    toggle("fly camera", "view_fly");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("WASD, Q/E down/up, Shift faster; hold the right button to look");
    const World& world = session_->world();
    ImGui::Text("t = %.2f s   %s", double(world.time()), world.figureIds().empty() ? "no figures" : world.atRest() ? "at rest" : "moving");
    ImGui::End();
}

void Viewer::drawLabels(const render::RenderScene& scene) {
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float sx = ImGui::GetIO().DisplayFramebufferScale.x, sy = ImGui::GetIO().DisplayFramebufferScale.y;
    for (const render::OverlayLabel& label : scene.overlay.labels) {
        const auto at = camera_->project(label.at, window_.width(), viewHeight());
        if (!at || at->y() > viewHeight()) continue;
        const ImU32 colour = ImGui::GetColorU32(ImVec4(label.colour[0], label.colour[1], label.colour[2], 1));
        draw->AddText({float(at->x()) / sx + 4, float(at->y()) / sy - 14}, colour, label.text.c_str());
    }
}

void Viewer::frame() {
    window_.beginFrame();
    handleMouse();
    handleFlyKeys();
    advanceClock();
    const render::RenderScene now = scene();
    renderer_.draw(now, marks(), camera(), window_.width(), viewHeight(), window_.height() - viewHeight());
    drawLabels(now);
    if (panels_) {
        drawControls();
        const ImGuiIO& io = ImGui::GetIO();
        const float top = float(viewHeight()) / io.DisplayFramebufferScale.y;
        panel_.draw(*console_, *session_, 0, top, io.DisplaySize.x, io.DisplaySize.y - top);
        const float width = std::min(kFigurePanelWidth, io.DisplaySize.x / 2);
        figurePanel_.draw(*console_, *session_, io.DisplaySize.x - width - 8, 8, width, std::max(100.0f, top - 16));
    }
    window_.renderImGui();
}

}  // namespace af::view
