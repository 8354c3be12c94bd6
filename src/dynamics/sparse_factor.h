#pragma once
// A sparse LDLᵀ factorisation of A = J M⁻¹ Jᵀ + diag(cfm) restricted to a chosen set of rows (the
// "free" rows), the matrix that every trial of the sparse active-set solve (sparse_lcp.h) needs.
//
// Rows are grouped by the pair of bodies they join (the world and static bodies count as no
// body), and two groups couple only through a body they share. A figure's joints form a tree and
// rows to the world (ground contacts) hang off single bodies, so eliminating the groups leaf first
// creates no fill: the factorisation costs time linear in the number of bodies, with dense work
// only in the small blocks of rows that meet at one body. Loops (a hand resting on a thigh, two
// figures touching twice) are handled by a minimum-fill order and its fill. Only groups with free
// rows take part in the order: a contact that touches without pushing couples nothing, and
// leaving it in would close loops that are not there (a resting ragdoll's arm lying on its
// thigh: 36 groups, of which 14 have no free row).
//
// With CFM > 0 on every row (or independent rows) A is symmetric positive definite, so LDLᵀ
// without pivoting is stable in any elimination order. A pivot that is not clearly positive (rows
// that depend on each other and carry no CFM) makes factor() fail rather than give garbage; the
// pivoting solver handles those.
//
// The grouping (analyse) depends only on which bodies the rows join, the order also on which
// groups have free rows; each is redone only when that changes, and both keep their buffers'
// capacity, so a step allocates nothing once the largest structure has been seen.

#include "af/dynamics/rigid_body.h"
#include "constraint_row.h"
#include "row_system.h"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace af {

class SparseRowFactor {
public:
    // Groups the rows and orders the groups. False (and the factor unusable) for a row that joins
    // a body to itself or names a body out of range.
    bool analyse(std::span<const ConstraintRow> rows, std::span<const RigidBody> bodies);
    // Whether the last analyse() met the body pairs of the one before, in the same order: a
    // factorisation made since that one still has the rows' places.
    bool structureKept() const { return structureKept_; }
    // Factorises A restricted to the rows with free[i] != 0 (rows as given to analyse, with their
    // responses M⁻¹Jᵀ and CFM). False if a pivot is not clearly positive.
    bool factor(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                std::span<const Real> cfm, std::span<const std::uint8_t> free);
    // Solves A_FF y = x for the free rows in place: x holds the right-hand side at the free rows'
    // indices on entry and y there on return; other entries are left alone.
    void solve(std::span<Real> x) const;

    // Entries the factor holds (L and D, fill included): its size, which the order keeps small.
    std::size_t entries() const { return values_.size(); }

