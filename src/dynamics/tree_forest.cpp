// Choosing the primary joints (a spanning forest over the bodies, the world one part) and
// numbering the nodes of each tree so that every node comes after its descendants.

#include "tree_internal.h"

#include <numeric>
#include <stdexcept>

namespace af::tree_detail {

namespace {

class Parts {
public:
    explicit Parts(int count) : parent_(static_cast<std::size_t>(count)) {
        std::iota(parent_.begin(), parent_.end(), 0);
    }
    int find(int v) {
        while (parent_[static_cast<std::size_t>(v)] != v) {
            int& p = parent_[static_cast<std::size_t>(v)];
            p = parent_[static_cast<std::size_t>(p)];
            v = p;
        }
        return v;
    }
    // Joins the parts of a and b; false if they were one part already.
    bool join(int a, int b) {
        a = find(a);
        b = find(b);
        if (a == b) return false;
        parent_[static_cast<std::size_t>(a)] = b;
        return true;
    }

private:
    std::vector<int> parent_;
};

// The graph of H: vertices 0..bodies−1 are bodies, bodies + k is joint k; edges join a primary
// joint to each of its dynamic bodies. Per-vertex scratch of rootOf, left clear after each use
// so the whole forest costs time linear in its size.
struct Graph {
    std::vector<std::vector<int>> adjacent;
    std::vector<int> degree;
    std::vector<std::uint8_t> seen, removed;
    std::vector<int> component, layer, next;
};

// The root of the tree holding `start`. A joint node must be eliminated after one of its bodies:
// eliminated first, its block would be −C alone, and the body would get the joint's stiffness
// 1/C (a penalty that swamps its mass in rounding). A joint to the world has only one body, so
// it becomes the root. A tree without one is rooted at its centre, found by peeling leaves
// layer by layer until at most two vertices are left (if the centre is a joint, one of its
// bodies).
int rootOf(Graph& g, int start, int bodyCount) {
    auto at = [](auto& v, int i) -> auto& { return v[static_cast<std::size_t>(i)]; };
    std::vector<int>& component = g.component;
    component.assign(1, start);
    at(g.seen, start) = 1;
    for (std::size_t k = 0; k < component.size(); ++k)
        for (int u : at(g.adjacent, component[k]))
            if (!at(g.seen, u)) {
                at(g.seen, u) = 1;
                component.push_back(u);
            }

    int root = -1;
    for (int v : component)
        if (v >= bodyCount && at(g.adjacent, v).size() == 1) root = v;
    if (root < 0) {
        g.layer.clear();
        for (int v : component) {
            at(g.degree, v) = static_cast<int>(at(g.adjacent, v).size());
            if (at(g.degree, v) <= 1) g.layer.push_back(v);
        }
        std::size_t remaining = component.size();
        while (remaining > 2) {
            g.next.clear();
            for (int v : g.layer) {
                at(g.removed, v) = 1;
                --remaining;
                for (int u : at(g.adjacent, v))
                    if (!at(g.removed, u) && --at(g.degree, u) == 1) g.next.push_back(u);
            }
            g.layer.swap(g.next);
        }
        for (int v : component)
            if (!at(g.removed, v) && root < 0)
                root = v < bodyCount ? v : at(g.adjacent, v).front();
    }
    for (int v : component) at(g.seen, v) = at(g.removed, v) = 0;
    return root;
}

}  // namespace

Forest buildForest(std::span<const RigidBody> bodies, std::span<const Joint> joints) {
    const int bodyCount = static_cast<int>(bodies.size());
    const int jointCount = static_cast<int>(joints.size());
    const int world = bodyCount;
    auto part = [&](int body) {
        if (body == kWorldBody) return world;
        if (body < 0 || body >= bodyCount) throw std::invalid_argument("tree solver: joint body index out of range");
        return bodies[static_cast<std::size_t>(body)].inverseMass > 0 ? body : world;
    };

    Forest forest;
    forest.primary.assign(static_cast<std::size_t>(jointCount), 0);
    Parts parts(bodyCount + 1);
    Graph graph;
    const std::size_t vertices = static_cast<std::size_t>(bodyCount + jointCount);
    graph.adjacent.resize(vertices);
    graph.degree.assign(vertices, 0);
    graph.seen.assign(vertices, 0);
    graph.removed.assign(vertices, 0);
    for (int k = 0; k < jointCount; ++k) {
        const Joint& joint = joints[static_cast<std::size_t>(k)];
        const int a = part(joint.bodyA);
        const int b = part(joint.bodyB);
        if (joint.type == ConstraintType::Spring || a == b || !parts.join(a, b)) continue;
        forest.primary[static_cast<std::size_t>(k)] = 1;
        for (int side : {a, b})
            if (side != world) {
                graph.adjacent[static_cast<std::size_t>(bodyCount + k)].push_back(side);
                graph.adjacent[static_cast<std::size_t>(side)].push_back(bodyCount + k);
            }
    }

    // Breadth first from each tree's root; reversed, that order puts descendants first.
    std::vector<int> vertexNode(vertices, -1);
    std::vector<int> vertexParent(vertices, -1);
    std::vector<int> order;
    for (int body = 0; body < bodyCount; ++body) {
        if (part(body) == world || vertexParent[static_cast<std::size_t>(body)] != -1) continue;
        const int root = rootOf(graph, body, bodyCount);
        const std::size_t begin = order.size();
        order.push_back(root);
        vertexParent[static_cast<std::size_t>(root)] = root;
        for (std::size_t k = begin; k < order.size(); ++k) {
            const int v = order[k];
            for (int u : graph.adjacent[static_cast<std::size_t>(v)])
                if (vertexParent[static_cast<std::size_t>(u)] == -1) {
                    vertexParent[static_cast<std::size_t>(u)] = v;
                    order.push_back(u);
                }
        }
        vertexParent[static_cast<std::size_t>(root)] = -2;  // a root; −1 means unvisited
    }

    const int nodeCount = static_cast<int>(order.size());
    forest.nodes.resize(order.size());
    for (int k = 0; k < nodeCount; ++k) vertexNode[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])] = nodeCount - 1 - k;
    forest.nodeOfBody.assign(static_cast<std::size_t>(bodyCount), -1);
    forest.nodeOfJoint.assign(static_cast<std::size_t>(jointCount), -1);
    for (int v : order) {
        TreeNode& node = forest.nodes[static_cast<std::size_t>(vertexNode[static_cast<std::size_t>(v)])];
        const int up = vertexParent[static_cast<std::size_t>(v)];
        node.parent = up >= 0 ? vertexNode[static_cast<std::size_t>(up)] : -1;
        if (v < bodyCount) {
            node.body = v;
            forest.nodeOfBody[static_cast<std::size_t>(v)] = vertexNode[static_cast<std::size_t>(v)];
        } else {
            node.joint = v - bodyCount;
            forest.nodeOfJoint[static_cast<std::size_t>(node.joint)] = vertexNode[static_cast<std::size_t>(v)];
        }
    }
    // A joint node's bodies, as nodes (−1 for the world or a static body), to check its rows.
    for (TreeNode& node : forest.nodes) {
        if (node.joint < 0) continue;
        const Joint& joint = joints[static_cast<std::size_t>(node.joint)];
        node.sideA = part(joint.bodyA) == world ? -1 : forest.nodeOfBody[static_cast<std::size_t>(joint.bodyA)];
        node.sideB = part(joint.bodyB) == world ? -1 : forest.nodeOfBody[static_cast<std::size_t>(joint.bodyB)];
    }
    return forest;
}

}  // namespace af::tree_detail
