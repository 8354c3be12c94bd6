#include "af/geometry/shapes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace af {

namespace {

using Loops = std::vector<std::vector<int>>;

// Loops of a prism or pyramid side ring 0…n−1 laid out counter-clockwise about +Z: the bottom
// face, seen from below, runs the ring backwards.
std::vector<int> reversedRing(int n, int first) {
    std::vector<int> loop;
    for (int i = n - 1; i >= 0; --i) {
        loop.push_back(first + i);
    }
    return loop;
}

// Vertex i of an n-gon inscribed in the ellipse of half-size h around c, at height z.
Vec3 ringVertex(const Vec3& c, const Vec3& h, Real z, int i, int n) {
    const Real phi = 2 * std::numbers::pi_v<Real> * i / n;
    return Vec3(c.x() + h.x() * std::cos(phi), c.y() + h.y() * std::sin(phi), z);
}

// The regular dodecahedron of circumradius 1 (vertices on the cube (±a)³ and on the three
// golden rectangles), and its faces. The faces are found rather than tabulated: each is
// perpendicular to one of the 12 icosahedron directions (0,±φ,±1) and their cyclic shifts, and
// holds the 5 vertices farthest along it. Sorting those by angle about the direction gives a
// counter-clockwise loop seen from outside.
struct UnitDodecahedron {
    Real              a = 1 / std::sqrt(Real(3));                    // 0.5773502691896257
    Real              b = std::sqrt((3 - std::sqrt(Real(5))) / 6);  // 0.3568220897730899
    Real              c = std::sqrt((3 + std::sqrt(Real(5))) / 6);  // 0.9341723589627156
    std::vector<Vec3> vertices;
    Loops             loops;

    UnitDodecahedron() {
        for (Real sx : {1, -1}) {
            for (Real sy : {1, -1}) {
                for (Real sz : {1, -1}) {
                    vertices.emplace_back(sx * a, sy * a, sz * a);
                }
            }
        }
        for (Real s0 : {1, -1}) {
            for (Real s1 : {1, -1}) {
                vertices.emplace_back(s0 * b, s1 * c, 0);
            }
        }
        for (Real s0 : {1, -1}) {
            for (Real s1 : {1, -1}) {
                vertices.emplace_back(s0 * c, 0, s1 * b);
            }
        }
        for (Real s0 : {1, -1}) {
            for (Real s1 : {1, -1}) {
                vertices.emplace_back(0, s0 * b, s1 * c);
            }
        }

        const Real phi = std::numbers::phi_v<Real>;
        for (int axis = 0; axis < 3; ++axis) {
            for (Real s0 : {1, -1}) {
                for (Real s1 : {1, -1}) {
                    Vec3 n = Vec3::Zero();
                    n[(axis + 1) % 3] = s0 * phi;
                    n[(axis + 2) % 3] = s1;
                    loops.push_back(faceAround(n.normalized()));
                }
            }
        }
    }

    std::vector<int> faceAround(const Vec3& n) const {
        Real top = -1;
        for (const Vec3& v : vertices) {
            top = std::max(top, v.dot(n));
        }
        // Face vertices lie at the inradius 0.7947 along n; the next layer is at 0.1876.
        std::vector<int> face;
        for (int i = 0; i < int(vertices.size()); ++i) {
            if (vertices[i].dot(n) > top - Real(0.1)) {
                face.push_back(i);
            }
        }
        const Vec3 u = (vertices[face[0]] - top * n).normalized();
        const Vec3 w = n.cross(u);
        auto angle = [&](int i) { return std::atan2(vertices[i].dot(w), vertices[i].dot(u)); };
        std::sort(face.begin(), face.end(), [&](int i, int j) { return angle(i) < angle(j); });
        return face;
    }
};

const UnitDodecahedron& unitDodecahedron() {
    static const UnitDodecahedron d;
    return d;
}

const char* axisName(int k) { return k == 0 ? "x" : (k == 1 ? "y" : "z"); }

void warnInvertedBounds(const ShapeSpec& spec, std::vector<std::string>& warnings) {
    for (int k = 0; k < 3; ++k) {
        if (spec.v1[k] > spec.v2[k]) {
            // Made in place: GCC 12 at -O3 misreads the move of a pushed temporary string as a
            // read past its small-string buffer (-Wstringop-overread).
            std::string& warning = warnings.emplace_back("bounds inverted on ");
            warning += axisName(k);
            warning += " (min > max); the shape is built mirrored, with positive volume";
        }
    }
}

}  // namespace

