// af_render as af-sim uses it: PNGs read back with cairo and checked pixel by pixel.

#include "render/projection.h"
#include "render/render.h"

#include "af/geometry/shapes.h"

#include <cairo.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace {

using af::Real;
using af::Vec3;
using namespace af::render;

struct Rgb {
    double r = 0, g = 0, b = 0;
    double luminance() const { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
    double distance(const Rgb& o) const { return std::abs(r - o.r) + std::abs(g - o.g) + std::abs(b - o.b); }
};

struct Image {
    int width = 0, height = 0;
    std::vector<Rgb> pixels;
    const Rgb& at(int x, int y) const { return pixels.at(static_cast<size_t>(y) * width + x); }
};

Image readPng(const std::string& path) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
    EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS) << path;
    Image image;
    if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
        image.width = cairo_image_surface_get_width(s);
        image.height = cairo_image_surface_get_height(s);
        const int stride = cairo_image_surface_get_stride(s);
        const unsigned char* data = cairo_image_surface_get_data(s);
        for (int y = 0; y < image.height; ++y) {
            for (int x = 0; x < image.width; ++x) {
                std::uint32_t p;
                std::memcpy(&p, data + y * stride + 4 * x, 4);
                image.pixels.push_back({((p >> 16) & 255) / 255.0, ((p >> 8) & 255) / 255.0, (p & 255) / 255.0});
            }
        }
    }
    cairo_surface_destroy(s);
    return image;
}

// A PNG path unique to this process (ctest runs tests in parallel), removed at the end of the test.
class TempPng {
public:
    explicit TempPng(const std::string& name)
        : path_(testing::TempDir() + "af_render_" + std::to_string(getpid()) + "_" + name + ".png") {}
    ~TempPng() { std::remove(path_.c_str()); }
    operator const std::string&() const { return path_; }

private:
    std::string path_;
};

RenderShape box(const Vec3& centre, Real half, Colour colour) {
    RenderShape s;
    s.shape = af::makeBox(Vec3::Constant(-half), Vec3::Constant(half));
    s.pose.position = centre;
    s.colour = colour;
    return s;
}

constexpr Colour kRed = {0.9f, 0.1f, 0.1f};
constexpr Colour kBlue = {0.1f, 0.2f, 0.9f};

bool reddish(const Rgb& c) { return c.r > 0.25 && c.g < 0.6 * c.r && c.b < 0.6 * c.r; }
bool bluish(const Rgb& c) { return c.b > 0.25 && c.r < 0.6 * c.b && c.g < 0.7 * c.b; }

// Looks at the origin from the +X side, a little to -Y and above: the view ray through the
// centre of the image enters a cube at the origin through the middle of its +X face.
Camera frontCamera() {
    Camera c;
    c.eye = Vec3(150, -40, 90);
    c.target = Vec3::Zero();
    return c;
}

// A 400 × 300 picture of a scene, read back from its PNG, and the pixel a world point lands on.
struct Picture {
    Picture(const RenderScene& scene, const Camera& camera, const std::string& name)
        : projector(camera, kWidth, kHeight) {
        const TempPng path(name);
        writePng(scene, camera, kWidth, kHeight, path);
        image = readPng(path);
    }
    Rgb of(const Vec3& p) const {
        const auto px = projector.toPixels(projector.toView(p));
        EXPECT_TRUE(px.x() >= 0 && px.x() < kWidth && px.y() >= 0 && px.y() < kHeight) << px.transpose();
        return image.at(std::clamp(static_cast<int>(px.x()), 0, kWidth - 1),
                        std::clamp(static_cast<int>(px.y()), 0, kHeight - 1));
    }

    static constexpr int kWidth = 400, kHeight = 300;
    af::render::detail::Projector projector;
    Image image;
};

