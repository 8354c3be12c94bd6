// Volume, centre of mass and inertia of every shape family against closed forms derived by hand
// (independently of the code's tetrahedral integration), to 1e-9 relative.
//
// Most checks go through the second moments E[x²] = ∫x² dV / V about the centroid: for a solid
// with diagonal covariance, I = m·diag(E[y²]+E[z²], E[x²]+E[z²], E[x²]+E[y²]).

#include "geometry_test_util.h"

#include "af/geometry/mass_properties.h"

#include <cmath>
#include <numbers>

namespace af {
namespace {

using test::nearRel;
using test::nearRelM;

constexpr Real kRel = 1e-9;
constexpr Real kPi = std::numbers::pi_v<Real>;

Mat3 inertiaFromDiagonalMoments(Real mass, const Vec3& e) {
    return mass * Vec3(e.y() + e.z(), e.x() + e.z(), e.x() + e.y()).asDiagonal();
}

// Inertia about the centroid from the moments about any point: volume V, first moment m1 and
// second moment M2 = ∫ p pᵀ dV all taken about that point.
Mat3 inertiaFromRawMoments(Real density, Real volume, const Vec3& m1, const Mat3& m2) {
    const Vec3 g = m1 / volume;
    const Mat3 c = m2 - volume * g * g.transpose();
    return density * (c.trace() * Mat3::Identity() - c);
}

void expectMass(const MassProperties& m, Real mass, const Vec3& com, const Mat3& inertia) {
    EXPECT_EQ(m.status, MassStatus::ok);
    EXPECT_TRUE(nearRel(m.mass, mass, kRel, 0));
    EXPECT_TRUE(nearRelM(m.centreOfMass, com, kRel));
    EXPECT_TRUE(nearRelM(m.inertia, inertia, kRel, 0));
}

TEST(MassClosedForm, BoxMassPropertiesMatchClosedForm) {
    // 5 × 7 × 9, offset: m = ρabc, I = m/12·(b²+c², a²+c², a²+b²).
    const Real rho = 0.2;
    const Real m = rho * 5 * 7 * 9;
    expectMass(massProperties(makeBox(Vec3(-1, -2, -3), Vec3(4, 5, 6)), rho), m, Vec3(1.5, 1.5, 1.5),
               inertiaFromDiagonalMoments(m, Vec3(25, 49, 81) / 12));
}

TEST(MassClosedForm, RotatedOffsetBoxHasRotatedDiagonalInertia) {
    const Mat3 r = test::rotationAbout(Vec3(2, -1, 3), 0.7);
    const Vec3 t(-40, 25, 300);
    const Polytope p = transformed(makeBox(Vec3(-1, -0.5, -2), Vec3(1, 0.5, 2)), r, t);
    const Real m = 3 * 2 * 1 * 4;
    const Mat3 body = inertiaFromDiagonalMoments(m, Vec3(4, 1, 16) / 12);
    expectMass(massProperties(p, 3), m, t, r * body * r.transpose());
}

TEST(MassClosedForm, OctahedronMatchesClosedForm) {
    // |x/hx| + |y/hy| + |z/hz| ≤ 1: V = 4/3·hx·hy·hz, E[x²] = hx²/10.
    const Vec3 h(2, 3, 4);
    const Real m = 4.0 / 3 * h.prod();
    expectMass(massProperties(makeOctahedron(Vec3(-1, -2, -3), Vec3(3, 4, 5)), 1), m, Vec3(1, 1, 1),
               inertiaFromDiagonalMoments(m, h.cwiseProduct(h) / 10));
}

TEST(MassClosedForm, RegularOctahedronHasInertiaMassTimesEdgeSquaredOverTen) {
    const Real h = 1.5, edge = h * std::sqrt(Real(2));
    const MassProperties mp = massProperties(makeOctahedron(Vec3::Constant(-h), Vec3::Constant(h)), 1);
    EXPECT_TRUE(nearRel(mp.mass, std::sqrt(Real(2)) / 3 * edge * edge * edge, kRel, 0));
    EXPECT_TRUE(nearRelM(mp.inertia, Mat3(mp.mass * edge * edge / 10 * Mat3::Identity()), kRel, 0));
}

TEST(MassClosedForm, RegularDodecahedronMatchesClosedForm) {
    // Half-extent R on every axis. The unit-circumradius dodecahedron reaches c = φ/√3 along each
    // axis and has edge 2/(√3·φ), so this one has circumradius R/c and edge a = 2R/φ².
    // V = (15 + 7√5)/4·a³, I = m·a²·(95 + 39√5)/300 about any axis through the centre.
    const Real radius = 2.5, rho = 0.7;
    const Real s5 = std::sqrt(Real(5));
    const Real phi = std::numbers::phi_v<Real>;
    const Real a = 2 * radius / (phi * phi);
    const Real m = rho * (15 + 7 * s5) / 4 * a * a * a;
    const Vec3 c(3, -1, 10);
    const MassProperties mp = massProperties(makeDodecahedron(c - Vec3::Constant(radius), c + Vec3::Constant(radius)), rho);
    expectMass(mp, m, c, Mat3(m * a * a * (95 + 39 * s5) / 300 * Mat3::Identity()));
}

TEST(MassClosedForm, DodecahedronScaledPerAxisMatchesClosedForm) {
    // Half-extents s: a linear image diag(s/c) of the unit-circumradius regular one (edge
    // a₁ = 2/(√3·φ), c = φ/√3). V scales by Π s_k/c and E[x²] by (s_x/c)², so E[x²] = (s_x/c)²·e
    // with e = I/(2m) = a₁²·(95 + 39√5)/600 for the unit one.
    const Real s5 = std::sqrt(Real(5));
    const Real phi = std::numbers::phi_v<Real>;
    const Real a1 = 2 / (std::sqrt(Real(3)) * phi);
    const Real c = phi / std::sqrt(Real(3));
    const Real e = a1 * a1 * (95 + 39 * s5) / 600;
    const Vec3 s(1, 2.5, 0.4);
    const Vec3 k = s / c;
    const Real m = (15 + 7 * s5) / 4 * a1 * a1 * a1 * k.prod();
    const MassProperties mp = massProperties(makeDodecahedron(Vec3(1, 1, 1) - s, Vec3(1, 1, 1) + s), 1);
    expectMass(mp, m, Vec3(1, 1, 1), inertiaFromDiagonalMoments(m, e * k.cwiseProduct(k)));
}

TEST(MassClosedForm, CylinderMatchesEllipticNGonPrism) {
    // Regular n-gon of circumradius 1: area A = n/2·sin θ and E[x²] = E[y²] = (2 + cos θ)/12,
    // θ = 2π/n (polar moment of its n triangles about the centre). Stretched by (hx, hy), height 2hz.
    const Vec3 v1(1, -2, -1), v2(5, 4, 3);
    const Vec3 c = (v1 + v2) / 2, h = (v2 - v1) / 2;
    for (int n = 3; n <= kMaxCylinderSides; ++n) {
        const Real th = 2 * kPi / n;
        const Real m = 2.5 * n / 2 * std::sin(th) * h.x() * h.y() * 2 * h.z();
        const Real ring = (2 + std::cos(th)) / 12;
        SCOPED_TRACE(n);
        expectMass(massProperties(makeCylinder(v1, v2, n), 2.5), m, c,
                   inertiaFromDiagonalMoments(m, Vec3(ring * h.x() * h.x(), ring * h.y() * h.y(), h.z() * h.z() / 3)));
    }
}

TEST(MassClosedForm, ManySidedCylinderApproachesTheCircularOne) {
    // Not a shape Doom builds (it clamps to 10 sides), but the prism formula must tend to πr²h, m(3r²+h²)/12.
    const MassProperties mp = massProperties(makeCylinder(Vec3(-1, -1, -2), Vec3(1, 1, 2), 720), 1);
    EXPECT_TRUE(nearRel(mp.mass, kPi * 4, 1e-4, 0));
    EXPECT_TRUE(nearRel(mp.inertia(0, 0), mp.mass * (3 + 16) / 12, 1e-4, 0));
}

TEST(MassClosedForm, RightConeMatchesPyramidClosedForm) {
    // Apex at 0, base n-gon (stretched by hx, hy) at z = −H: V = A·hx·hy·H/3, centroid at z = −3H/4,
    // about it E[z²] = 3H²/80 and E[x²] = 3/5·hx²·(2 + cos θ)/12.
    const Real hx = 1.5, hy = 2, big = 7;
    for (int n = 3; n <= kMaxConeSides; ++n) {
        const Real th = 2 * kPi / n;
        const Real m = n / 2.0 * std::sin(th) * hx * hy * big / 3;
        const Real ring = 3.0 / 5 * (2 + std::cos(th)) / 12;
        SCOPED_TRACE(n);
        expectMass(massProperties(makeCone(Vec3(-hx, -hy, 1), Vec3(hx, hy, 1 + big), n), 1), m,
                   Vec3(0, 0, -0.75 * big),
                   inertiaFromDiagonalMoments(m, Vec3(ring * hx * hx, ring * hy * hy, 3 * big * big / 80)));
    }
}

TEST(MassClosedForm, ObliqueConeMatchesShearedPyramid) {
    // The cone's base is centred on (cx, cy) but its apex is at the origin: a shear of the right
    // unit pyramid U (base ring (cos φ, sin φ, −1), apex 0) by L = [[hx,0,−cx],[0,hy,−cy],[0,0,H]].
    // About the apex, U has V₀ = A/3, ∫p = V₀·(0,0,−3/4), ∫ppᵀ = V₀·diag(k, k, 3/5) with
    // k = 3/5·(2 + cos θ)/12; the image has det L·V₀, det L·L∫p, det L·L∫ppᵀLᵀ.
    const Vec3 v1(3, 1, -2), v2(7, 4, 6);
    const Real cx = 5, cy = 2.5, hx = 2, hy = 1.5, big = 8;
    Mat3 l;
    l << hx, 0, -cx, 0, hy, -cy, 0, 0, big;
    for (int n = 3; n <= kMaxConeSides; ++n) {
        const Real th = 2 * kPi / n;
        const Real v0 = n / 2.0 * std::sin(th) / 3;
        const Real k = 3.0 / 5 * (2 + std::cos(th)) / 12;
        const Real det = l.determinant();
        const Real volume = det * v0;
        const Vec3 m1 = det * l * Vec3(0, 0, -0.75 * v0);
        const Mat3 m2 = det * l * Mat3(v0 * Vec3(k, k, 0.6).asDiagonal()) * l.transpose();
        SCOPED_TRACE(n);
        expectMass(massProperties(makeCone(v1, v2, n), 0.3), 0.3 * volume, m1 / volume,
                   inertiaFromRawMoments(0.3, volume, m1, m2));
    }
}

TEST(MassClosedForm, BoneMatchesDoubleTetrahedron) {
    // Two pyramids over the middle triangle (area 3W²/8, centroid 0) with apexes at ±L/2:
    // V = W²L/8, E[x²] = W²/40, E[y²] = 3W²/160, E[z²] = L²/40.
    const Real len = 12, w = 3, rho = 1.2;
    const Real m = rho * w * w * len / 8;
    expectMass(massProperties(makeBone(len, w), rho), m, Vec3::Zero(),
               inertiaFromDiagonalMoments(m, Vec3(w * w / 40, 3 * w * w / 160, len * len / 40)));
}

TEST(MassClosedForm, VolumeOfInvertedBoundsIsPositive) {
    const VolumeProperties v = volumeProperties(makeBox(Vec3(4, 5, -3), Vec3(-1, -2, 6)));
    EXPECT_TRUE(nearRel(v.volume, 5 * 7 * 9, 1e-12, 0));
    EXPECT_TRUE(nearRelM(v.centroid, Vec3(1.5, 1.5, 1.5), 1e-12));
}

}  // namespace
}  // namespace af