    // Sparse pieces of A_FF⁻¹ = L⁻ᵀ D⁻¹ L⁻¹ for a few entries of it (sliding friction, see
    // sparse_lcp.cpp), in the factor's own numbering of the free rows ("variables"). A vector there
    // comes with a flag per group saying where it may be non-zero; the solves touch only those
    // groups and the groups they pass into, the path to the root of the elimination tree.
    int variables() const { return varStart_.empty() ? 0 : varStart_.back(); }
    int groups() const { return static_cast<int>(groupKeys_.size()); }
    // The first variable of group g (groups are numbered in elimination order, so a vector
    // forwarded from group g is zero before it).
    int firstVariable(int g) const { return varStart_[static_cast<std::size_t>(g)]; }
    // Row i's variable, or −1 if it is not free.
    int variableOf(int row) const;
    // The column A_F,row of a row (free or not) into y (zeroed first), flagging its groups.
    void column(int row, std::span<const ConstraintRow> rows, std::span<const RowResponse> responses,
                std::span<Real> y, std::span<std::uint8_t> active) const;
    // Unit vector of a free row's variable into y (zeroed first), flagging its group.
    void unit(int row, std::span<Real> y, std::span<std::uint8_t> active) const;
    // y ← L⁻¹ y over the flagged groups, flagging those it reaches.
    void forward(std::span<Real> y, std::span<std::uint8_t> active) const;
    // x_F ← L⁻ᵀ z for z in the factor's numbering: A_FF⁻¹ r when z = D⁻¹ L⁻¹ r, a right-hand side
    // already forwarded and scaled (other entries of x are left alone).
    void solveForwarded(std::span<const Real> z, std::span<Real> x) const;
    // D⁻¹ per variable.
    void inversePivots(std::span<Real> out) const;
    // The flagged groups that hold variables, ascending, appended to out: where a forwarded
    // vector may be non-zero, as a list (a path to the root is a few groups of many).
    void support(std::span<const std::uint8_t> active, std::vector<int>& out) const;
    // uᵀ D⁻¹ v over the groups in both supports (lists from support()).
    Real scaledDot(std::span<const Real> u, std::span<const int> uGroups, std::span<const Real> v,
                   std::span<const int> vGroups) const;

private:
    bool sameBodies(std::span<const ConstraintRow> rows, std::span<const RigidBody> bodies) const;
    void rememberBodies(std::span<const ConstraintRow> rows, std::span<const RigidBody> bodies);
    void connect();
    void order(const std::vector<std::uint8_t>& active);
    void arrange();
    int frontSlot(int column, int group) const;
    void assemble(std::span<const ConstraintRow> rows, std::span<const RowResponse> responses, std::span<const Real> cfm);
    bool eliminate(int group);
    void backward() const;

    // Structure (analyse): the distinct body pairs, ascending (sortedKeys_), each row's pair and
    // the pairs' graph. Order (factor, when the pairs with free rows change): groups numbered in
    // elimination order; positionOf_ maps a pair to its group.
    std::vector<std::uint64_t> rowKey_, groupKeys_, sortedKeys_, scratchKeys_;
    std::vector<int> pairOfRow_, positionOf_, groupOfRow_;
    std::vector<std::uint8_t> active_, orderedFor_;  // pairs with free rows: now, and as ordered
    std::vector<int> rowStart_, groupRows_;  // rows of each group, ascending
    std::vector<int> frontStart_, front_;    // later groups coupled to each group, fill included, ascending
    std::vector<int> bodyStart_, bodyRows_;  // rows touching each dynamic body, ascending
    std::vector<int> fill_;                  // scratch
    bool analysed_ = false;                  // rowKey_ and what follows from it are valid
    bool structureKept_ = false;             // see structureKept()
    std::vector<int> rowBodies_;             // bodyA, bodyB of each row at the last analyse()
    std::vector<std::uint8_t> dynamicBodies_;  // and which bodies were dynamic then
    std::vector<std::uint64_t> graph_;       // bit matrix of the pairs sharing a body
    std::size_t words_ = 0;                  // 64-bit words per row of graph_
    std::vector<std::uint64_t> adjacency_, remaining_;  // scratch: graph with fill, pairs left
    std::vector<std::uint64_t> recount_;                // scratch: pairs whose counts order() redoes
    std::vector<std::size_t> missingOf_, degreeOf_;     // order(): each pair's missing links, neighbours

    // Values (factor): per group, its free rows; per group a column panel holding its diagonal
    // block (L below the unit diagonal, D on it) above the blocks of its front groups.
    std::vector<int> size_, local_, varStart_, rowOfVariable_;
    std::vector<int> panelStart_, panelHeight_, blockOffset_;
    std::vector<int> belowStart_, belowVariable_;  // per group: the variable of each panel row below its block
    std::vector<Real> values_, diagonal_;
    std::vector<Real> pivots_;  // D per variable, contiguous (scaledDot)
    std::vector<Real> scaled_, update_;  // scratch of eliminate()
    struct Packed {                      // a free row on one body (assemble)
        Real jacobian[6], response[6];
        int group, local;
    };
    std::vector<Packed> packed_;  // diagonal_: each free row's own A_rr, for the pivot test
    std::vector<std::pair<std::uint64_t, int>> packOrder_;  // assemble(): (group, local) and row
    mutable std::vector<Real> work_;
};

}  // namespace af
