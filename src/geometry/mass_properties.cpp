#include "af/geometry/mass_properties.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace af {

// Method: the divergence theorem turns volume integrals over the solid into a sum over its
// boundary. Cut each face into a fan of triangles and join every triangle (a, b, c) to one
// reference point r; the signed tetrahedra (r, a, b, c) tile the solid exactly, with the outside
// parts cancelling, because the faces are consistently oriented. For a tetrahedron with one
// vertex at the origin and the others at a, b, c (D = a·(b×c), the edge matrix's determinant):
//
//     ∫ 1 dV      = D / 6
//     ∫ p dV      = D / 24 · (a + b + c)
//     ∫ p pᵀ dV   = D / 120 · (a aᵀ + b bᵀ + c cᵀ + (a+b+c)(a+b+c)ᵀ)
//
// the last being the image of the unit tetrahedron's (1/120)(I + 1 1ᵀ) under p ↦ [a b c] p
// (Tonon 2004, "Explicit exact formulas for the 3-D tetrahedron inertia tensor in terms of its
// vertex coordinates"; Blow & Binstock 2004, "How to find the inertia tensor (or other mass
// properties) of a 3D solid body represented by a triangle mesh"). The inertia tensor about the
// centroid is then tr(C)·I − C with C = ∫ p pᵀ dV − V·g gᵀ. Doom uses Mirtich's projection
// integrals (1996) instead; both are exact, so results agree to rounding.
//
// Everything is taken relative to the vertex mean r, not the frame origin, so that a shape far
// from the origin keeps its digits and moving the input moves nothing but the centroid.

namespace {

// Volumes below this fraction of (largest bounding-box side)³ are flat shapes; Doom's own test
// is for exactly zero, which rounding makes meaningless in our arithmetic.
constexpr Real kFlatVolumeFraction = 1e-12;

Real boundingScale(const Polytope& polytope) {
    if (polytope.vertices.empty()) {
        return 0;
    }
    Vec3 lo = polytope.vertices[0], hi = polytope.vertices[0];
    for (const Vec3& v : polytope.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    return (hi - lo).maxCoeff();
}

MassProperties doomFallback(MassStatus why) {
    MassProperties m;  // mass 1, centre 0, identity inertia: what Doom substitutes
    m.status = why;
    return m;
}

}  // namespace

VolumeProperties volumeProperties(const Polytope& polytope) {
    Vec3 r = Vec3::Zero();
    for (const Vec3& v : polytope.vertices) {
        r += v;
    }
    if (!polytope.vertices.empty()) {
        r /= Real(polytope.vertices.size());
    }

    Real sixV = 0;                     // 6 ∫ 1 dV
    Vec3 twentyFourM1 = Vec3::Zero();  // 24 ∫ p dV
    Mat3 oneTwentyM2 = Mat3::Zero();   // 120 ∫ p pᵀ dV
    for (const Face& face : polytope.faces) {
        const std::vector<int>& loop = face.loop;
        for (size_t i = 1; i + 1 < loop.size(); ++i) {
            const Vec3 a = polytope.vertices[loop[0]] - r;
            const Vec3 b = polytope.vertices[loop[i]] - r;
            const Vec3 c = polytope.vertices[loop[i + 1]] - r;
            const Real d = a.dot(b.cross(c));
            const Vec3 s = a + b + c;
            sixV += d;
            twentyFourM1 += d * s;
            oneTwentyM2 += d * (a * a.transpose() + b * b.transpose() + c * c.transpose() +
                                s * s.transpose());
        }
    }

    VolumeProperties out;
    out.volume = sixV / 6;
    if (out.volume == 0) {
        out.centroid = r;
        return out;
    }
    const Vec3 g = twentyFourM1 / (4 * sixV);  // centroid relative to r: ∫p dV / V
    const Mat3 c = oneTwentyM2 / 120 - out.volume * g * g.transpose();
    out.centroid = r + g;
    out.unitInertia = c.trace() * Mat3::Identity() - c;
    return out;
}

MassProperties massProperties(const Polytope& polytope, Real density) {
    const VolumeProperties v = volumeProperties(polytope);
    const Real scale = boundingScale(polytope);
    if (!(v.volume > kFlatVolumeFraction * scale * scale * scale)) {
        return doomFallback(MassStatus::zeroVolume);
    }
    MassProperties m;
    m.mass = density * v.volume;
    if (!(m.mass > 0)) {
        return doomFallback(MassStatus::nonPositiveMass);
    }
    m.centreOfMass = v.centroid;
    m.inertia = density * v.unitInertia;
    return m;
}

Mat3 applyInertiaScale(const Mat3& inertia, const Mat3& scale) {
    if (scale == Mat3::Identity()) {
        return inertia;
    }
    return inertia * scale;
}

Real totalMassScale(std::span<const MassProperties> bodies, Real totalMass) {
    if (!(totalMass > 0)) {
        return 1;
    }
    Real sum = 0;
    for (const MassProperties& b : bodies) {
        sum += b.mass;
    }
    return sum > 0 ? totalMass / sum : Real(1);
}

std::vector<MassProperties> rescaledToTotalMass(std::span<const MassProperties> bodies,
                                                Real totalMass) {
    const Real factor = totalMassScale(bodies, totalMass);
    std::vector<MassProperties> out(bodies.begin(), bodies.end());
    for (MassProperties& b : out) {
        b.mass *= factor;
        b.inertia *= factor;
    }
    return out;
}

PrincipalInertia principalInertia(const Mat3& inertia) {
    const Mat3 symmetric = (inertia + inertia.transpose()) * Real(0.5);
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(symmetric);
    PrincipalInertia p;
    p.moments = solver.eigenvalues();
    p.axes = solver.eigenvectors();
    if (p.axes.determinant() < 0) {
        p.axes.col(2) = -p.axes.col(2);
    }
    return p;
}

}  // namespace af
