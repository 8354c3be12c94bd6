// af-view run as a user runs it for a picture: `--exec SCRIPT --screenshot FILE` under xvfb-run.
// The same commands run in-process in a Session tell where the bodies are; the picture must show
// the figure there (projected with the camera the script sets, by the formula of
// tools/af-view/orbit_camera.h written out again here), and a scripted mouse drag must pull the
// grabbed body toward the cursor.

#include "af/text/af_parser.h"
#include "console/command_system.h"
#include "console/session.h"
#include "tool_run.h"

#include <gtest/gtest.h>

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace {

using af::Real;
using af::Vec3;

constexpr int kWidth = 640, kHeight = 480;

using af::test::readAll;
using af::test::scratchDir;

bool onPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "");
    for (std::string dir; std::getline(dirs, dir, ':');)
        if (!dir.empty() && access((std::filesystem::path(dir) / program).c_str(), X_OK) == 0) return true;
    return false;
}

struct ViewRun {
    int status = -1;
    std::string out, err;
    std::filesystem::path picture;
};

// af-view --exec (the script) --screenshot, in a virtual X server of its own; `options` are more
// of af-view's options (--panels).
ViewRun afView(const std::string& script, const std::string& options = "") {
    const std::filesystem::path dir = scratchDir();
    std::ofstream(dir / "script.cfg") << script;
    ViewRun run;
    run.picture = dir / "view.png";
    // xvfb-run -a takes the first free display from -n on; starting each test from a number of its
    // own keeps tests run side by side (ctest -j) from racing for the same one.
    // Under AddressSanitizer (CI's clang build) leak checking is off for af-view alone: GLFW's
    // glfwTerminate unloads the X and Mesa libraries it opened, and what they still held is then
    // reported as leaked from an "<unknown module>", which no suppression can name (a window
    // program that skips glfwTerminate reports nothing). Memory errors are still caught.
    const std::string server = "xvfb-run -a -n " + std::to_string(100 + getpid() % 30000) + " -s '-screen 0 1024x768x24' ";
    const std::string command = "ASAN_OPTIONS=\"${ASAN_OPTIONS:-}:detect_leaks=0\" " + server + AF_VIEW_PATH + " --root '" + AF_SOURCE_DIR +
                                "' --exec '" + (dir / "script.cfg").string() + "' --screenshot '" + run.picture.string() +
                                "' --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight) + " " + options + " > '" + (dir / "out").string() +
                                "' 2> '" + (dir / "err").string() + "'";
    const int status = std::system(command.c_str());
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.out = readAll(dir / "out");
    run.err = readAll(dir / "err");
    return run;
}

// The same commands in-process, for the bodies' poses (the clock only moves when told, so the
// two runs step the same world).
struct Bodies {
    std::vector<std::string> names;
    std::vector<Vec3> centres;
    std::vector<Vec3> contacts;  // the last step's contact points
};
Bodies bodiesAfter(const std::string& script) {
    af::console::CommandSystem console;
    af::console::Session session({AF_SOURCE_DIR}, console);
    EXPECT_TRUE(console.execute(script).ok());
    Bodies b;
    for (const af::FigureId f : session.world().figureIds())
        for (const auto& body : session.world().definition(f).bodies) b.names.push_back(body.name);
    for (const af::RigidPose& p : session.world().bodyPoses()) b.centres.push_back(p.position);
    for (const af::BodyContact& c : session.world().contacts())
        for (int k = 0; k < c.manifold.count; ++k) b.contacts.push_back(c.manifold.points[std::size_t(k)].point);
    return b;
}