Polytope makeBox(const Vec3& v1, const Vec3& v2) {
    std::vector<Vec3> v;
    for (Real z : {v1.z(), v2.z()}) {
        v.emplace_back(v1.x(), v1.y(), z);
        v.emplace_back(v2.x(), v1.y(), z);
        v.emplace_back(v2.x(), v2.y(), z);
        v.emplace_back(v1.x(), v2.y(), z);
    }
    Loops loops;
    for (int i = 0; i < 4; ++i) {
        const int j = (i + 1) % 4;
        loops.push_back({i, j, 4 + j, 4 + i});
    }
    loops.push_back(reversedRing(4, 0));
    loops.push_back({4, 5, 6, 7});
    return makePolytope(std::move(v), loops);
}

Polytope makeOctahedron(const Vec3& v1, const Vec3& v2) {
    const Vec3 c = (v1 + v2) * Real(0.5);
    const Vec3 h = v2 - c;
    std::vector<Vec3> v = {
        c + Vec3(h.x(), 0, 0), c - Vec3(h.x(), 0, 0),
        c + Vec3(0, h.y(), 0), c - Vec3(0, h.y(), 0),
        c + Vec3(0, 0, h.z()), c - Vec3(0, 0, h.z()),
    };
    // One triangle per octant; (+x, +y, +z) is counter-clockwise seen from outside, and each
    // negative sign mirrors the octant, which reverses the loop.
    Loops loops;
    for (int octant = 0; octant < 8; ++octant) {
        const int nx = octant & 1, ny = (octant >> 1) & 1, nz = (octant >> 2) & 1;
        std::vector<int> loop = {0 + nx, 2 + ny, 4 + nz};
        if ((nx + ny + nz) % 2 == 1) {
            std::swap(loop[1], loop[2]);
        }
        loops.push_back(loop);
    }
    return makePolytope(std::move(v), loops);
}

Polytope makeDodecahedron(const Vec3& v1, const Vec3& v2) {
    const UnitDodecahedron& unit = unitDodecahedron();
    const Vec3 c = (v1 + v2) * Real(0.5);
    const Vec3 s = (v2 - v1) / (2 * unit.c);
    std::vector<Vec3> v;
    for (const Vec3& u : unit.vertices) {
        v.push_back(c + s.cwiseProduct(u));
    }
    return makePolytope(std::move(v), unit.loops);
}

int clampCylinderSides(int sides) { return std::clamp(sides, 3, kMaxCylinderSides); }

int clampConeSides(int sides) { return sides < 2 ? 3 : std::min(sides, kMaxConeSides); }

Polytope makeCylinder(const Vec3& v1, const Vec3& v2, int sides) {
    const int n = sides;
    const Vec3 c = (v1 + v2) * Real(0.5);
    const Vec3 h = v2 - c;
    std::vector<Vec3> v;
    for (int i = 0; i < n; ++i) {
        v.push_back(ringVertex(c, h, c.z() - h.z(), i, n));
    }
    for (int i = 0; i < n; ++i) {
        v.push_back(ringVertex(c, h, c.z() + h.z(), i, n));
    }
    Loops loops;
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        loops.push_back({i, j, n + j, n + i});
    }
    loops.push_back(reversedRing(n, 0));
    std::vector<int> top;
    for (int i = 0; i < n; ++i) {
        top.push_back(n + i);
    }
    loops.push_back(top);
    return makePolytope(std::move(v), loops);
}

Polytope makeCone(const Vec3& v1, const Vec3& v2, int sides) {
    const int n = sides;
    const Vec3 lo(v1.x(), v1.y(), v1.z() - v2.z());
    const Vec3 hi(v2.x(), v2.y(), 0);
    const Vec3 c = (lo + hi) * Real(0.5);
    const Vec3 h = hi - c;
    std::vector<Vec3> v;
    for (int i = 0; i < n; ++i) {
        v.push_back(ringVertex(c, h, c.z() - h.z(), i, n));
    }
    v.push_back(Vec3::Zero());
    Loops loops;
    for (int i = 0; i < n; ++i) {
        loops.push_back({i, (i + 1) % n, n});
    }
    loops.push_back(reversedRing(n, 0));
    return makePolytope(std::move(v), loops);
}

