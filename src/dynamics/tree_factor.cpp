// Block LDLᵀ of H = [M Jᵀ; J −C] over the forest of primary joints (tree_internal.h).
//
// With E_i the block of H coupling node i to its parent (a body's parent is a joint: E is the
// joint's Jacobian block of that body; a joint's parent is a body: E is that block transposed),
// eliminating leaves first gives
//     D_i ← D_i − Σ_children c  E_c D_c⁻¹ E_cᵀ,      F_i = E_i D_i⁻¹  (L's block below node i),
// and no other block changes, because a node meets the rest only through its parent. Body blocks
// stay positive definite (M plus the stiffness its subtrees add) and joint blocks negative
// definite (−C − J M̃⁻¹ Jᵀ), so both are inverted through an LDLᵀ factorisation.
//
// A joint of k rows only fills k rows or columns of its blocks, so the products are written for
// k (a template per size); the padding stays zero, and the solve passes use whole 6×6 blocks.

#include "tree_internal.h"

#include <Eigen/Cholesky>

namespace af::tree_detail {

namespace {

template <int M>
using Small = Eigen::Matrix<Real, M, M>;

// Sylvester's test (leading minors > 0) and the inverse by cofactors of a symmetric M×M matrix,
// M ≤ 3. Exactly symmetric. False if the matrix is not positive definite.
template <int M>
bool invertSmall(const Small<M>& a, Small<M>& inverse) {
    if constexpr (M == 1) {
        if (!(a(0, 0) > 0)) return false;
        inverse(0, 0) = 1 / a(0, 0);
    } else if constexpr (M == 2) {
        const Real det = a(0, 0) * a(1, 1) - a(0, 1) * a(0, 1);
        if (!(a(0, 0) > 0 && det > 0)) return false;
        const Real s = 1 / det;
        inverse << a(1, 1) * s, -a(0, 1) * s, -a(0, 1) * s, a(0, 0) * s;
    } else {
        const Real c00 = a(1, 1) * a(2, 2) - a(1, 2) * a(1, 2);
        const Real c01 = a(1, 2) * a(0, 2) - a(0, 1) * a(2, 2);
        const Real c02 = a(0, 1) * a(1, 2) - a(1, 1) * a(0, 2);
        const Real det = a(0, 0) * c00 + a(0, 1) * c01 + a(0, 2) * c02;
        if (!(a(0, 0) > 0 && a(0, 0) * a(1, 1) - a(0, 1) * a(0, 1) > 0 && det > 0)) return false;
        const Real s = 1 / det;
        const Real c11 = a(0, 0) * a(2, 2) - a(0, 2) * a(0, 2);
        const Real c12 = a(0, 1) * a(0, 2) - a(0, 0) * a(1, 2);
        const Real c22 = a(0, 0) * a(1, 1) - a(0, 1) * a(0, 1);
        inverse << c00 * s, c01 * s, c02 * s, c01 * s, c11 * s, c12 * s, c02 * s, c12 * s, c22 * s;
    }
    return true;
}

// The inverse of sign·A, A's top-left N×N block (its lower triangle is read), into the same
// block of `inverse`, times sign again: A⁻¹ for sign = ±1 when sign·A is positive definite.
// Past 3 rows by blocks: with sign·A = [P Q; Qᵀ R] (P 3×3), X = P⁻¹Q and the Schur complement
// T = R − QᵀX, the inverse is [P⁻¹ + X T⁻¹ Xᵀ, −X T⁻¹; −T⁻¹Xᵀ, T⁻¹], and sign·A is positive
// definite iff P and T are: short, independent small products instead of the long dependent
// chain of a Cholesky factorisation (and of Eigen's general triangular solves). Exactly
// symmetric. False if sign·A is not positive definite.
template <int N>
bool invertDefinite(const Mat6& a, Real sign, Mat6& inverse) {
    if constexpr (N <= 3) {
        Small<N> result;
        if (!invertSmall<N>(sign * Small<N>(a.topLeftCorner<N, N>().template selfadjointView<Eigen::Lower>()), result))
            return false;
        inverse.topLeftCorner<N, N>() = sign * result;
    } else {
        constexpr int M = N - 3;
        const Mat3 p = sign * Mat3(a.topLeftCorner<3, 3>().selfadjointView<Eigen::Lower>());
        const Small<M> r = sign * Small<M>(a.block<M, M>(3, 3).template selfadjointView<Eigen::Lower>());
        const Eigen::Matrix<Real, M, 3> qt = sign * a.block<M, 3>(3, 0);
        Mat3 pInverse;
        Small<M> tInverse;
        if (!invertSmall<3>(p, pInverse)) return false;
        // A leaf body's block is [m·1 0; 0 I]: with q exactly 0 the coupling terms below are
        // exact zeros and t is r, so skipping them gives the same values (bench single: a third
        // of the bodies, 0.14M of 218M instructions).
        if (qt.isZero(0)) {
            if (!invertSmall<M>(r, tInverse)) return false;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j <= i; ++j) inverse(i, j) = inverse(j, i) = sign * Real(0.5) * (pInverse(i, j) + pInverse(j, i));
            inverse.block<3, M>(0, 3).setZero();
            inverse.block<M, 3>(3, 0).setZero();
            inverse.block<M, M>(3, 3) = sign * tInverse;
            return true;
        }
        const Eigen::Matrix<Real, 3, M> x = pInverse * qt.transpose();
        const Small<M> t = r - qt * x;
        if (!invertSmall<M>(Real(0.5) * (t + t.transpose()), tInverse)) return false;
        const Eigen::Matrix<Real, 3, M> y = x * tInverse;
        const Mat3 top = pInverse + y * x.transpose();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j <= i; ++j) inverse(i, j) = inverse(j, i) = sign * Real(0.5) * (top(i, j) + top(j, i));
        inverse.block<3, M>(0, 3) = -sign * y;
        inverse.block<M, 3>(3, 0) = -sign * y.transpose();
        inverse.block<M, M>(3, 3) = sign * tInverse;
    }
    return true;
}

}  // namespace