// A perspective camera from eye to target, world +Z up on screen, as orbit_camera.h states it.
struct Camera {
    Vec3 eye, target;
    Real fovY = 30;
    // In a view `height` pixels high (less than the window's with --panels).
    Eigen::Vector2d project(const Vec3& p, int height = kHeight) const {
        const Vec3 forward = (target - eye).normalized(), right = forward.cross(Vec3::UnitZ()).normalized(), up = right.cross(forward);
        const Vec3 d = p - eye;
        const Real f = 1 / std::tan(fovY * std::numbers::pi / 360), aspect = Real(kWidth) / height;
        return {kWidth / 2.0 * (1 + f / aspect * d.dot(right) / d.dot(forward)), height / 2.0 * (1 - f * d.dot(up) / d.dot(forward))};
    }
    std::string command() const {
        std::ostringstream s;
        s << "view_camera " << eye.x() << ' ' << eye.y() << ' ' << eye.z() << ' ' << target.x() << ' ' << target.y() << ' ' << target.z()
          << ' ' << fovY << '\n';
        return s.str();
    }
};

class Picture {
public:
    explicit Picture(const std::filesystem::path& path) : surface_(cairo_image_surface_create_from_png(path.c_str())) {}
    ~Picture() { cairo_surface_destroy(surface_); }
    bool ok() const { return cairo_surface_status(surface_) == CAIRO_STATUS_SUCCESS; }
    int width() const { return cairo_image_surface_get_width(surface_); }
    int height() const { return cairo_image_surface_get_height(surface_); }
    // How coloured pixel (x, y) is: (max − min) / max of its channels; the sky, floor, grid,
    // brushes, edges and skeleton are greys (below 0.2), the bodies' palette is not (0.45 up).
    double saturation(int x, int y) const {
        const unsigned char* row = cairo_image_surface_get_data(surface_) + std::size_t(y) * std::size_t(cairo_image_surface_get_stride(surface_));
        const std::uint32_t p = reinterpret_cast<const std::uint32_t*>(row)[x];
        const int r = (p >> 16) & 255, g = (p >> 8) & 255, b = p & 255;
        const int hi = std::max({r, g, b}), lo = std::min({r, g, b});
        return hi == 0 ? 0 : double(hi - lo) / hi;
    }
    // The contact overlay's red (af_showContacts: points and normals), which no body, brush or other mark is.
    bool contactRedAt(int x, int y) const {
        if (x < 0 || y < 0 || x >= width() || y >= height()) return false;
        const std::uint32_t p = reinterpret_cast<const std::uint32_t*>(cairo_image_surface_get_data(surface_) +
                                                                        std::size_t(y) * std::size_t(cairo_image_surface_get_stride(surface_)))[x];
        return ((p >> 16) & 255) > 200 && ((p >> 8) & 255) < 60 && (p & 255) < 60;
    }
    bool figureAt(int x, int y) const { return x >= 0 && y >= 0 && x < width() && y < height() && saturation(x, y) > 0.3; }
    // Body colour within `r` pixels of (x, y).
    bool figureNear(const Eigen::Vector2d& p, int r) const {
        for (int dy = -r; dy <= r; ++dy)
            for (int dx = -r; dx <= r; ++dx)
                if (figureAt(int(p.x()) + dx, int(p.y()) + dy)) return true;
        return false;
    }

private:
    cairo_surface_t* surface_;
};

#define SKIP_WITHOUT_XVFB()                                                                     \
    if (!onPath("xvfb-run")) GTEST_SKIP() << "xvfb-run is not installed (Debian: xvfb xauth): af-view's tests need a virtual X server"

// Runs af-view on `script` into `run`, or skips the test when the virtual X server cannot start
// here (a sandbox without the sockets it needs): that says nothing about the viewer.
#define RUN_AF_VIEW(run, ...)                                                                              \
    const ViewRun run = afView(__VA_ARGS__);                                                                \
    if (run.err.find("Xvfb failed to start") != std::string::npos) GTEST_SKIP() << "Xvfb does not start here: " << run.err

const Camera kCamera{Vec3(130, -170, 110), Vec3(0, 0, 30), 30};
const std::string kSpawn = "spawn ragdoll_humanoid origin \"0 0 0\"\nrun 0.5\n";
// The skeleton is drawn over the bodies, in white: off, so that each body shows at its centre.
const std::string kNoSkeleton = "view_skeleton 0\n";

