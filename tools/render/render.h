#pragma once
// Pictures for af-sim: flat-shaded convex bodies over a floor, contact sheets of several frames,
// and plots of a run's energy and joint error, written as PNG files with cairo.
//
// Frame: Doom's world frame, Z up, lengths in file units (a humanoid ragdoll is ~70 units tall).
// Pixels: x to the right, y down, origin at the top-left corner of the image.

#include "af/geometry/math.h"
#include "af/geometry/polytope.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace af::render {

using Colour = std::array<float, 3>;  ///< linear 0..1 red, green, blue

/// One convex shape placed in the world: world point = pose.position + pose.rotation · local point.
struct RenderShape {
    Polytope              shape;   ///< in its own local frame (for a body: the body frame)
    RigidPose             pose;
    std::optional<Colour> colour;  ///< none: a body takes the palette colour of its index, a static grey
};

/// Marks drawn over the shaded scene, never hidden by it (a debug view, as Doom's af_show* lines
/// are): translucent polygons first, then lines, dots and labels, each kind in the order given.
/// World space; widths and radii in pixels of a 480-pixel-high image, scaled with the picture.
struct OverlayPolygon {
    std::vector<Vec3> points;  ///< a planar convex outline
    Colour colour;
    double alpha = 0.3;
};
struct OverlayLine {
    Vec3   from = Vec3::Zero(), to = Vec3::Zero();
    Colour colour;
    double width = 1.5;
    bool   arrow = false;  ///< a head at `to`
};
struct OverlayDot {
    Vec3   at = Vec3::Zero();
    Colour colour;
    double radius = 2.5;
};
struct OverlayLabel {
    Vec3        at = Vec3::Zero();
    std::string text;
    Colour      colour;
};
struct Overlay {
    std::vector<OverlayPolygon> polygons;
    std::vector<OverlayLine>    lines;
    std::vector<OverlayDot>     dots;
    std::vector<OverlayLabel>   labels;
};

/// What one picture shows. The floor, when present, is the infinite plane z = floorZ, drawn as a
/// checkered area around the bodies that fades out with distance.
struct RenderScene {
    std::vector<RenderShape> bodies;
    std::vector<RenderShape> statics;  ///< world brushes: floors, steps, walls
    std::optional<Real>      floorZ;
    Overlay                  overlay;  ///< empty for af-sim's pictures; the camera does not frame it
};

/// A perspective camera whose image "up" is as close to world +Z as the view direction allows.
struct Camera {
    Vec3 eye    = Vec3(100, -100, 80);
    Vec3 target = Vec3::Zero();  ///< the point shown at the centre of the image
    Real fovYDegrees = 30;       ///< vertical field of view
};

/// The palette colour of body `index` (cycles through distinct hues).
Colour bodyColour(int index);

/// A 3/4 view from above that frames every body and a margin around them of the floor and of the
/// statics' faces turned to the camera (only that margin of a brush: a floor brush may be
/// thousands of units wide). The view is from the front-right (Doom's +X is forward, +Y left)
/// unless statics stand between that eye and the bodies (a step next to a lying figure); then it
/// is the first of a fixed list of other directions (left, steeper, far side, from above) whose eye
/// the statics hide the fewest body points from. Without bodies it frames the statics.
/// `aspect` is the image's width / height.
Camera fitCamera(const RenderScene& scene, double aspect = 4.0 / 3.0);

/// One camera framing the bodies of all `frames`, so that motion between them is visible; the
/// statics of every frame count as in fitCamera above.
Camera fitCamera(const std::vector<RenderScene>& frames, double aspect = 4.0 / 3.0);

/// Renders `scene` and writes it as a width × height PNG. Bodies and statics are convex hulls,
/// Lambert-shaded from a fixed light, outlined, drawn back to front with back faces culled.
/// Bodies cast shadows straight down onto the floor and onto the statics' upward faces.
/// Throws std::invalid_argument for a non-positive size, std::runtime_error naming the path
/// when the file cannot be written.
void writePng(const RenderScene& scene, const Camera& camera, int width, int height, const std::string& path);

/// Size of one contact-sheet cell in pixels and the gap between cells and around the sheet.
struct SheetOptions {
    int cellWidth  = 360;
    int cellHeight = 270;
    int gap        = 6;
};

/// A rectangle in pixels.
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

/// Where cell `index` (row-major, `columns` per row) lies on a contact sheet.
PixelRect contactSheetCell(int index, int columns, const SheetOptions& options = {});

/// The whole sheet for `count` cells: x = y = 0, width and height of the image.
PixelRect contactSheetSize(int count, int columns, const SheetOptions& options = {});

/// A grid of small views, one per frame, all with one camera fitted to every frame, each labelled
/// with its entry of `labels` (e.g. "t = 0.50 s") in its top-left corner. Throws
/// std::invalid_argument when frames is empty, labels do not match frames or columns < 1, and
/// std::runtime_error when the file cannot be written.
void writeContactSheet(const std::vector<RenderScene>& frames, const std::vector<std::string>& labels,
                       int columns, const std::string& path, const SheetOptions& options = {});

/// A run's history: one entry per sample in each vector, time in seconds (increasing), kinetic
/// energy in mass units · units² / s², joint error in units.
struct PlotData {
    std::vector<double>   time;
    std::vector<double>   kineticEnergy;
    std::vector<double>   maxJointError;
    std::optional<double> restTime;  ///< when the figure came to rest, if it did
    std::string           title;
};

struct PlotOptions {
    int width  = 900;
    int height = 600;
};

/// The horizontal time axis shared by both panels: pixel columns `left` and `right` show times
/// `tMin` and `tMax`.
struct TimeAxis {
    double left = 0, right = 0;
    double tMin = 0, tMax = 1;
    double pixelX(double t) const { return left + (t - tMin) / (tMax - tMin) * (right - left); }
};

/// The time axis writePlot uses for `data`.
TimeAxis plotTimeAxis(const PlotData& data, const PlotOptions& options = {});

/// Writes two panels over a shared time axis: kinetic energy (log scale) above, max joint error
/// below, each with axis labels and ticks, and a vertical red line at restTime when there is one.
/// Non-positive energies sit on the bottom of the log axis. Throws std::invalid_argument when the
/// vectors are empty or differ in length, std::runtime_error when the file cannot be written.
void writePlot(const PlotData& data, const std::string& path, const PlotOptions& options = {});

/// The colour of the rest marker in writePlot's pictures.
inline constexpr Colour kRestMarkerColour = {0.84f, 0.12f, 0.14f};

}  // namespace af::render
