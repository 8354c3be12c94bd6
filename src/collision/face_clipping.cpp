#include "face_clipping.h"

#include "contact_ids.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace af::collision_detail {

namespace {

// A vertex of the polygon being clipped, named by the two lines that meet there (contact_ids.h):
// `in` the line of the edge arriving, `out` the line of the edge leaving.
struct ClipVertex {
    Vec3 p = Vec3::Zero();
    std::uint8_t in = 0, out = 0;
};

// Keeps the part of `in` where side·(p − origin) ≤ 0 (side is unit). Points within
// kLengthTolerance of the plane count as on it and are kept as they are, so that a vertex lying
// on a side plane keeps its own id instead of spawning a crossing next to it.
void clipAgainst(const std::vector<ClipVertex>& in, const Vec3& side, const Vec3& origin,
                 std::uint8_t sideLine, std::vector<ClipVertex>& out) {
    out.clear();
    const size_t n = in.size();
    for (size_t k = 0; k < n; ++k) {
        const ClipVertex& p = in[k];
        const ClipVertex& q = in[(k + 1) % n];
        const Real dp = side.dot(p.p - origin);
        const Real dq = side.dot(q.p - origin);
        if (dp <= kLengthTolerance) {
            out.push_back(p);
        }
        const bool leaving = dp < -kLengthTolerance && dq > kLengthTolerance;
        const bool entering = dp > kLengthTolerance && dq < -kLengthTolerance;
        if (leaving || entering) {
            ClipVertex x;
            x.p = p.p + (dp / (dp - dq)) * (q.p - p.p);
            x.in = leaving ? p.out : sideLine;
            x.out = leaving ? sideLine : p.out;
            out.push_back(x);
        }
    }
}

}  // namespace

int mostOpposedFaceAround(const PlacedShape& shape, int vertex, const Vec3& direction) {
    const Vec3 d = shape.toOwn(direction);
    int best = -1;
    Real bestDot = std::numeric_limits<Real>::infinity();
    for (int f = 0; f < shape.faceCount(); ++f) {
        if (!shape.hasFace(f)) {
            continue;
        }
        const std::vector<int>& loop = shape.polytope->faces[f].loop;
        if (std::find(loop.begin(), loop.end(), vertex) == loop.end()) {
            continue;
        }
        const Real x = shape.polytope->faces[f].normal.dot(d);
        if (x < bestDot) {
            best = f;
            bestDot = x;
        }
    }
    return best;
}

void clipFaces(const PlacedShape& reference, int referenceFace, const PlacedShape& incident, int incidentFace,
               const Vec3& outward, bool referenceIsB, Real margin, std::vector<Candidate>& out) {
    const Vec3 normal = reference.normal(referenceFace);
    const Real offset = reference.offset(referenceFace, normal);
    const Real slant = normal.dot(outward);  // 1 for a face axis

    thread_local std::vector<ClipVertex> polygon, clipped;
    const std::vector<int>& incidentLoop = incident.polytope->faces[incidentFace].loop;
    const int ni = int(incidentLoop.size());
    polygon.resize(ni);
    for (int k = 0; k < ni; ++k) {
        polygon[k].p = incident.vertex(incidentLoop[k]);
        polygon[k].in = incidentLine((k + ni - 1) % ni);
        polygon[k].out = incidentLine(k);
    }

    // The side planes contain a reference edge and `outward`; on a counter-clockwise loop
    // edge × outward points out of the face.
    const std::vector<int>& referenceLoop = reference.polytope->faces[referenceFace].loop;
    const int nr = int(referenceLoop.size());
    Vec3 r1 = reference.vertex(referenceLoop[0]);
    for (int j = 0; j < nr && !polygon.empty(); ++j) {
        const Vec3 r0 = r1;
        r1 = reference.vertex(referenceLoop[(j + 1) % nr]);
        const Vec3 side = (r1 - r0).cross(outward);
        const Real len = side.norm();
        if (len <= kLengthTolerance) {
            continue;
        }
        clipAgainst(polygon, side / len, r0, referenceSide(j), clipped);
        std::swap(polygon, clipped);
    }

    for (const ClipVertex& v : polygon) {
        const Real separation = (normal.dot(v.p) - offset) / slant;  // along `outward`
        if (separation <= margin) {
            out.push_back({v.p - Real(0.5) * separation * outward, -separation,
                           faceContactId(referenceIsB, referenceFace, v.in, v.out)});
        }
    }
}

}  // namespace af::collision_detail