TEST(AfView, ScreenshotShowsTheFigureWhereItsBodiesProject) {
    SKIP_WITHOUT_XVFB();
    RUN_AF_VIEW(run, kSpawn + kNoSkeleton + kCamera.command());
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const Picture picture(run.picture);
    ASSERT_TRUE(picture.ok());
    ASSERT_EQ(picture.width(), kWidth);
    ASSERT_EQ(picture.height(), kHeight);

    const Bodies bodies = bodiesAfter(kSpawn);
    ASSERT_EQ(bodies.centres.size(), 16u);
    Eigen::Vector2d lo(kWidth, kHeight), hi(0, 0);
    for (std::size_t i = 0; i < bodies.centres.size(); ++i) {
        const Eigen::Vector2d p = kCamera.project(bodies.centres[i]);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        EXPECT_TRUE(picture.figureNear(p, 1)) << bodies.names[i] << " projects to " << p.transpose() << " but the picture is not figure-coloured there";
    }
    // The figure fills a fair part of the picture, and nothing of it is far from its bodies:
    // beyond 60 pixels around the projected centres the picture is background.
    ASSERT_GT((hi - lo).norm(), 100) << "the camera is too far to tell";
    int far = 0, coloured = 0;
    for (int y = 0; y < kHeight; y += 4)
        for (int x = 0; x < kWidth; x += 4) {
            const bool outside = x < lo.x() - 60 || x > hi.x() + 60 || y < lo.y() - 60 || y > hi.y() + 60;
            if (!outside) continue;
            ++far;
            if (picture.figureAt(x, y)) ++coloured;
        }
    EXPECT_GT(far, 1000);
    EXPECT_EQ(coloured, 0) << "figure-coloured pixels far from every body";
}

TEST(AfView, ContactOverlayMarksWhereTheFeetTouchTheFloor) {
    SKIP_WITHOUT_XVFB();
    RUN_AF_VIEW(run, kSpawn + kNoSkeleton + kCamera.command() + "af_showContacts 1\n");
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const Picture picture(run.picture);
    ASSERT_TRUE(picture.ok());
    const Bodies bodies = bodiesAfter(kSpawn);
    ASSERT_GE(bodies.contacts.size(), 2u) << "the standing figure touches the floor";
    int red = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) red += picture.contactRedAt(x, y);
    for (const Vec3& c : bodies.contacts) {
        const Eigen::Vector2d p = kCamera.project(c);
        bool marked = false;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) marked = marked || picture.contactRedAt(int(p.x()) + dx, int(p.y()) + dy);
        EXPECT_TRUE(marked) << "contact at " << c.transpose() << " (pixel " << p.transpose() << ") is not marked";
    }
    // Dots and short normals: a few pixels around each point, not a red picture.
    EXPECT_LT(red, int(bodies.contacts.size()) * 200);
}

// "drag point (x y z) target (x y z) distance d" as view_dragInfo prints it.
struct DragInfo {
    Vec3 point, target;
    Real distance = 0;
};
std::vector<DragInfo> dragInfos(const std::string& out) {
    static const std::regex line(R"(drag point \(([-\d.]+) ([-\d.]+) ([-\d.]+)\) target \(([-\d.]+) ([-\d.]+) ([-\d.]+)\) distance ([-\d.]+))");
    std::vector<DragInfo> infos;
    for (std::sregex_iterator it(out.begin(), out.end(), line), end; it != end; ++it) {
        const std::smatch& m = *it;
        const auto v = [&](int i) { return std::stod(m[i].str()); };
        infos.push_back({Vec3(v(1), v(2), v(3)), Vec3(v(4), v(5), v(6)), v(7)});
    }
    return infos;
}

