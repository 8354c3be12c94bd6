#pragma once
// A prepared shape placed in the query's working frame (A's body frame, so that coordinates stay
// small wherever the bodies are in the world). The rigid map from the shape's own frame is applied
// to query directions and to the few points a query needs, never to every vertex.
//
// Per-thread scratch buffers grow to the largest shapes seen and are then reused: once warmed up, a
// query allocates nothing.

#include "shape_features.h"

#include "af/collision/manifold.h"

#include <cstdint>
#include <vector>

namespace af::collision_detail {

// Plain scalar dot product for the hot loops over vertices: Eigen's vectorised one costs several
// shuffles per 3-vector, about three times the arithmetic.
inline Real dot3(const Vec3& u, const Vec3& v) { return u.x() * v.x() + u.y() * v.y() + u.z() * v.z(); }

struct PlacedShape {
    const Polytope* polytope = nullptr;
    const ShapeFeatures* features = nullptr;
    Mat3 rotation = Mat3::Identity();  // own frame → working frame
    Vec3 translation = Vec3::Zero();

    int vertexCount() const { return int(polytope->vertices.size()); }
    int faceCount() const { return int(polytope->faces.size()); }
    bool hasFace(int f) const { return polytope->faces[f].normal.squaredNorm() > 0; }
    bool flat() const { return features->flat; }

    Vec3 vertex(int i) const { return rotation * polytope->vertices[i] + translation; }
    Vec3 normal(int f) const { return rotation * polytope->faces[f].normal; }
    // Plane offset of face f in the working frame, given its normal there.
    Real offset(int f, const Vec3& normalHere) const { return polytope->faces[f].offset + normalHere.dot(translation); }
    Vec3 toOwn(const Vec3& direction) const { return rotation.transpose() * direction; }
    Vec3 centre() const { return rotation * features->centre + translation; }
};

// Index of the vertex farthest along `dir` (working frame; lowest index on ties).
int supportIndex(const PlacedShape& shape, const Vec3& dir);
// max over the vertices of dir · vertex, in the working frame.
Real maxAlong(const PlacedShape& shape, const Vec3& dir);
// min and max of dir · vertex in one pass.
std::pair<Real, Real> interval(const PlacedShape& shape, const Vec3& dir);

// Separation of A and B along the unit `normal` pointing from B towards A:
// min over A of normal·a − max over B of normal·b; > 0 when this axis separates them.
Real separationAlong(const PlacedShape& a, const PlacedShape& b, const Vec3& normal);

// A contact point before reduction, in the working frame. Left uninitialised by default (always
// made with all three values), so that a query's array of them on the stack costs nothing to set up.
struct Candidate {
    Vec3 point;
    Real depth;
    std::uint32_t id;
};

// Per-thread buffers of one query.
struct Scratch {
    ShapeFeatures a, b;  // for polytopes that were not prepared
    std::vector<Candidate> candidates;
};
Scratch& scratch();

}  // namespace af::collision_detail
