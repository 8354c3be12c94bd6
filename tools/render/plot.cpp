// Kinetic energy (log scale) above max joint error, over one time axis, with the moment of rest.

#include "cairo_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace af::render {
namespace {

using detail::Align;
using detail::drawText;

constexpr Colour kEnergyColour = {0.16f, 0.40f, 0.72f};
constexpr Colour kErrorColour  = {0.90f, 0.50f, 0.08f};
constexpr Colour kInk          = {0.15f, 0.16f, 0.18f};
constexpr Colour kGrid         = {0.88f, 0.89f, 0.91f};

struct Layout {
    double left, right, top, bottom;  // of the plotting area, both panels together
    double gap;                       // between the two panels
    double font;
    double panelHeight() const { return (bottom - top - gap) / 2; }
};

Layout layout(const PlotData& data, const PlotOptions& o) {
    const double font = std::max(9.0, o.height / 46.0);
    const double top = (data.title.empty() ? 1.6 : 3.2) * font;
    return {7.0 * font, o.width - 2.0 * font, top, o.height - 4.0 * font, 2.2 * font, font};
}

// A step of 1, 2 or 5 times a power of ten giving about `count` intervals over `range`.
double niceStep(double range, int count) {
    const double raw = range / count;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    const double n = raw / magnitude;
    return (n < 1.5 ? 1 : n < 3 ? 2 : n < 7 ? 5 : 10) * magnitude;
}

std::string formatTick(double value, double step) {
    if (std::abs(value) < step * 1e-6) return "0";
    char text[32];
    if (step < 1e-3 || std::abs(value) >= 1e5) {
        std::snprintf(text, sizeof text, "%.3g", value);
    } else {
        const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
        std::snprintf(text, sizeof text, "%.*f", decimals, value);
    }
    return text;
}

// Maps values to pixel rows of one panel, linear or in decades.
struct ValueAxis {
    double top, bottom;  // pixel rows of vMax and vMin
    double vMin, vMax;   // for a log axis, powers of ten
    bool log;
    double step = 0;     // between labelled ticks of a linear axis
    double pixelY(double v) const {
        const double t = log ? (std::log10(std::max(v, std::pow(10.0, vMin))) - vMin) / (vMax - vMin)
                             : (v - vMin) / (vMax - vMin);
        return bottom + std::clamp(t, -0.02, 1.02) * (top - bottom);
    }
};

ValueAxis energyAxis(const std::vector<double>& e, double top, double bottom) {
    double hi = 0, lo = std::numeric_limits<double>::max();
    for (double v : e) {
        if (!std::isfinite(v) || v <= 0) continue;
        hi = std::max(hi, v);
        lo = std::min(lo, v);
    }
    if (hi == 0) return {top, bottom, -6, 0, true};
    const double dMax = std::ceil(std::log10(hi));
    // Eight decades are plenty; below them a resting figure's jitter is noise.
    const double dMin = std::max(std::floor(std::log10(lo)), dMax - 8);
    return {top, bottom, std::min(dMin, dMax - 1), dMax, true};
}

ValueAxis errorAxis(const std::vector<double>& e, double top, double bottom) {
    // Errors below a hundredth of a unit are invisible in any game: the axis does not zoom into
    // solver round-off, so a flat line at zero means a tight figure (the peak label has the number).
    double hi = 0.01;
    for (double v : e)
        if (std::isfinite(v)) hi = std::max(hi, v);
    const double step = niceStep(hi, 4);
    return {top, bottom, 0, std::ceil(hi / step - 1e-9) * step, false, step};
}

void line(cairo_t* cr, double x0, double y0, double x1, double y1) {
    cairo_move_to(cr, x0, y0);
    cairo_line_to(cr, x1, y1);
}

// "10" with a raised exponent, right-aligned at x.
void drawPowerOfTen(cairo_t* cr, int exponent, double x, double y, double font) {
    const std::string exp = std::to_string(exponent);
    detail::useFont(cr, 0.75 * font);
    cairo_text_extents_t e;
    cairo_text_extents(cr, exp.c_str(), &e);
    drawText(cr, exp, x, y - 0.45 * font, Align::Right);
    detail::useFont(cr, font);
    drawText(cr, "10", x - e.x_advance - 1, y, Align::Right);
}

void drawPanel(cairo_t* cr, const Layout& l, const TimeAxis& time, const ValueAxis& axis, const std::string& label,
               bool timeLabels) {
    cairo_rectangle(cr, l.left, axis.top, l.right - l.left, axis.bottom - axis.top);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_fill(cr);

    cairo_set_line_width(cr, 1);
    const double tStep = niceStep(time.tMax - time.tMin, 8);
    detail::useFont(cr, l.font);
    for (double t = std::ceil(time.tMin / tStep) * tStep; t <= time.tMax + 1e-9 * tStep; t += tStep) {
        const double x = std::round(time.pixelX(t)) + 0.5;
        detail::setColour(cr, kGrid);
        line(cr, x, axis.top, x, axis.bottom);
        cairo_stroke(cr);
        detail::setColour(cr, kInk);
        line(cr, x, axis.bottom, x, axis.bottom + 0.4 * l.font);
        cairo_stroke(cr);
        if (timeLabels) drawText(cr, formatTick(t, tStep), x, axis.bottom + 1.5 * l.font, Align::Centre);
    }

    const auto yTick = [&](double v, bool major) {
        const double y = std::round(axis.pixelY(v)) + 0.5;
        detail::setColour(cr, kGrid, major ? 1.0 : 0.5);
        line(cr, l.left, y, l.right, y);
        cairo_stroke(cr);
        detail::setColour(cr, kInk);
        line(cr, l.left - (major ? 0.4 : 0.2) * l.font, y, l.left, y);
        cairo_stroke(cr);
        return y;
    };
    if (axis.log) {
        const int decades = static_cast<int>(axis.vMax - axis.vMin);
        const int every = decades > 6 ? 2 : 1;  // label every other decade when crowded
        for (int d = static_cast<int>(axis.vMin); d <= static_cast<int>(axis.vMax); ++d) {
            const double y = yTick(std::pow(10.0, d), true);
            if ((d - static_cast<int>(axis.vMin)) % every == 0)
                drawPowerOfTen(cr, d, l.left - 0.6 * l.font, y + 0.35 * l.font, l.font);
            if (d < axis.vMax && decades <= 4)
                for (int m = 2; m <= 9; ++m) yTick(m * std::pow(10.0, d), false);
        }
    } else {
        const double step = axis.step;
        detail::useFont(cr, l.font);
        for (double v = axis.vMin; v <= axis.vMax + 1e-9 * step; v += step) {
            const double y = yTick(v, true);
            drawText(cr, formatTick(v, step), l.left - 0.6 * l.font, y + 0.35 * l.font, Align::Right);
        }
    }

    detail::setColour(cr, kInk);
    cairo_rectangle(cr, std::round(l.left) + 0.5, std::round(axis.top) + 0.5, std::round(l.right - l.left),
                    std::round(axis.bottom - axis.top));
    cairo_stroke(cr);

    // The axis label, written upwards along the left edge.
    cairo_save(cr);
    cairo_translate(cr, 1.3 * l.font, 0.5 * (axis.top + axis.bottom));
    cairo_rotate(cr, -std::numbers::pi / 2);
    detail::useFont(cr, l.font);
    drawText(cr, label, 0, 0, Align::Centre);
    cairo_restore(cr);
}

void drawCurve(cairo_t* cr, const Layout& l, const TimeAxis& time, const ValueAxis& axis,
               const std::vector<double>& t, const std::vector<double>& v, const Colour& colour) {
    cairo_save(cr);
    cairo_rectangle(cr, l.left, axis.top, l.right - l.left, axis.bottom - axis.top);
    cairo_clip(cr);
    cairo_new_path(cr);
    bool drawing = false;
    for (size_t i = 0; i < t.size(); ++i) {
        if (!std::isfinite(t[i]) || !std::isfinite(v[i])) {
            drawing = false;  // a gap, not a line through nonsense
            continue;
        }
        const double x = time.pixelX(t[i]), y = axis.pixelY(v[i]);
        drawing ? cairo_line_to(cr, x, y) : cairo_move_to(cr, x, y);
        drawing = true;
    }
    detail::setColour(cr, colour);
    cairo_set_line_width(cr, std::max(1.5, l.font / 7));
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_stroke(cr);
    cairo_restore(cr);
}

std::string format(const char* pattern, double a, double b = 0) {
    char text[96];
    std::snprintf(text, sizeof text, pattern, a, b);
    return text;
}

}  // namespace