Polytope makeBone(Real length, Real width) {
    const Real halfLength = length * Real(0.5);
    std::vector<Vec3> v = {
        Vec3(0, 0, -halfLength),
        Vec3(0, -width * Real(0.5), 0),
        Vec3(width * Real(0.5), width * Real(0.25), 0),
        Vec3(-width * Real(0.5), width * Real(0.25), 0),
        Vec3(0, 0, halfLength),
    };
    // The middle triangle 1, 2, 3 runs counter-clockwise about +Z.
    Loops loops;
    for (int k = 0; k < 3; ++k) {
        const int i = 1 + k, j = 1 + (k + 1) % 3;
        loops.push_back({i, j, 4});
        loops.push_back({j, i, 0});
    }
    return makePolytope(std::move(v), loops);
}

Mat3 boneRotation(const Vec3& v1, const Vec3& v2) {
    const Vec3 delta = v2 - v1;
    const Real length = delta.norm();
    if (length == 0) {
        return Mat3::Identity();
    }
    const Vec3 d = delta / length;
    const Real planar = std::sqrt(d.x() * d.x() + d.y() * d.y());
    const Vec3 x = planar == 0 ? Vec3(1, 0, 0) : Vec3(Vec3(-d.y(), d.x(), 0) / planar);
    Mat3 r;
    r.col(0) = x;
    r.col(1) = d.cross(x);
    r.col(2) = d;
    return r;
}

BodyShape buildShape(const ShapeSpec& spec) {
    BodyShape body;
    body.origin = spec.origin;
    if (spec.kind == ShapeKind::bone) {
        const Real length = (spec.v2 - spec.v1).norm();
        if (length == 0) {
            body.warnings.emplace_back("bone has zero length (v1 = v2); using the identity frame");
        }
        body.rotation = boneRotation(spec.v1, spec.v2);
        body.local = makeBone(length, spec.width);
        return body;
    }

    body.rotation = rotationFromAngles(spec.angles.x(), spec.angles.y(), spec.angles.z());
    warnInvertedBounds(spec, body.warnings);
    switch (spec.kind) {
    case ShapeKind::box:
        body.local = makeBox(spec.v1, spec.v2);
        break;
    case ShapeKind::octahedron:
        body.local = makeOctahedron(spec.v1, spec.v2);
        break;
    case ShapeKind::dodecahedron:
        body.local = makeDodecahedron(spec.v1, spec.v2);
        break;
    case ShapeKind::cylinder:
        body.sides = clampCylinderSides(spec.sides);
        if (spec.sides > kMaxCylinderSides) {
            body.warnings.push_back("cylinder has " + std::to_string(spec.sides) +
                                    " sides; clamped to " + std::to_string(body.sides) +
                                    " (trace model limits)");
        }
        body.local = makeCylinder(spec.v1, spec.v2, body.sides);
        break;
    case ShapeKind::cone:
        body.sides = clampConeSides(spec.sides);
        if (spec.sides > kMaxConeSides) {
            body.warnings.push_back("cone has " + std::to_string(spec.sides) + " sides; clamped to " +
                                    std::to_string(body.sides) + " (trace model limits)");
        }
        body.local = makeCone(spec.v1, spec.v2, body.sides);
        break;
    case ShapeKind::bone:
        break;
    }
    return body;
}

BodyShape recentred(const BodyShape& body, const Vec3& centre) {
    BodyShape moved = body;
    moved.local = translated(body.local, -centre);
    moved.origin = body.origin + body.rotation * centre;
    return moved;
}

const char* toString(ShapeKind kind) {
    switch (kind) {
    case ShapeKind::box: return "box";
    case ShapeKind::octahedron: return "octahedron";
    case ShapeKind::dodecahedron: return "dodecahedron";
    case ShapeKind::cylinder: return "cylinder";
    case ShapeKind::cone: return "cone";
    case ShapeKind::bone: return "bone";
    }
    return "?";
}

}  // namespace af
