#pragma once
// Inside the tree solver (tree_solver.h): the forest of primary joints, and its
// block LDLᵀ factorisation after Baraff, "Linear-Time Dynamics using Lagrange Multipliers"
// (SIGGRAPH 1996).
//
// The primary rows are solved through the sparse symmetric system
//     H [y; μ] = [f; b],   H = [ M   Jᵀ ]
//                              [ J  −C  ]
// with M the bodies' 6×6 mass matrices, J the primary rows, C their CFM. Eliminating y gives
// (J M⁻¹ Jᵀ + C) λ = b − J M⁻¹ f with λ = −μ, and y = M⁻¹ (f + Jᵀ λ) is the velocity change:
// exactly the dense rows' system. H's graph has one node per body (a 6×6 block) and one per
// primary joint (a k×k block, k ≤ 6 equality rows); an edge joins a joint and each of its
// bodies. Primary joints form a forest, so eliminating nodes leaves first creates no fill-in:
// O(nodes) 6×6 block operations.
//
// Every block lives in fixed 6×6 storage, so one contiguous array serves every node; a joint
// of k rows uses its k×k part (and k rows or columns of its edges), through code instantiated
// for each k (withSize). Node vectors are 6 long; a joint's entries past k are 0.

#include "af/dynamics/rigid_body.h"
#include "constraint_row.h"
#include "joint_rows.h"

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace af::tree_detail {

// Node vectors and blocks; a body's are [linear; angular], as a row's coupling to it.
using Vec6 = Eigen::Matrix<Real, 6, 1>;
using Mat6 = Eigen::Matrix<Real, 6, 6>;

struct TreeNode {
    int parent = -1;  // node index, −1 for a root; always greater than the node's own index
    int body = -1;    // a body node: its body index, else −1
    int joint = -1;   // a joint node: its joint index, else −1
    int sideA = -1;   // a joint node: the nodes of its bodies A and B (−1: world or static)
    int sideB = -1;
};

// Primary joints and the elimination order. Nodes are numbered so that every node comes after
// all of its descendants (leaves first). A tree is rooted at its joint to the world if it has
// one (a joint node must have a body below it, see tree_forest.cpp), else at a body near its
// centre, which keeps the paths to the root, and so the Schur complement's work, short.
struct Forest {
    std::vector<std::uint8_t> primary;  // per joint
    std::vector<TreeNode> nodes;
    std::vector<int> nodeOfBody;        // −1 for a static body (it acts as the world)
    std::vector<int> nodeOfJoint;       // −1 for an auxiliary joint
};

Forest buildForest(std::span<const RigidBody> bodies, std::span<const Joint> joints);

// The node of a body, −1 for the world (and a static body).
inline int nodeOf(const Forest& forest, int body) {
    return body == kWorldBody ? -1 : forest.nodeOfBody[static_cast<std::size_t>(body)];
}

// The factorisation H = L D Lᵀ: per node D⁻¹ and F = E D⁻¹, with E the block coupling the node
// to its parent (L's block below the diagonal). Node vectors are Vec6 per node.
class TreeFactor {
public:
    // Builds H from the bodies' inertia and the primary joints' equality rows, and factorises.
    // Returns false if the rows do not fit the forest (wrong bodies, more than 6 equality rows).
    // A block that is not definite (dependent rows without CFM) is inverted as well as it can be
    // and counted in singularBlocks().
    bool factor(const Forest& forest, const ConstraintRows& rows, std::span<const JointRowRange> ranges,
                std::span<const RigidBody> bodies);

    // In place: z ← L⁻¹ z (leaves to roots).
    void forward(std::span<Vec6> z) const;
    // x ← L⁻ᵀ D⁻¹ z (roots to leaves); z is left unchanged.
    void backward(std::span<const Vec6> z, std::span<Vec6> x) const;

    int size() const { return static_cast<int>(parent_.size()); }
    int parent(int node) const { return parent_[static_cast<std::size_t>(node)]; }
    int rows(int node) const { return size_[static_cast<std::size_t>(node)]; }  // 6 for a body
    // D⁻¹ of a node, in its rows() × rows() block; F of its edge to the parent, in the joint's k
    // rows (a body under a joint) or k columns (a joint under a body). Other entries are unused.
    const Mat6& inverseDiagonal(int node) const { return dinv_[static_cast<std::size_t>(node)]; }
    const Mat6& lower(int node) const { return f_[static_cast<std::size_t>(node)]; }
    int singularBlocks() const { return singular_; }

private:
    void invert(int node);

    std::vector<int> parent_;
    std::vector<int> size_;            // rows of the node: 6 for a body, k for a joint
    std::vector<int> edge_;            // rows of the joint on the edge to the parent
    std::vector<std::uint8_t> body_;
    std::vector<Mat6> d_, dinv_, e_, f_;
    int singular_ = 0;
};

// The auxiliary rows seen through the factorised tree. With e_k the body vector of auxiliary
// row k (its Jacobian blocks at its bodies' nodes, zero elsewhere), the Schur complement of the
// primary rows in the whole system is
//     S_lk = e_lᵀ H⁻¹ e_k = (L⁻¹e_l)ᵀ D⁻¹ (L⁻¹e_k) = Σ_nodes g_l · h_k,   g = L⁻¹e, h = D⁻¹g,
// which is A_XX − A_XP (A_PP + C_P)⁻¹ A_PX (the rows' own J M⁻¹ Jᵀ included, their CFM not).
// g_k is zero off the paths from row k's bodies to their roots, so each row costs the forward
// half of one linear solve along its path, and S_lk sums over the nodes the two paths share.
// The work runs node by node, leaves first, over every row that passes the node (tree_schur.cpp).
class Auxiliary {
public:
    // The paths of rows[auxRows[k]] and S.
    void build(const TreeFactor& factor, const Forest& forest, const ConstraintRows& rows, std::span<const int> auxRows);

    int size() const { return size_; }
    // The next build finds the paths again (the forest changed).
    void forgetPaths() { pathsKnown_ = false; }
    // S, size()² values, row-major, exactly symmetric.
    std::span<const Real> schur() const { return s_; }
    // out_k = b_k − e_kᵀ x0 with x0 = H⁻¹[0; b_P] (at the body nodes: the velocity change the
    // primary rows alone make): the right-hand side left for the auxiliary rows.
    void reduce(std::span<const Vec6> x0, std::span<const Real> b, std::span<Real> out) const;
    // r += Σ_k λ_k e_k: the auxiliary impulses as node vectors of H's right-hand side.
    void inject(std::span<const Real> lambda, std::span<Vec6> r) const;

private:
    void findPaths(const Forest& forest, int nodes);

    int size_ = 0;
    // Entries: one per row and node of its path, grouped by node (rows in order within a node).
    std::vector<int> nodeBegin_;  // node i's entries are [nodeBegin_[i], nodeBegin_[i+1])
    std::vector<int> entryRow_;
    std::vector<int> entryUp_;    // the same row's entry at the parent node, −1 at a root
    std::vector<Vec6> g_, h_;
    // Paths row by row while they are found: node, then its entry.
    std::vector<int> pathBegin_, pathNode_, pathEntry_, cursor_;
    std::vector<int> bodyNodes_;   // per row: its bodies' nodes, what the paths were found for
    std::vector<int> bodyEntry_;   // per row: the entries at those nodes (−1: the world)
    std::vector<Vec6> jacobian_;   // per row: e_k at those nodes
    bool pathsKnown_ = false;
    std::vector<Real> s_;
};

// Calls f(std::integral_constant<int, k>) for k in 1..6: blocks of k rows as fixed-size code.
template <class F>
void withSize(int k, F&& f) {
    switch (k) {
    case 1: f(std::integral_constant<int, 1>{}); break;
    case 2: f(std::integral_constant<int, 2>{}); break;
    case 3: f(std::integral_constant<int, 3>{}); break;
    case 4: f(std::integral_constant<int, 4>{}); break;
    case 5: f(std::integral_constant<int, 5>{}); break;
    default: f(std::integral_constant<int, 6>{}); break;
    }
}

}  // namespace af::tree_detail