// The overlay (af-console's af_show* pictures) is drawn over the bodies where its points
// project, even inside a body, and nowhere else; an empty overlay changes nothing.
TEST(Render, OverlayMarksAreDrawnOverTheBodiesWhereTheirPointsProject) {
    RenderScene scene;
    scene.bodies.push_back(box(Vec3::Zero(), 20, kBlue));
    const Picture plain(scene, frontCamera(), "overlay_none");
    const Vec3 inside(0, 0, 0), arrowFrom(0, 30, 30), arrowTo(0, 60, 30), fanApex(0, -40, 0);
    scene.overlay.dots.push_back({inside, kRed, 4});
    scene.overlay.lines.push_back({arrowFrom, arrowTo, kRed, 4, true});
    scene.overlay.polygons.push_back({{fanApex, fanApex + Vec3(0, -15, 5), fanApex + Vec3(0, -15, -5)}, kRed, 0.3});
    scene.overlay.labels.push_back({Vec3(0, 0, 40), "neck", kRed});
    const Picture marked(scene, frontCamera(), "overlay_marks");
    EXPECT_TRUE(bluish(plain.of(inside)));
    EXPECT_TRUE(reddish(marked.of(inside))) << "the dot shows through the box that holds it";
    EXPECT_TRUE(reddish(marked.of(0.5 * (arrowFrom + arrowTo))));
    EXPECT_FALSE(reddish(plain.of(0.5 * (arrowFrom + arrowTo))));
    EXPECT_GT(marked.of(fanApex + Vec3(0, -10, 0)).distance(plain.of(fanApex + Vec3(0, -10, 0))), 0.05) << "the translucent fan";
    EXPECT_LT(marked.of(fanApex + Vec3(0, -10, 0)).distance(plain.of(fanApex + Vec3(0, -10, 0))), 0.6) << "lets the scene show";
    int changed = 0;
    for (std::size_t i = 0; i < plain.image.pixels.size(); ++i) changed += plain.image.pixels[i].distance(marked.image.pixels[i]) > 0;
    EXPECT_LT(changed, int(plain.image.pixels.size()) / 20) << "the marks change only their own few pixels";
    for (auto [x, y] : {std::pair{0, 0}, {399, 0}, {0, 299}, {399, 299}}) EXPECT_EQ(marked.image.at(x, y).distance(plain.image.at(x, y)), 0);
}

TEST(Render, PngHasTheRequestedSize) {
    RenderScene scene;
    scene.bodies.push_back(box(Vec3::Zero(), 10, kRed));
    const TempPng path("size");
    writePng(scene, fitCamera(scene), 321, 203, path);
    const Image image = readPng(path);
    EXPECT_EQ(image.width, 321);
    EXPECT_EQ(image.height, 203);
}

TEST(Render, BoxInTheCentreColoursTheCentreAndNotTheCorners) {
    RenderScene scene;
    scene.bodies.push_back(box(Vec3::Zero(), 20, kRed));
    const TempPng path("centre");
    writePng(scene, frontCamera(), 400, 300, path);
    const Image image = readPng(path);
    EXPECT_TRUE(reddish(image.at(200, 150)));
    for (auto [x, y] : {std::pair{0, 0}, {399, 0}, {0, 299}, {399, 299}}) {
        EXPECT_FALSE(reddish(image.at(x, y))) << x << "," << y;
        EXPECT_GE(image.at(x, y).luminance(), 0.7) << "background is light";
    }
}

TEST(Render, NearerBoxCoversFartherOneWhereTheyOverlap) {
    // Both boxes sit on the view ray through the image centre; the red one halfway to the eye.
    const Camera camera = frontCamera();
    const RenderShape farBox = box(Vec3::Zero(), 20, kBlue);
    const RenderShape nearBox = box(0.5 * camera.eye, 8, kRed);
    for (bool nearFirst : {true, false}) {
        RenderScene scene;
        scene.bodies = nearFirst ? std::vector{nearBox, farBox} : std::vector{farBox, nearBox};
        const TempPng path("overlap");
        writePng(scene, camera, 400, 300, path);
        const Image image = readPng(path);
        EXPECT_TRUE(reddish(image.at(200, 150))) << "near box listed first: " << nearFirst;
        int blue = 0;
        for (const Rgb& c : image.pixels) blue += bluish(c);
        EXPECT_GT(blue, 1000) << "the far box shows around the near one";
    }
}

TEST(Render, BodyOnAFloorBrushIsNotHiddenByTheBrushWhoseCentreIsNearer) {
    RenderScene scene;
    scene.bodies.push_back(box(Vec3(0, 0, 10), 10, kRed));
    const Camera camera = fitCamera(scene);
    // A 4000-unit brush centred under the eye: its centroid is nearer the eye than the body's,
    // so ordering by centroid distance would paint it over the body.
    RenderShape brush;
    brush.shape = af::makeBox(Vec3(-2000, -2000, -16), Vec3(2000, 2000, 0));
    brush.pose.position = Vec3(camera.eye.x(), camera.eye.y(), 0);
    scene.statics.push_back(brush);
    ASSERT_LT((Vec3(camera.eye.x(), camera.eye.y(), -8) - camera.eye).norm(), (Vec3(0, 0, 10) - camera.eye).norm());
    const TempPng path("brush");
    writePng(scene, camera, 400, 300, path);
    const Image image = readPng(path);
    EXPECT_TRUE(reddish(image.at(200, 150)));
    EXPECT_FALSE(reddish(image.at(200, 295))) << "the brush fills the bottom of the picture";
    EXPECT_LT(image.at(200, 295).distance(image.at(200, 5)), 0.05) << "grey brush, not sky, at top and bottom";
}

