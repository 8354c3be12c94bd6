// Load-time guards on a body's mass properties (docs/figures.md §3.4.1): a figure that passes
// them never gives the World a zero, negative or non-finite mass, nor a singular inertia.
//
// Errors are for what cannot be simulated (no volume, no mass, a singular inertia); warnings for
// what Doom 3 loads and what is merely suspicious (an absurd density). Each is said at the
// position of the key that caused it.

#include "af/geometry/mass_properties.h"
#include "figure_build_context.h"

#include <cmath>
#include <cstdio>

namespace af {

namespace {

// Densities outside this range are warned about: Doom's default is 0.2 and a figure's bodies
// rarely stray more than a few factors of ten from it, while 1e30 makes a body's mass swamp
// every other in the solver (docs/figures.md §3.4.1).
constexpr Real kLowestPlainDensity = 1e-4;
constexpr Real kHighestPlainDensity = 1e4;

// The smallest principal moment, as a fraction of the largest, that still counts as an inertia
// the solver can invert: below it the inverse amplifies rounding by more than 1e12.
constexpr Real kSingularMomentRatio = 1e-12;

std::string extentsText(const Polytope& shape) {
    Vec3 lo = Vec3::Constant(HUGE_VAL), hi = Vec3::Constant(-HUGE_VAL);
    for (const Vec3& v : shape.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const Vec3 size = shape.vertices.empty() ? Vec3::Zero() : Vec3(hi - lo);
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "%g x %g x %g", size.x(), size.y(), size.z());
    return buffer;
}

// A value in a message: short, and readable for 1e30 as for 0.2.
std::string shortText(Real v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return buffer;
}

SourceLocation orBody(SourceLocation where, const AFBody& b) { return where.line ? where : b.where; }

}  // namespace

void guardShape(FigureBuildContext& context, const AFBody& b, const Polytope& shape, MassStatus status) {
    const std::string label = "body \"" + b.name + "\"";
    if (status == MassStatus::zeroVolume) {
        context.diagnostics.error(orBody(b.shape.where, b),
                                  label + ": the " + std::string(toString(b.shape.type)) +
                                      " has no volume (its extents are " + extentsText(shape) +
                                      " units); the figure cannot be simulated (Doom 3 would use mass 1 and "
                                      "unit inertia)");
        return;
    }
    if (status == MassStatus::nonPositiveMass) {
        context.diagnostics.error(orBody(b.densityWhere, b),
                                  label + ": density times volume is not a positive mass; the figure cannot be "
                                          "simulated");
        return;
    }
    if (b.density < kLowestPlainDensity || b.density > kHighestPlainDensity)
        context.diagnostics.warning(orBody(b.densityWhere, b),
                                    label + ": density " + shortText(b.density) +
                                        " is absurd (the default is 0.2; 1e-4 to 1e4 passes without a word); Doom 3 "
                                        "loads it, but the body's mass will swamp or vanish beside the others");
}

void guardInertia(FigureBuildContext& context, const AFBody& b, Real mass, const Mat3& inertia) {
    const std::string label = "body \"" + b.name + "\"";
    if (!std::isfinite(mass) || !(mass > 0)) {
        context.diagnostics.error(b.where, label + ": its mass (" + shortText(mass) +
                                               ") is not a positive finite number; the figure cannot be simulated");
        return;
    }
    const Vec3 moments = principalInertia(inertia).moments;  // ascending
    if (!inertia.allFinite() || !(moments[0] > kSingularMomentRatio * moments[2]))
        context.diagnostics.error(orBody(b.inertiaScaleWhere, b),
                                  label + ": its inertia is singular (principal moments " +
                                      shortText(moments[0]) + ", " + shortText(moments[1]) + ", " +
                                      shortText(moments[2]) + "); the figure cannot be simulated");
}

}  // namespace af
