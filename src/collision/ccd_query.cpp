#include "ccd_query.h"

#include <ccd/ccd.h>

#include <cmath>

namespace af::collision_detail {

namespace {

struct CcdShape {
    const PlacedShape* shape;
    Real inflation;
};

Vec3 toVec3(const ccd_vec3_t& v) { return {v.v[0], v.v[1], v.v[2]}; }

void toCcd(const Vec3& v, ccd_vec3_t* out) {
    out->v[0] = v.x();
    out->v[1] = v.y();
    out->v[2] = v.z();
}

void supportOf(const void* object, const ccd_vec3_t* dir, ccd_vec3_t* out) {
    const CcdShape& s = *static_cast<const CcdShape*>(object);
    const Vec3 d = toVec3(*dir);
    Vec3 p = s.shape->vertex(supportIndex(*s.shape, d));
    const Real len = d.norm();
    if (s.inflation > 0 && len > 0) {
        p += (s.inflation / len) * d;
    }
    toCcd(p, out);
}

void centreOf(const void* object, ccd_vec3_t* out) {
    toCcd(static_cast<const CcdShape*>(object)->shape->centre(), out);
}

// libccd's direction moves its second object (B) out of the first (A): from A towards B.
bool usableDirection(const ccd_vec3_t& dir, Vec3& normal) {
    const Vec3 d = toVec3(dir);
    const Real len = d.norm();
    if (!std::isfinite(len) || len == 0) {
        return false;
    }
    normal = -d / len;
    return true;
}

}  // namespace

CcdResult ccdPenetration(const PlacedShape& a, const PlacedShape& b, Real inflation) {
    const CcdShape shapeA{&a, inflation};
    const CcdShape shapeB{&b, 0};
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = supportOf;
    ccd.support2 = supportOf;
    ccd.center1 = centreOf;
    ccd.center2 = centreOf;
    ccd.max_iterations = 100;  // both converge in far fewer on polytopes; never loop forever

    CcdResult result;
    ccd_real_t depth = 0;
    ccd_vec3_t dir, pos;
    if (ccdMPRPenetration(&shapeA, &shapeB, &ccd, &depth, &dir, &pos) != 0) {
        return result;
    }
    result.intersecting = true;
    if (usableDirection(dir, result.normal)) {
        return result;
    }
    if (ccdGJKPenetration(&shapeA, &shapeB, &ccd, &depth, &dir, &pos) == 0 &&
        usableDirection(dir, result.normal)) {
        return result;
    }
    const Vec3 centreLine = a.centre() - b.centre();
    result.normal = centreLine.norm() > 0 ? Vec3(centreLine.normalized()) : Vec3(Vec3::UnitZ());
    return result;
}

}  // namespace af::collision_detail