TimeAxis plotTimeAxis(const PlotData& data, const PlotOptions& options) {
    const Layout l = layout(data, options);
    TimeAxis axis{l.left, l.right, 0, 1};
    if (!data.time.empty()) {
        axis.tMin = data.time.front();
        axis.tMax = data.time.back() > axis.tMin ? data.time.back() : axis.tMin + 1;
    }
    return axis;
}

void writePlot(const PlotData& data, const std::string& path, const PlotOptions& options) {
    if (data.time.empty()) throw std::invalid_argument("plot: no samples");
    if (data.kineticEnergy.size() != data.time.size() || data.maxJointError.size() != data.time.size()) {
        throw std::invalid_argument("plot: time, kinetic energy and joint error must have the same length");
    }
    detail::Canvas canvas = detail::makeCanvas(options.width, options.height);
    cairo_t* cr = canvas.cr.get();
    const Layout l = layout(data, options);
    const TimeAxis time = plotTimeAxis(data, options);
    cairo_set_source_rgb(cr, 0.97, 0.97, 0.98);
    cairo_paint(cr);

    const ValueAxis energy = energyAxis(data.kineticEnergy, l.top, l.top + l.panelHeight());
    const ValueAxis error = errorAxis(data.maxJointError, l.bottom - l.panelHeight(), l.bottom);
    drawPanel(cr, l, time, energy, "kinetic energy", false);
    drawPanel(cr, l, time, error, "max joint error (units)", true);
    drawCurve(cr, l, time, energy, data.time, data.kineticEnergy, kEnergyColour);
    drawCurve(cr, l, time, error, data.time, data.maxJointError, kErrorColour);

    detail::setColour(cr, kInk);
    detail::useFont(cr, l.font);
    drawText(cr, "time (s)", 0.5 * (l.left + l.right), options.height - 0.8 * l.font, Align::Centre);
    if (!data.title.empty()) {
        detail::useFont(cr, 1.2 * l.font, true);
        drawText(cr, data.title, l.left, 2.0 * l.font);
    }

    // Where the joint error peaked: the number a modder tuning the figure wants.
    size_t peak = 0;
    for (size_t i = 1; i < data.maxJointError.size(); ++i)
        if (data.maxJointError[i] > data.maxJointError[peak]) peak = i;
    detail::useFont(cr, 0.9 * l.font);
    detail::setColour(cr, kErrorColour);
    drawText(cr, format("peak %.3g at t = %.2f s", data.maxJointError[peak], data.time[peak]), l.right - 0.5 * l.font,
             error.top + 1.3 * l.font, Align::Right);

    if (data.restTime && *data.restTime >= time.tMin && *data.restTime <= time.tMax) {
        // Two whole pixel columns either side of round(pixelX(restTime)), so the marker is crisp.
        const double x = std::round(time.pixelX(*data.restTime));
        detail::setColour(cr, kRestMarkerColour);
        cairo_set_line_width(cr, 2);
        line(cr, x, l.top, x, l.bottom);
        cairo_stroke(cr);
        detail::useFont(cr, 0.9 * l.font, true);
        const bool roomOnRight = x + 12 * l.font < l.right;
        drawText(cr, format("at rest, t = %.2f s", *data.restTime), roomOnRight ? x + 0.5 * l.font : x - 0.5 * l.font,
                 l.top + 1.3 * l.font, roomOnRight ? Align::Left : Align::Right);
    }
    detail::savePng(canvas.surface.get(), path);
}

}  // namespace af::render