// Only the blocks a node uses are written: a body's 6×6 D and D⁻¹, a joint's k×k; E and F of
// an edge in the joint's k rows (a body under a joint) or k columns (a joint under a body).
bool TreeFactor::factor(const Forest& forest, const ConstraintRows& rows, std::span<const JointRowRange> ranges,
                        std::span<const RigidBody> bodies) {
    const std::size_t n = forest.nodes.size();
    parent_.resize(n);
    size_.resize(n);
    edge_.resize(n);
    body_.resize(n);
    d_.resize(n);
    dinv_.resize(n);
    e_.resize(n);
    f_.resize(n);
    singular_ = 0;
    if (ranges.size() != forest.nodeOfJoint.size() || bodies.size() != forest.nodeOfBody.size()) return false;

    for (std::size_t i = 0; i < n; ++i) {
        const TreeNode& node = forest.nodes[i];
        parent_[i] = node.parent;
        body_[i] = node.body >= 0;
        if (node.body < 0) continue;
        const RigidBody& body = bodies[static_cast<std::size_t>(node.body)];
        size_[i] = 6;
        Mat6& d = d_[i];
        d.topLeftCorner<3, 3>() = Mat3::Identity() * body.mass();
        d.topRightCorner<3, 3>().setZero();
        d.bottomLeftCorner<3, 3>().setZero();
        d.bottomRightCorner<3, 3>() = body.inertiaWorld();
    }

    // Joint nodes: −C on the diagonal, and the Jacobian blocks into the edges to their bodies.
    for (std::size_t i = 0; i < n; ++i) {
        const TreeNode& node = forest.nodes[i];
        if (node.joint < 0) continue;
        const JointRowRange& range = ranges[static_cast<std::size_t>(node.joint)];
        const int k = range.equalityRows;
        if (k < 1 || k > 6 || range.first < 0 || static_cast<std::size_t>(range.first + k) > rows.size()) return false;
        size_[i] = k;
        edge_[i] = k;
        Mat6& toParent = e_[i];  // the parent body's block, transposed: columns q < k
        Mat6* toChild = nullptr;  // the child body's block: rows q < k
        for (const int side : {node.sideA, node.sideB})
            if (side >= 0 && side != node.parent) {
                toChild = &e_[static_cast<std::size_t>(side)];
                edge_[static_cast<std::size_t>(side)] = k;
            }
        Mat6& d = d_[i];
        d.setZero();
        for (int q = 0; q < k; ++q) {
            const ConstraintRow& row = rows[static_cast<std::size_t>(range.first + q)];
            if (nodeOf(forest, row.bodyA) != node.sideA || nodeOf(forest, row.bodyB) != node.sideB) return false;
            d(q, q) = -row.cfm;
            for (int s = 0; s < 2; ++s) {
                const int side = s == 0 ? node.sideA : node.sideB;
                if (side < 0) continue;
                const Vec3& linear = s == 0 ? row.linearA : row.linearB;
                const Vec3& angular = s == 0 ? row.angularA : row.angularB;
                if (side == node.parent) {
                    toParent.col(q) << linear, angular;
                } else {
                    toChild->row(q) << linear.transpose(), angular.transpose();
                }
            }
        }
    }

    for (std::size_t i = 0; i < n; ++i) {
        invert(static_cast<int>(i));
        const int p = parent_[i];
        if (p < 0) continue;
        Mat6& up = d_[static_cast<std::size_t>(p)];
        const Mat6& e = e_[i];
        Mat6& f = f_[i];
        withSize(edge_[i], [&](auto size) {
            constexpr int k = decltype(size)::value;
            if (body_[i]) {
                f.topRows<k>().noalias() = e.topRows<k>() * dinv_[i];
                up.topLeftCorner<k, k>().noalias() -= f.topRows<k>() * e.topRows<k>().transpose();
            } else {
                f.leftCols<k>().noalias() = e.leftCols<k>() * dinv_[i].topLeftCorner<k, k>();
                // invert reads only the lower triangle of a body's block, so most of the top right
                // 3×3 is skipped; rows 2-5 keep Eigen's two-row packets, and so the same sums.
                up.leftCols<3>().noalias() -= f.leftCols<k>() * e.leftCols<k>().template topRows<3>().transpose();
                up.block<4, 3>(2, 3).noalias() -=
                    f.leftCols<k>().template middleRows<4>(2) * e.leftCols<k>().template bottomRows<3>().transpose();
            }
        });
    }
    return true;
}