// maps/default.map's floor brush (1024 wide, top at z = 0) and its two stacked steps at +X.
std::vector<RenderShape> defaultMapBrushes() {
    std::vector<RenderShape> brushes(3);
    brushes[0].shape = af::makeBox(Vec3(-512, -512, -16), Vec3(512, 512, 0));
    brushes[1].shape = af::makeBox(Vec3(64, -64, 0), Vec3(192, 64, 32));
    brushes[2].shape = af::makeBox(Vec3(128, -64, 32), Vec3(192, 64, 64));
    return brushes;
}

bool staticGrey(const Rgb& c) {
    return c.luminance() < 0.75 && std::max({c.r, c.g, c.b}) - std::min({c.r, c.g, c.b}) < 0.08;
}

TEST(Render, BodyBesideAStepOnAFloorBrushIsInFullViewOfTheFittedCamera) {
    // The default 3/4 view of this body looks at it across the step: fitted to the body alone,
    // the eye lands inside the step brush and the picture is all grey.
    RenderScene scene;
    scene.bodies.push_back(box(Vec3(40, 0, 8), 8, kRed));
    scene.bodies.push_back(box(Vec3(20, 10, 4), 4, kBlue));
    scene.statics = defaultMapBrushes();
    const Picture picture(scene, fitCamera(scene), "step");
    EXPECT_TRUE(reddish(picture.of(Vec3(40, 0, 8))));
    EXPECT_TRUE(bluish(picture.of(Vec3(20, 10, 4))));
    int red = 0, grey = 0;
    for (const Rgb& c : picture.image.pixels) {
        red += reddish(c);
        grey += staticGrey(c);
    }
    EXPECT_GT(red, 0.02 * 400 * 300) << "framed, not lost in the distance";
    EXPECT_GT(grey, 0.2 * 400 * 300) << "the floor brush around the bodies";
}

TEST(Render, FloorBrushUnderTheBodiesIsFramedLikeTheInfiniteFloor) {
    RenderScene onPlane;
    onPlane.bodies.push_back(box(Vec3(0, 0, 8), 8, kRed));
    onPlane.bodies.push_back(box(Vec3(30, -10, 4), 4, kBlue));
    onPlane.floorZ = 0;
    RenderScene onBrush = onPlane;
    onBrush.floorZ.reset();
    onBrush.statics.push_back(defaultMapBrushes().front());
    const Camera a = fitCamera(onPlane), b = fitCamera(onBrush);
    EXPECT_LT((a.eye - b.eye).norm(), 1e-9);
    EXPECT_LT((a.target - b.target).norm(), 1e-9);
}

TEST(Render, BodyAboveAFloorBrushCastsAShadowOnIt) {
    RenderScene scene;
    scene.bodies.push_back(box(Vec3(0, 0, 30), 8, kRed));
    scene.statics.push_back(defaultMapBrushes().front());
    const Picture picture(scene, frontCamera(), "brush_shadow");
    // Neither floor point is behind the box from this eye; only the first is under it.
    const Rgb under = picture.of(Vec3(0, 0, 0)), beside = picture.of(Vec3(0, 40, 0));
    ASSERT_TRUE(staticGrey(beside));
    EXPECT_LT(under.luminance(), beside.luminance() - 0.05);
    EXPECT_LT(under.distance(beside), 0.5) << "darkened floor, not the body";
}

TEST(Render, TopFaceIsShadedDifferentlyFromSideFace) {
    RenderScene scene;
    scene.bodies.push_back(box(Vec3::Zero(), 20, kRed));
    const Picture picture(scene, frontCamera(), "shading");
    const Rgb top = picture.of(Vec3(0, 0, 20)), side = picture.of(Vec3(20, 0, 0));
    ASSERT_TRUE(reddish(top));
    ASSERT_TRUE(reddish(side));
    EXPECT_GT(top.r - side.r, 0.1) << "lit from above, the top is brighter";
}

TEST(Render, ShapeWithZeroAreaFacesStillDraws) {
    RenderScene scene;
    RenderShape flat;
    flat.shape = af::makeBox(Vec3(-20, -20, 0), Vec3(20, 20, 0));
    flat.colour = kRed;
    scene.bodies.push_back(flat);
    const TempPng path("flat");
    writePng(scene, frontCamera(), 400, 300, path);
    EXPECT_TRUE(reddish(readPng(path).at(200, 150)));
}

