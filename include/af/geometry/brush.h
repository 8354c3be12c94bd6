#pragma once
// The solid of a map brush: the convex polytope where all its half-spaces a·x + b·y + c·z + d ≤ 0
// overlap (docs/formats.md §5.6). Frame and units: those of the map (world, Doom units; brush
// planes are not offset by the entity origin).
//
// Vertices are the intersections of plane triples that lie inside every other half-space,
// merged within a tolerance; each face is the loop of vertices on one plane, counter-clockwise
// seen from outside. A plane that touches the solid in less than an area (it lies outside, or
// meets it in an edge or a corner, or repeats another plane) is redundant and dropped.
// A brush whose half-spaces leave a direction unbounded is open; one with no volume is empty.
// Both are error values, never exceptions.

#include "af/geometry/polytope.h"
#include "af/text/map_file.h"

#include <optional>
#include <string>
#include <vector>

namespace af {

/// normal·x + d = 0 with `normal` pointing out of the solid; any non-zero length.
struct BrushPlane {
    Vec3 normal = Vec3::UnitZ();
    Real d = 0;
};

enum class BrushProblem {
    none,
    badPlane,  ///< a normal that is zero or not finite, or a d that is not finite
    open,      ///< the half-spaces do not enclose a bounded region
    empty,     ///< they enclose no volume (they miss each other, or meet in a plane, line or point),
               ///< or a sliver so thin that its faces do not close up within the tolerance
};

struct BrushPolytope {
    std::optional<Polytope> polytope;  ///< present exactly when problem == none
    std::vector<int> faceSides;        ///< for each face, the index of the plane it lies on
    std::vector<int> droppedSides;     ///< redundant planes, ascending
    BrushProblem problem = BrushProblem::none;
    std::string message;               ///< what is wrong, for a diagnostic; empty when ok

    bool ok() const { return problem == BrushProblem::none; }
};

/// The solid of `planes`. `tolerance` is the distance within which a point counts as on a plane
/// and two vertices as one; 0 picks 1e-6 × max(1, largest |d| of the normalised planes), which
/// absorbs the float rounding of planes read from a file.
BrushPolytope polytopeFromPlanes(const std::vector<BrushPlane>& planes, Real tolerance = 0);

/// The planes of a brushDef3's sides, in side order.
std::vector<BrushPlane> brushPlanes(const BrushDef3& brush);

/// polytopeFromPlanes(brushPlanes(brush), tolerance); faceSides index the brush's sides.
BrushPolytope polytopeFromBrush(const BrushDef3& brush, Real tolerance = 0);

}  // namespace af
