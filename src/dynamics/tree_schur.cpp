// The auxiliary rows' paths through the tree and their Schur complement (tree_internal.h).

#include "tree_internal.h"

#include <algorithm>

namespace af::tree_detail {


// Row k's path is the union of its bodies' paths to their roots: walked up from the one or two
// body nodes, always from the smaller of the (at most two) current nodes, so the nodes come out
// in increasing order and two walks that meet become one.
void Auxiliary::findPaths(const Forest& forest, int nodes) {
    const std::size_t n = static_cast<std::size_t>(size_);
    pathBegin_.resize(n + 1);
    pathNode_.clear();
    for (std::size_t k = 0; k < n; ++k) {
        pathBegin_[k] = static_cast<int>(pathNode_.size());
        int current[2];
        int count = 0;
        for (const int node : {bodyNodes_[2 * k], bodyNodes_[2 * k + 1]})
            if (node >= 0 && (count == 0 || current[0] != node)) current[count++] = node;
        while (count > 0) {
            const int s = count == 2 && current[1] < current[0] ? 1 : 0;
            const int i = current[s];
            pathNode_.push_back(i);
            const int p = forest.nodes[static_cast<std::size_t>(i)].parent;
            if (p < 0 || (count == 2 && current[1 - s] == p)) {
                current[s] = current[count - 1];
                --count;
            } else {
                current[s] = p;
            }
        }
    }
    pathBegin_[n] = static_cast<int>(pathNode_.size());

    // Entries by node (a counting sort keeps rows in order within a node), and each entry's
    // successor: the same row at the parent node, which is on the path, further along it.
    const std::size_t entries = pathNode_.size();
    nodeBegin_.assign(static_cast<std::size_t>(nodes) + 1, 0);
    for (int node : pathNode_) ++nodeBegin_[static_cast<std::size_t>(node) + 1];
    for (int i = 0; i < nodes; ++i) nodeBegin_[static_cast<std::size_t>(i) + 1] += nodeBegin_[static_cast<std::size_t>(i)];
    cursor_.assign(nodeBegin_.begin(), nodeBegin_.end() - 1);
    entryRow_.resize(entries);
    entryUp_.resize(entries);
    pathEntry_.resize(entries);
    for (std::size_t k = 0; k < n; ++k)
        for (int f = pathBegin_[k]; f < pathBegin_[k + 1]; ++f) {
            const int node = pathNode_[static_cast<std::size_t>(f)];
            const int e = cursor_[static_cast<std::size_t>(node)]++;
            entryRow_[static_cast<std::size_t>(e)] = static_cast<int>(k);
            pathEntry_[static_cast<std::size_t>(f)] = e;
        }
    // A path holds the parent of each of its nodes but a root (the walks go up to the roots), and
    // a node's parent comes after it: read backwards, the parent's entry is already known.
    // cursor_, done with the counting sort, holds per node the current row's entry there.
    bodyEntry_.assign(2 * n, -1);
    cursor_.resize(static_cast<std::size_t>(nodes));
    for (std::size_t k = 0; k < n; ++k) {
        for (int f = pathBegin_[k + 1]; f-- > pathBegin_[k];) {
            const std::size_t node = static_cast<std::size_t>(pathNode_[static_cast<std::size_t>(f)]);
            const int e = pathEntry_[static_cast<std::size_t>(f)];
            const int p = forest.nodes[node].parent;
            entryUp_[static_cast<std::size_t>(e)] = p < 0 ? -1 : cursor_[static_cast<std::size_t>(p)];
            cursor_[node] = e;
        }
        for (std::size_t s = 2 * k; s < 2 * k + 2; ++s)
            if (bodyNodes_[s] >= 0) bodyEntry_[s] = cursor_[static_cast<std::size_t>(bodyNodes_[s])];
    }
}

void Auxiliary::build(const TreeFactor& factor, const Forest& forest, const ConstraintRows& rows,
                      std::span<const int> auxRows) {
    const std::size_t n = auxRows.size();
    const int nodes = factor.size();
    size_ = static_cast<int>(n);
    // The paths depend only on the rows' bodies, which rarely change from step to step.
    bool same = pathsKnown_ && bodyNodes_.size() == 2 * n && nodeBegin_.size() == static_cast<std::size_t>(nodes) + 1;
    bodyNodes_.resize(2 * n);
    for (std::size_t k = 0; k < n; ++k) {
        const ConstraintRow& row = rows[static_cast<std::size_t>(auxRows[k])];
        const int a = nodeOf(forest, row.bodyA);
        const int b = nodeOf(forest, row.bodyB);
        same = same && bodyNodes_[2 * k] == a && bodyNodes_[2 * k + 1] == b;
        bodyNodes_[2 * k] = a;
        bodyNodes_[2 * k + 1] = b;
    }
    if (!same) findPaths(forest, nodes);
    pathsKnown_ = true;

    // e_k at the row's body nodes.
    g_.assign(entryRow_.size(), Vec6::Zero());
    h_.resize(entryRow_.size());
    jacobian_.resize(2 * n);
    for (std::size_t k = 0; k < n; ++k) {
        const ConstraintRow& row = rows[static_cast<std::size_t>(auxRows[k])];
        jacobian_[2 * k] << row.linearA, row.angularA;
        jacobian_[2 * k + 1] << row.linearB, row.angularB;
        for (std::size_t s = 2 * k; s < 2 * k + 2; ++s)
            if (bodyEntry_[s] >= 0) g_[static_cast<std::size_t>(bodyEntry_[s])] += jacobian_[s];
    }

    // Leaves first: a node's g is complete once its children have passed theirs up (−F g).
    // A joint node has one child, its body below, and no row starts there, so its g is that
    // body's times −F: its share of S is folded into the body's, whose D⁻¹ becomes
    // W = D⁻¹ + Fᵀ D_joint⁻¹ F. Every pair of rows at a body then adds g·Wg to S's lower
    // triangle.
    s_.assign(n * n, 0);
    for (int i = 0; i < nodes; ++i) {
        const int begin = nodeBegin_[static_cast<std::size_t>(i)];
        const int end = nodeBegin_[static_cast<std::size_t>(i) + 1];
        if (begin == end) continue;
        const Mat6& f = factor.lower(i);
        const int p = factor.parent(i);
        if (forest.nodes[static_cast<std::size_t>(i)].joint >= 0) {
            if (p < 0) continue;
            withSize(factor.rows(i), [&](auto size) {
                constexpr int k = decltype(size)::value;
                for (int e = begin; e < end; ++e)
                    g_[static_cast<std::size_t>(entryUp_[static_cast<std::size_t>(e)])].noalias() -=
                        f.leftCols<k>() * g_[static_cast<std::size_t>(e)].head<k>();
            });
            continue;
        }
        Mat6 w = factor.inverseDiagonal(i);
        withSize(p >= 0 ? factor.rows(p) : 6, [&](auto size) {
            constexpr int k = decltype(size)::value;
            if (p >= 0) {
                const Eigen::Matrix<Real, k, 6> t = factor.inverseDiagonal(p).topLeftCorner<k, k>() * f.topRows<k>();
                w.noalias() += f.topRows<k>().transpose() * t;
            }
            for (int e = begin; e < end; ++e) {
                const Vec6& g = g_[static_cast<std::size_t>(e)];
                h_[static_cast<std::size_t>(e)].noalias() = w * g;
                if (const int up = entryUp_[static_cast<std::size_t>(e)]; up >= 0)
                    g_[static_cast<std::size_t>(up)].head<k>().noalias() -= f.topRows<k>() * g;
            }
        });
        for (int a = begin; a < end; ++a) {
            Real* out = s_.data() + static_cast<std::size_t>(entryRow_[static_cast<std::size_t>(a)]) * n;
            const Vec6& ga = g_[static_cast<std::size_t>(a)];
            for (int b = begin; b <= a; ++b) out[entryRow_[static_cast<std::size_t>(b)]] += ga.dot(h_[static_cast<std::size_t>(b)]);
        }
    }
    for (std::size_t l = 0; l < n; ++l)
        for (std::size_t k = 0; k < l; ++k) s_[k * n + l] = s_[l * n + k];
}

void Auxiliary::reduce(std::span<const Vec6> x0, std::span<const Real> b, std::span<Real> out) const {
    for (std::size_t k = 0; k < b.size(); ++k) {
        Real v = b[k];
        for (std::size_t s = 0; s < 2; ++s)
            if (const int node = bodyNodes_[2 * k + s]; node >= 0) v -= jacobian_[2 * k + s].dot(x0[static_cast<std::size_t>(node)]);
        out[k] = v;
    }
}

void Auxiliary::inject(std::span<const Real> lambda, std::span<Vec6> r) const {
    for (std::size_t k = 0; k < lambda.size(); ++k) {
        if (lambda[k] == 0) continue;
        for (std::size_t s = 0; s < 2; ++s)
            if (const int node = bodyNodes_[2 * k + s]; node >= 0) r[static_cast<std::size_t>(node)] += lambda[k] * jacobian_[2 * k + s];
    }
}

}  // namespace af::tree_detail