TEST(Render, BodyWithNonFinitePoseIsLeftOutAndTheRestDrawn) {
    RenderScene scene;
    scene.bodies.push_back(box(Vec3::Zero(), 20, kRed));
    scene.bodies.push_back(box(Vec3(std::nan(""), 0, 0), 20, kBlue));
    scene.floorZ = -20;
    const Camera camera = fitCamera(scene);
    ASSERT_TRUE(camera.eye.allFinite());
    const TempPng path("exploded");
    writePng(scene, camera, 400, 300, path);
    EXPECT_TRUE(reddish(readPng(path).at(200, 150)));
}

TEST(Render, FloorIsDrawnAroundTheBodies) {
    RenderScene scene;
    scene.bodies.push_back(box(Vec3(0, 0, 8), 8, kRed));
    scene.floorZ = 0;
    const Camera camera = fitCamera(scene);
    const TempPng bare("nofloor"), floored("floor");
    writePng(scene, camera, 400, 300, floored);
    scene.floorZ.reset();
    writePng(scene, camera, 400, 300, bare);
    const Image a = readPng(bare), b = readPng(floored);
    const af::render::detail::Projector projector(camera, 400, 300);
    const auto px = projector.toPixels(projector.toView(Vec3(20, 0, 0)));
    const int x = static_cast<int>(px.x()), y = static_cast<int>(px.y());
    EXPECT_GT(a.at(x, y).distance(b.at(x, y)), 0.05) << "the floor beside the box";
    EXPECT_LT(a.at(x, 2).distance(b.at(x, 2)), 1e-9) << "the sky above the floor";
}

TEST(Render, FittedCameraFramesEveryBodyFromAboveFrontRight) {
    RenderScene scene;
    scene.bodies.push_back(box(Vec3(0, 0, 10), 10, kRed));
    scene.bodies.push_back(box(Vec3(60, 30, 10), 10, kRed));
    scene.bodies.push_back(box(Vec3(-40, -20, 50), 5, kRed));
    scene.floorZ = 0;
    const Camera camera = fitCamera(scene, 4.0 / 3.0);
    EXPECT_GT(camera.eye.z(), camera.target.z());
    EXPECT_GT(camera.eye.x(), camera.target.x());
    EXPECT_LT(camera.eye.y(), camera.target.y());
    const af::render::detail::Projector projector(camera, 400, 300);
    Eigen::AlignedBox2d covered;
    for (const RenderShape& b : scene.bodies) {
        for (const Vec3& v : b.shape.vertices) {
            const auto px = projector.toPixels(projector.toView(b.pose.apply(v)));
            EXPECT_TRUE(px.x() >= 0 && px.x() <= 400 && px.y() >= 0 && px.y() <= 300) << px.transpose();
            covered.extend(px);
        }
    }
    EXPECT_GT(std::max(covered.sizes().x() / 400, covered.sizes().y() / 300), 0.5)
        << "framed, not lost in the distance";
}

TEST(Render, ContactSheetHasOneLabelledCellPerFrameThatDiffersWithThePose) {
    std::vector<RenderScene> frames;
    std::vector<std::string> labels;
    const std::vector<Real> heights = {60, 45, 30, 15, 8, 8};  // the last two at rest, same pose
    for (size_t i = 0; i < heights.size(); ++i) {
        RenderScene s;
        s.bodies.push_back(box(Vec3(0, 0, heights[i]), 8, kRed));
        s.floorZ = 0;
        frames.push_back(s);
        labels.push_back("t = " + std::to_string(i) + ".00 s");
    }
    const TempPng path("sheet");
    const int columns = 3;
    writeContactSheet(frames, labels, columns, path);
    const Image image = readPng(path);
    const PixelRect size = contactSheetSize(6, columns);
    ASSERT_EQ(image.width, size.width);
    ASSERT_EQ(image.height, size.height);

    const auto darkPixels = [&](const PixelRect& r, int x0, int x1, int y0, int y1) {
        int n = 0;
        for (int y = r.y + y0; y < r.y + y1; ++y)
            for (int x = r.x + x0; x < r.x + x1; ++x) n += image.at(x, y).luminance() < 0.35;
        return n;
    };
    // How many pixels below the label plate differ between two cells.
    const auto differing = [&](const PixelRect& a, const PixelRect& b) {
        int n = 0;
        for (int y = 40; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x)
                n += image.at(a.x + x, a.y + y).distance(image.at(b.x + x, b.y + y)) > 0.1;
        return n;
    };
    for (int i = 0; i < 6; ++i) {
        const PixelRect cell = contactSheetCell(i, columns);
        EXPECT_GT(darkPixels(cell, 2, 110, 2, 30), 30) << "label text in cell " << i;
        EXPECT_GT(image.at(cell.x - 3, cell.y + 100).luminance(), 0.99) << "white gap left of cell " << i;
        if (i + 1 < 5) {
            EXPECT_GT(differing(cell, contactSheetCell(i + 1, columns)), 200) << "cells " << i << " and " << i + 1;
        }
    }
    EXPECT_EQ(differing(contactSheetCell(4, columns), contactSheetCell(5, columns)), 0)
        << "same pose, same camera: same picture";
}

