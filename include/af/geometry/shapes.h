#pragma once
// The convex shapes of an .af body `model`, built as Doom 3 builds them (docs/formats.md §1.6,
// docs/figures.md §3.3; D3 idAF::LoadBody and idTraceModel::Setup*), from values already resolved to numbers.
//
// Frames: v1 and v2 of box/octahedron/dodecahedron/cylinder/cone are bounds in the BODY frame.
// The body frame sits at `origin` (model space) with rotation R = rotationFromAngles(angles)
// (body → model, columns = body axes). A bone's v1 and v2 are MODEL-space points instead; its
// frame is derived from them and `angles` is ignored. Lengths in file units, angles in degrees.
//
// `custom( "…" )` models are not offered: Doom rejects them ("not yet implemented") and so do we;
// the parser reports them and they never reach this stage.

#include "af/geometry/polytope.h"

#include <string>
#include <vector>

namespace af {

enum class ShapeKind { box, octahedron, dodecahedron, cylinder, cone, bone };

/// The shape word as .af files write it.
const char* toString(ShapeKind kind);

/// Doom's trace-model limits, which cap the side count of cylinders and cones.
inline constexpr int kMaxCylinderSides = 10;  ///< 3n edges ≤ 32
inline constexpr int kMaxConeSides = 15;      ///< n + 1 faces ≤ 16

/// One body's model and placement, as the decl says after vector resolution.
struct ShapeSpec {
    ShapeKind kind = ShapeKind::box;
    Vec3      v1 = Vec3::Constant(-10);  ///< bounds min (body frame) or bone start (model space)
    Vec3      v2 = Vec3::Constant(10);   ///< bounds max (body frame) or bone end (model space)
    int       sides = 3;                 ///< cylinder and cone only, as written (clamped when built)
    Real      width = 0;                 ///< bone only: full x-extent of the bone's middle triangle
    Vec3      origin = Vec3::Zero();     ///< body frame origin in model space
    Vec3      angles = Vec3::Zero();     ///< (pitch, yaw, roll) in degrees; ignored for bones
};

/// A built body shape: the polytope in its body frame and the frame's pose in model space.
/// Model-space points are `origin + rotation * p` for p in `local`.
struct BodyShape {
    Polytope                 local;
    Vec3                     origin = Vec3::Zero();
    Mat3                     rotation = Mat3::Identity();
    int                      sides = 0;  ///< sides actually built (cylinder, cone); 0 otherwise
    std::vector<std::string> warnings;   ///< clamping, inverted bounds, zero-length bone; never printed
};

/// Builds the shape of `spec` and places it. Never throws for finite input; questionable input
/// yields a (possibly degenerate) shape plus warnings.
BodyShape buildShape(const ShapeSpec& spec);

/// The same body with its frame moved to `centre` (given in the body frame), usually the centre
/// of mass: the polytope is translated by −centre and origin becomes origin + rotation·centre, so
/// every model-space point stays put. This is Doom's "reference point is the centre of mass" step.
BodyShape recentred(const BodyShape& body, const Vec3& centre);

// The builders below work in the body frame and take bounds min/max as written in the file.
// Bounds whose min exceeds max on some axis are accepted: the vertices are where Doom puts them
// and the faces are oriented outward anyway (Doom would get a negative volume); buildShape warns.

/// The 8 corners of [v1, v2].
Polytope makeBox(const Vec3& v1, const Vec3& v2);

/// 6 vertices at the centres of the faces of [v1, v2]: c ± (hx,0,0), c ± (0,hy,0), c ± (0,0,hz).
Polytope makeOctahedron(const Vec3& v1, const Vec3& v2);

/// The regular dodecahedron of circumradius 1, (±a,±a,±a), (±b,±c,0), (±c,0,±b), (0,±b,±c),
/// scaled per axis by (v2 − v1)/(2c) so it spans exactly [v1, v2], centred on the bounds' centre.
Polytope makeDodecahedron(const Vec3& v1, const Vec3& v2);

/// Number of sides Doom builds for a cylinder asked for `sides`: < 3 → 3, > 10 → 10. The
/// upper clamp warns in Doom, the lower one is silent.
int clampCylinderSides(int sides);

/// Number of sides Doom builds for a cone asked for `sides`: < 2 → 3 (2 is kept and builds a
/// flat, zero-volume shape), > 15 → 15 (warns in Doom).
int clampConeSides(int sides);

/// Prism along body Z over an n-gon inscribed in the ellipse of the bounds: for φ = 2πi/n the
/// bottom vertex i is (cx + hx·cosφ, cy + hy·sinφ, cz − hz) and top vertex n + i the same at
/// cz + hz. `sides` is used as given: clamp it first.
Polytope makeCylinder(const Vec3& v1, const Vec3& v2, int sides);

/// Pyramid with its apex at the body origin, pointing up +Z. As idAF::LoadBody does, the bounds
/// are first shifted so that their top is at z = 0 (min.z ← v1.z − v2.z, max.z ← 0); the base
/// ring (vertices 0…n−1) is the cylinder's bottom ring at z = min.z, centred on (cx, cy); the
/// apex (vertex n) is (0, 0, 0) whatever cx and cy are. `sides` is used as given: clamp it first.
Polytope makeCone(const Vec3& v1, const Vec3& v2, int sides);

/// The bone's double tetrahedron in its own frame (z along the bone, centred on the origin):
/// vertex 0 = (0,0,−L/2), the middle triangle 1…3 = (0,−W/2,0), (W/2,W/4,0), (−W/2,W/4,0), and
/// vertex 4 = (0,0,L/2). Volume W²·L/8, centroid at the origin.
Polytope makeBone(Real length, Real width);

/// Rotation (bone frame → model, columns = bone axes) of a bone from v1 to v2: Z = unit(v2 − v1);
/// X = (−d.y, d.x, 0)/|(d.x, d.y)|, or (1,0,0) when the bone is vertical; Y = Z × X. Identity
/// when v1 = v2 (Doom would produce NaNs there).
Mat3 boneRotation(const Vec3& v1, const Vec3& v2);

}  // namespace af