TEST(AfView, ScriptedMouseDragPullsTheBodyTowardTheCursor) {
    SKIP_WITHOUT_XVFB();
    const Bodies bodies = bodiesAfter(kSpawn);
    const auto chest = std::find(bodies.names.begin(), bodies.names.end(), "chest") - bodies.names.begin();
    ASSERT_LT(std::size_t(chest), bodies.names.size());
    const Eigen::Vector2d grab = kCamera.project(bodies.centres[std::size_t(chest)]);
    const int x = int(grab.x()), y = int(grab.y());
    // Press on the chest, move the cursor 120 pixels up and 60 to the right, let the world run.
    const std::string script = kSpawn + kCamera.command() + "view_mouseDown " + std::to_string(x) + " " + std::to_string(y) + "\n" +
                               "view_mouseMove " + std::to_string(x + 60) + " " + std::to_string(y - 120) + "\n" +
                               "view_dragInfo\nrun 1\nview_dragInfo\n";
    RUN_AF_VIEW(run, script);
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_NE(run.out.find("dragging ragdoll_humanoid"), std::string::npos) << run.out;
    const std::vector<DragInfo> infos = dragInfos(run.out);
    ASSERT_EQ(infos.size(), 2u) << run.out;
    const DragInfo& before = infos[0];
    const DragInfo& after = infos[1];
    // The target is where the cursor is: on screen 120 pixels above the grab, on the plane
    // through the grabbed point that faces the camera.
    const Eigen::Vector2d targetPixel = kCamera.project(before.target);
    EXPECT_NEAR(targetPixel.x(), x + 60, 1.0);
    EXPECT_NEAR(targetPixel.y(), y - 120, 1.0);
    EXPECT_NEAR((before.target - before.point).dot((kCamera.target - kCamera.eye).normalized()), 0, 0.5);
    EXPECT_GT(before.distance, 20);
    // A second later the grabbed point is most of the way there, and it went up.
    EXPECT_LT(after.distance, 0.2 * before.distance);
    EXPECT_GT(after.point.z(), before.point.z() + 10);
    EXPECT_TRUE(Picture(run.picture).ok());
}

TEST(AfView, PressingOnNothingGrabsNothing) {
    SKIP_WITHOUT_XVFB();
    RUN_AF_VIEW(run, kSpawn + kCamera.command() + "view_mouseDown 5 5\n");
    EXPECT_EQ(run.status, 1) << run.out << run.err;
    EXPECT_NE(run.err.find("view_mouseDown: no body under 5 5"), std::string::npos) << run.err;
}

// The lamp's shade in world space after `script`, run in-process: its vertices and its centre.
struct Shape {
    std::vector<Vec3> vertices;
    Vec3 centre;
};
Shape shadeAfter(const std::string& script) {
    af::console::CommandSystem console;
    af::console::Session session({AF_SOURCE_DIR}, console);
    EXPECT_TRUE(console.execute(script).ok());
    const af::FigureId f = session.world().figureIds().front();
    const af::Figure& figure = session.world().definition(f);
    const int shade = figure.findBody("shade");
    const af::RigidPose pose = session.world().bodyPoses(f)[std::size_t(shade)];
    Shape out{{}, pose.position};
    for (const Vec3& v : figure.bodies[std::size_t(shade)].shape.vertices) out.vertices.push_back(pose.apply(v));
    return out;
}

int colouredPixels(const Picture& p) {
    int n = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) n += p.figureAt(x, y);
    return n;
}

// Looking along +x at the lamp: the shade's rim is as wide on screen as its radius, tilt or none.
const Camera kLampCamera{Vec3(-150, 0, 62), Vec3(9, 0, 60), 30};
const std::string kLamp = "spawn af_lamp origin \"0 0 0\"\n";
const std::string kWideShade = "editBody af_lamp_1 shade model \"cone( ( -16, -16, -5 ), ( 16, 16, 0 ), 12 )\"\n";