TEST(Render, ContactSheetRejectsLabelsThatDoNotMatchFrames) {
    EXPECT_THROW(writeContactSheet({RenderScene{}}, {}, 2, TempPng("bad")), std::invalid_argument);
    EXPECT_THROW(writeContactSheet({}, {}, 2, TempPng("bad")), std::invalid_argument);
    EXPECT_THROW(writeContactSheet({RenderScene{}}, {"a"}, 0, TempPng("bad")), std::invalid_argument);
}

PlotData decayingRun(std::optional<double> restTime) {
    PlotData data;
    for (int i = 0; i <= 500; ++i) {
        const double t = 0.01 * i;
        data.time.push_back(t);
        data.kineticEnergy.push_back(t < 4 ? 100 * std::exp(-3 * t) : 0.0);
        data.maxJointError.push_back(0.5 * std::exp(-t) * std::abs(std::sin(5 * t)));
    }
    data.restTime = restTime;
    data.title = "test run";
    return data;
}

// Pixels of the rest marker's colour in each column of the picture.
std::vector<int> markerPixelsPerColumn(const Image& image) {
    const Rgb marker{kRestMarkerColour[0], kRestMarkerColour[1], kRestMarkerColour[2]};
    std::vector<int> count(image.width, 0);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) count[x] += image.at(x, y).distance(marker) < 0.12;
    return count;
}

TEST(Render, PlotMarksTheRestTimeAtItsColumn) {
    for (double rest : {1.0, 3.2}) {
        const PlotData data = decayingRun(rest);
        const TempPng path("plot");
        writePlot(data, path);
        const Image image = readPng(path);
        ASSERT_EQ(image.width, PlotOptions{}.width);
        ASSERT_EQ(image.height, PlotOptions{}.height);
        const std::vector<int> count = markerPixelsPerColumn(image);
        const int column = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
        const double expected = plotTimeAxis(data).pixelX(rest);
        EXPECT_NEAR(column, expected, 1.5) << "rest at " << rest << " s";
        EXPECT_GT(count[column], image.height / 2) << "a line through both panels";
    }
}

TEST(Render, PlotWithoutRestHasNoMarker) {
    const TempPng path("plot_norest");
    writePlot(decayingRun(std::nullopt), path);
    const std::vector<int> count = markerPixelsPerColumn(readPng(path));
    EXPECT_LT(*std::max_element(count.begin(), count.end()), 10);
}

TEST(Render, PlotRejectsMismatchedSeries) {
    PlotData data = decayingRun(1.0);
    data.maxJointError.pop_back();
    EXPECT_THROW(writePlot(data, TempPng("bad")), std::invalid_argument);
    EXPECT_THROW(writePlot(PlotData{}, TempPng("bad")), std::invalid_argument);
}

TEST(Render, WritingIntoAMissingDirectoryThrowsNamingThePath) {
    RenderScene scene;
    scene.bodies.push_back(box(Vec3::Zero(), 10, kRed));
    const std::string path = testing::TempDir() + "no_such_directory_af_render/picture.png";
    const auto expectThrowNamingPath = [&](auto write) {
        try {
            write();
            ADD_FAILURE() << "no exception";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    };
    expectThrowNamingPath([&] { writePng(scene, fitCamera(scene), 64, 48, path); });
    expectThrowNamingPath([&] { writeContactSheet({scene}, {"t = 0 s"}, 1, path); });
    expectThrowNamingPath([&] { writePlot(decayingRun(1.0), path); });
}

TEST(Render, NonPositiveImageSizeIsRejected) {
    EXPECT_THROW(writePng(RenderScene{}, Camera{}, 0, 10, TempPng("bad")), std::invalid_argument);
}

}  // namespace
