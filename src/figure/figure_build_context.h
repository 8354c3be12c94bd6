#pragma once
// Shared state of one buildFigure call: the skeleton, the placement and the diagnostics.

#include "af/figure/figure.h"
#include "af/geometry/mass_properties.h"

#include <string>

namespace af {

struct FigureBuildContext {
    const DeclAF& decl;
    const Skeleton& skeleton;
    const RigidPose& placement;
    Diagnostics diagnostics;

    // A decl vector in model space (docs/figures.md §3.2): joint positions only, the negation applied last.
    // A joint the skeleton lacks is warned about and counts as the origin, as in Doom 3.
    Vec3 resolve(const AFVector& v);
    // A resolved direction in world space, normalised; a zero direction is an error.
    Vec3 worldDirection(const AFVector& v, const std::string& what);
    Vec3 worldPoint(const AFVector& v) { return placement.apply(resolve(v)); }

private:
    Vec3 jointPosition(const std::string& name, SourceLocation where);
};

void buildBodies(FigureBuildContext& context, Figure& figure);
// The load-time guards (docs/figures.md §3.4.1). guardShape: a shape without volume or a body
// without mass is an error, an absurd density a warning. guardInertia, on the final mass and
// inertia (after inertiaScale and totalMass): not finite, not positive, or singular is an error.
void guardShape(FigureBuildContext& context, const AFBody& body, const Polytope& shape, MassStatus status);
void guardInertia(FigureBuildContext& context, const AFBody& body, Real mass, const Mat3& inertia);
void buildConstraints(FigureBuildContext& context, Figure& figure);
void claimJoints(FigureBuildContext& context, Figure& figure);
// The warnings about figures that tend to misbehave (mass and inertia ratios, overlap, trees).
void checkFigure(FigureBuildContext& context, const Figure& figure);

}  // namespace af
