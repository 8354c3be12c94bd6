#include "depth_order.h"

#include <algorithm>
#include <limits>

namespace af::render::detail {
namespace {

Vec3 centroid(const Polytope& p) {
    Vec3 sum = Vec3::Zero();
    for (const Vec3& v : p.vertices) sum += v;
    return p.vertices.empty() ? sum : Vec3(sum / static_cast<double>(p.vertices.size()));
}

double extent(const Polytope& p) {
    if (p.vertices.empty()) return 0;
    Vec3 lo = p.vertices.front(), hi = lo;
    for (const Vec3& v : p.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    return (hi - lo).norm();
}

// +1 when a face plane of `a` has all of `b` outside it with the eye on b's side (a is behind),
// -1 when such a plane has the eye on a's side (a is in front), 0 when no face of a separates.
int orderByPlanesOf(const Polytope& a, const Polytope& b, const Vec3& eye, double tolerance) {
    for (const Face& f : a.faces) {
        if (f.normal.squaredNorm() < 0.5) continue;  // a degenerate face has no plane
        bool separates = true;
        for (const Vec3& v : b.vertices) {
            if (f.normal.dot(v) - f.offset < -tolerance) {
                separates = false;
                break;
            }
        }
        if (separates) return f.normal.dot(eye) - f.offset >= 0 ? +1 : -1;
    }
    return 0;
}

}  // namespace

std::vector<int> depthOrder(const std::vector<DepthItem>& items, const Vec3& eye) {
    const int n = static_cast<int>(items.size());
    std::vector<double> distance(n);
    std::vector<double> size(n);
    for (int i = 0; i < n; ++i) {
        distance[i] = (centroid(*items[i].shape) - eye).norm();
        size[i] = extent(*items[i].shape);
    }
    // before[i][j]: i must be drawn before j.
    std::vector<std::vector<char>> before(n, std::vector<char>(n, 0));
    for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) {
            if (!items[i].screenBox.intersects(items[j].screenBox)) continue;
            // Resting contact leaves slight penetration; a plane still separates within this.
            const double tolerance = 1e-3 + 0.02 * std::min(size[i], size[j]);
            int order = orderByPlanesOf(*items[i].shape, *items[j].shape, eye, tolerance);
            if (order == 0) order = -orderByPlanesOf(*items[j].shape, *items[i].shape, eye, tolerance);
            if (order == 0) order = distance[i] >= distance[j] ? +1 : -1;
            (order > 0 ? before[i][j] : before[j][i]) = 1;
        }
    }
    std::vector<int> pending(n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) pending[j] += before[i][j];
    std::vector<char> done(n, 0);
    std::vector<int> order;
    order.reserve(n);
    while (static_cast<int>(order.size()) < n) {
        // The farthest object that waits for nothing; in a cycle, the farthest of all left.
        int pick = -1;
        for (int i = 0; i < n; ++i) {
            if (done[i] || pending[i] > 0) continue;
            if (pick < 0 || distance[i] > distance[pick]) pick = i;
        }
        if (pick < 0) {
            for (int i = 0; i < n; ++i)
                if (!done[i] && (pick < 0 || distance[i] > distance[pick])) pick = i;
        }
        done[pick] = 1;
        order.push_back(pick);
        for (int j = 0; j < n; ++j)
            if (before[pick][j]) --pending[j];
    }
    return order;
}

}  // namespace af::render::detail