// A script doubles the shade's width: the picture shows the shade where only the wide one
// reaches, and saveAF writes the new shape.
TEST(AfView, AShadeMadeWiderByAScriptIsDrawnWiderAndSaved) {
    SKIP_WITHOUT_XVFB();
    const std::filesystem::path saved = scratchDir() / "lamp.af";
    RUN_AF_VIEW(before, kLamp + kNoSkeleton + kLampCamera.command());
    ASSERT_EQ(before.status, 0) << before.out << before.err;
    const Picture narrow(before.picture);  // read before the second run writes the same file
    ASSERT_TRUE(narrow.ok());
    RUN_AF_VIEW(after, kLamp + kNoSkeleton + kLampCamera.command() + kWideShade + "saveAF af_lamp_1 \"" + saved.string() + "\"\n");
    ASSERT_EQ(after.status, 0) << after.out << after.err;
    EXPECT_NE(after.out.find("1 ragdoll respawned"), std::string::npos) << after.out;
    const Picture wide(after.picture);
    ASSERT_TRUE(wide.ok());

    // A point of the wide shade, 85 % of the way from its centre to its rim vertex farthest to the
    // right on screen; the narrow shade's projected corners all lie well left of it.
    const Shape shape = shadeAfter(kLamp + kWideShade), old = shadeAfter(kLamp);
    const Vec3 right = (kLampCamera.target - kLampCamera.eye).cross(Vec3::UnitZ()).normalized();
    Vec3 rim = shape.vertices.front();
    for (const Vec3& v : shape.vertices)
        if ((v - shape.centre).dot(right) > (rim - shape.centre).dot(right)) rim = v;
    const Eigen::Vector2d inWide = kLampCamera.project(shape.centre + 0.85 * (rim - shape.centre));
    double narrowRightmost = 0;
    for (const Vec3& v : old.vertices) narrowRightmost = std::max(narrowRightmost, kLampCamera.project(v).x());
    ASSERT_GT(inWide.x(), narrowRightmost + 10) << "the test's point must be beyond the narrow shade";

    EXPECT_TRUE(wide.figureNear(inWide, 1)) << "the wide shade is drawn at " << inWide.transpose();
    EXPECT_FALSE(narrow.figureNear(inWide, 2)) << "the narrow shade is not drawn at " << inWide.transpose();
    EXPECT_GT(colouredPixels(wide), 2 * colouredPixels(narrow)) << "four times the rim's area, seen from the side: twice the picture's";

    const af::AFParseResult read = af::loadAFFile(saved.string());
    ASSERT_TRUE(read.ok()) << read.diagnostics.formatAll();
    ASSERT_EQ(read.file.decls.size(), 1u);
    const af::AFBody* body = read.file.decls[0].findBody("shade");
    ASSERT_NE(body, nullptr);
    EXPECT_EQ(body->shape.type, af::ShapeType::Cone);
    EXPECT_EQ(body->shape.v1.coordinates, (af::Real3{-16, -16, -5}));
    EXPECT_EQ(body->shape.v2.coordinates, (af::Real3{16, 16, 0}));
}

// A press on a body selects it in the figure panel, which draws its fields (--panels).
TEST(AfView, PressingOnABodySelectsItInTheFigurePanel) {
    SKIP_WITHOUT_XVFB();
    // With the panels the console takes 40 % of the window's height below the 3D view (viewer.cpp).
    const Eigen::Vector2d shade = kLampCamera.project(shadeAfter(kLamp).centre, kHeight - kHeight * 2 / 5);
    RUN_AF_VIEW(run, kLamp + kLampCamera.command() + "view_selection\nview_mouseDown " + std::to_string(int(shade.x())) + " " +
                         std::to_string(int(shade.y())) + "\nview_selection\n",
                "--panels");
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const std::size_t first = run.out.find("selected ");
    ASSERT_NE(first, std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("selected af_lamp_1 body shade"), run.out.rfind("selected ")) << run.out;
    EXPECT_EQ(run.out.find("selected af_lamp_1 body shade"), run.out.find("selected ", first + 1)) << "not before the press: " << run.out;
}

}  // namespace
