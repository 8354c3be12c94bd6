// findBestBoxAxis(): the separating-axis search of two boxes in closed form. Every candidate is
// scored from the boxes' centres, half extents and the rotation C between their axes, as in the
// classic fifteen-axis box test, instead of by projecting eight vertices per axis; the features
// each axis names (faces, support edges) are those the polytope search would name.

#include "separating_axis.h"

#include <cmath>
#include <limits>

namespace af::collision_detail {

namespace {

int edgeIndex(const BoxFeatures& box, int axis, Real alongNext, Real alongAfter) {
    return box.edge[axis][(alongNext > 0 ? 1 : 0) | (alongAfter > 0 ? 2 : 0)];
}

}  // namespace

std::optional<SeparatingAxis> findBestBoxAxis(const PlacedShape& a, const PlacedShape& b, Real margin) {
    const BoxFeatures& boxA = a.features->box;
    const BoxFeatures& boxB = b.features->box;
    // A box in its own body frame, as collide() places A, has the working frame's axes: then the
    // products with A's axes are copies, and are skipped.
    const bool aIsFrame = boxA.aligned && a.rotation == Mat3::Identity();
    const Mat3 axesB = boxB.aligned ? b.rotation : Mat3(b.rotation * boxB.axes);  // working frame, columns v_j
    const Vec3 centreB = b.rotation * boxB.centre + b.translation;
    Mat3 axesA, c;  // A's axes in the working frame, columns u_i; c(i, j) = u_i · v_j
    Vec3 between, dA;  // B's centre from A's, in the working frame and along A's axes
    if (aIsFrame) {
        axesA.setIdentity();
        c = axesB;
        between = centreB - (boxA.centre + a.translation);
        dA = between;
    } else {
        axesA = a.rotation * boxA.axes;
        c = axesA.transpose() * axesB;
        between = centreB - (a.rotation * boxA.centre + a.translation);
        dA = axesA.transpose() * between;
    }
    // A's faces, then B's, first only as a test for a gap beyond the margin (most pairs the
    // broadphase lets through end here): along each axis the better of its two faces.
    const Mat3 absC = c.cwiseAbs();
    const Vec3 radiusB = absC * boxB.half;  // B's half width along each u_i
    if ((dA.cwiseAbs() - radiusB - boxA.half).maxCoeff() > margin) {
        return std::nullopt;
    }
    const Vec3 dB = axesB.transpose() * between;        // the same along B's axes
    const Vec3 radiusA = absC.transpose() * boxA.half;  // A's half width along each v_j
    if ((dB.cwiseAbs() - radiusA - boxB.half).maxCoeff() > margin) {
        return std::nullopt;
    }

    // Faces in the polytopes' order, so that ties go where the polytope search sends them.
    constexpr Real kNone = -std::numeric_limits<Real>::infinity();
    int bestFaceA = -1, bestFaceB = -1;
    Real sepFaceA = kNone, sepFaceB = kNone;
    for (int f = 0; f < 6; ++f) {
        const int i = boxA.faceAxis[f];
        const Real sep = boxA.faceSign[f] * dA[i] - radiusB[i] - boxA.half[i];
        if (sep > sepFaceA) {
            bestFaceA = f;
            sepFaceA = sep;
        }
    }
    for (int f = 0; f < 6; ++f) {
        const int j = boxB.faceAxis[f];
        const Real sep = -boxB.faceSign[f] * dB[j] - radiusA[j] - boxB.half[j];
        if (sep > sepFaceB) {
            bestFaceB = f;
            sepFaceB = sep;
        }
    }

    // Edge pairs: L = u_i × v_j. Along A's axes L = (…, −c(i2, j), c(i1, j)) at (i1, i2) = the
    // axes after i; along B's, L · v_j1 = c(i, j2) and L · v_j2 = −c(i, j1).
    // The best pair is built into a SeparatingAxis once, at the end.
    int bestI = -1, bestJ = -1;
    Real sepEdges = kNone, bestSign = 1, bestLen = 1;
    for (int ga = 0; ga < 3; ++ga) {
        const int i = boxA.groupAxis[ga], i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int gb = 0; gb < 3; ++gb) {
            const int j = boxB.groupAxis[gb], j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            const Real lA1 = -c(i2, j), lA2 = c(i1, j);
            const Real lB1 = c(i, j2), lB2 = -c(i, j1);
            const Real len = std::sqrt(lA1 * lA1 + lA2 * lA2);
            if (len <= kParallelSine) {
                continue;
            }
            const Real centres = lA1 * dA[i1] + lA2 * dA[i2];
            const Real sep = (std::abs(centres) - boxA.half[i1] * std::abs(lA1) - boxA.half[i2] * std::abs(lA2) -
                              boxB.half[j1] * std::abs(lB1) - boxB.half[j2] * std::abs(lB2)) /
                             len;
            if (sep > margin) {
                return std::nullopt;
            }
            if (sep > sepEdges) {
                sepEdges = sep;
                bestI = i;
                bestJ = j;
                bestSign = centres >= 0 ? 1 : -1;
                bestLen = len;
            }
        }
    }

    SeparatingAxis edges;
    if (bestI >= 0) {
        // s = sign·L points out of A towards B: A's support edge along s, B's along −s.
        const int i = bestI, j = bestJ;
        const Real sign = bestSign;
        const Real lA1 = -c((i + 2) % 3, j), lA2 = c((i + 1) % 3, j);
        const Real lB1 = c(i, (j + 2) % 3), lB2 = -c(i, (j + 1) % 3);
        const Vec3 s = (sign / bestLen) * axesA.col(i).cross(axesB.col(j));
        edges = {AxisKind::edges, -s, sepEdges, edgeIndex(boxA, i, sign * lA1, sign * lA2),
                 edgeIndex(boxB, j, -sign * lB1, -sign * lB2)};
    }

    SeparatingAxis faceA, faceB;
    if (bestFaceA >= 0) {
        faceA = {AxisKind::faceA, -a.normal(bestFaceA), sepFaceA, bestFaceA, -1};
    }
    if (bestFaceB >= 0) {
        faceB = {AxisKind::faceB, b.normal(bestFaceB), sepFaceB, -1, bestFaceB};
    }
    return chooseAxis(a, b, faceA, faceB, edges);
}

}  // namespace af::collision_detail