// Body blocks are positive definite, joint blocks negative definite.
void TreeFactor::invert(int node) {
    const std::size_t i = static_cast<std::size_t>(node);
    const int k = size_[i];
    const Real sign = body_[i] ? 1 : -1;
    bool ok = true;
    withSize(k, [&](auto size) { ok = invertDefinite<decltype(size)::value>(d_[i], sign, dinv_[i]); });
    if (ok) return;
    // Dependent rows without CFM: LDLᵀ with pivoting drops the zero pivots (a pseudo-inverse of
    // sorts); the solve carries on, as Doom's does, and reports it.
    ++singular_;
    using Block = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;  // no heap
    const Block block = d_[i].topLeftCorner(k, k).selfadjointView<Eigen::Lower>();
    const Block pseudo = Eigen::LDLT<Block>(block).solve(Block::Identity(k, k));
    dinv_[i].topLeftCorner(k, k) = Real(0.5) * (pseudo + pseudo.transpose());
}

void TreeFactor::forward(std::span<Vec6> z) const {
    const std::size_t n = parent_.size();
    for (std::size_t i = 0; i < n; ++i) {
        const int p = parent_[i];
        if (p < 0) continue;
        Vec6& up = z[static_cast<std::size_t>(p)];
        withSize(edge_[i], [&](auto size) {
            constexpr int k = decltype(size)::value;
            if (body_[i]) {
                up.head<k>().noalias() -= f_[i].topRows<k>() * z[i];
            } else {
                up.noalias() -= f_[i].leftCols<k>() * z[i].head<k>();
            }
        });
    }
}

void TreeFactor::backward(std::span<const Vec6> z, std::span<Vec6> x) const {
    for (std::size_t i = parent_.size(); i-- > 0;) {
        const int p = parent_[i];
        if (body_[i]) {
            x[i].noalias() = dinv_[i] * z[i];
            if (p < 0) continue;
            withSize(edge_[i], [&](auto size) {
                constexpr int k = decltype(size)::value;
                x[i].noalias() -= f_[i].topRows<k>().transpose() * x[static_cast<std::size_t>(p)].head<k>();
            });
        } else {
            withSize(size_[i], [&](auto size) {
                constexpr int k = decltype(size)::value;
                x[i].head<k>().noalias() = dinv_[i].topLeftCorner<k, k>() * z[i].head<k>();
                if (p >= 0) x[i].head<k>().noalias() -= f_[i].leftCols<k>().transpose() * x[static_cast<std::size_t>(p)];
                x[i].tail<6 - k>().setZero();
            });
        }
    }
}

}  // namespace af::tree_detail
