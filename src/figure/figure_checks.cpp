// Warnings about figures that tend to misbehave (docs/doom-quirks.md items 1–2, from
// iddevnet's advice): very different masses across a joint, lopsided inertia, jointed bodies that start
// inside each other, and bodies that are not all joined into one tree.

#include "af/geometry/mass_properties.h"
#include "figure_build_context.h"

#include <algorithm>
#include <cstdio>
#include <numeric>

namespace af {

namespace {

constexpr Real kMaxMassRatio = 20;
constexpr Real kMaxInertiaRatio = 20;
constexpr Real kMaxOverlapFraction = 0.2;  // of the smaller body's volume
constexpr int kOverlapSamples = 12;        // per axis

std::string ratioText(Real r) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f", r);
    return buffer;
}

bool inside(const Polytope& shape, const Vec3& p) {
    for (const Face& f : shape.faces)
        if (f.normal.dot(p) > f.offset + 1e-9) return false;
    return true;
}

// The fraction of `a`'s volume that lies inside `b`, from a regular grid over `a`'s bounds:
// deterministic, and plenty for a warning threshold.
Real overlapFraction(const FigureBody& a, const FigureBody& b) {
    Vec3 lo = Vec3::Constant(1e30), hi = Vec3::Constant(-1e30);
    for (const Vec3& v : a.shape.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const RigidPose aInB = b.pose.inverse() * a.pose;
    int inA = 0, inBoth = 0;
    for (int i = 0; i < kOverlapSamples; ++i)
        for (int j = 0; j < kOverlapSamples; ++j)
            for (int k = 0; k < kOverlapSamples; ++k) {
                const Vec3 t((i + 0.5) / kOverlapSamples, (j + 0.5) / kOverlapSamples, (k + 0.5) / kOverlapSamples);
                const Vec3 p = lo + (hi - lo).cwiseProduct(t);
                if (!inside(a.shape, p)) continue;
                ++inA;
                if (inside(b.shape, aInB.apply(p))) ++inBoth;
            }
    return inA ? Real(inBoth) / inA : 0;
}

int root(std::vector<int>& parent, int i) {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
}

}  // namespace

std::vector<std::vector<int>> bodyTrees(const Figure& figure) {
    std::vector<int> parent(figure.bodies.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (const FigureConstraint& c : figure.constraints)
        if (c.body1 >= 0 && c.body2 >= 0) parent[static_cast<std::size_t>(root(parent, c.body1))] = root(parent, c.body2);
    std::vector<std::vector<int>> trees;
    std::vector<int> treeOfRoot(figure.bodies.size(), -1);
    for (std::size_t i = 0; i < figure.bodies.size(); ++i) {
        int& t = treeOfRoot[static_cast<std::size_t>(root(parent, static_cast<int>(i)))];
        if (t < 0) {
            t = static_cast<int>(trees.size());
            trees.emplace_back();
        }
        trees[static_cast<std::size_t>(t)].push_back(static_cast<int>(i));
    }
    return trees;
}

std::vector<FigureWarning> figureWarnings(const Figure& figure) {
    using Subject = FigureWarning::Subject;
    std::vector<FigureWarning> out;
    for (std::size_t i = 0; i < figure.bodies.size(); ++i) {
        const FigureBody& b = figure.bodies[i];
        const Vec3 m = principalInertia(b.inertia).moments;
        if (m[0] > 0 && m[2] / m[0] > kMaxInertiaRatio)
            out.push_back({Subject::Body, int(i),
                           "body \"" + b.name + "\": its principal moments of inertia differ by " + ratioText(m[2] / m[0]) +
                               ":1 (more than 20:1); consider inertiaScale or a stouter shape"});
    }

    for (std::size_t i = 0; i < figure.constraints.size(); ++i) {
        const FigureConstraint& c = figure.constraints[i];
        if (c.body1 < 0 || c.body2 < 0) continue;
        const FigureBody& a = figure.bodies[static_cast<std::size_t>(c.body1)];
        const FigureBody& b = figure.bodies[static_cast<std::size_t>(c.body2)];
        const std::string label = std::string(toString(c.type)) + " \"" + c.name + "\"";
        const Real ratio = std::max(a.mass, b.mass) / std::min(a.mass, b.mass);
        if (ratio > kMaxMassRatio)
            out.push_back({Subject::Constraint, int(i),
                           label + " joins \"" + a.name + "\" and \"" + b.name + "\", whose masses differ by " + ratioText(ratio) +
                               ":1 (more than 20:1)"});
        if (c.type == ConstraintType::Spring) continue;
        const FigureBody& smaller = a.volume <= b.volume ? a : b;
        const FigureBody& larger = a.volume <= b.volume ? b : a;
        const Real overlap = overlapFraction(smaller, larger);
        if (overlap > kMaxOverlapFraction)
            out.push_back({Subject::Constraint, int(i),
                           label + ": \"" + smaller.name + "\" starts " + ratioText(100 * overlap) + "% inside \"" + larger.name + "\""});
    }

    const std::vector<std::vector<int>> trees = bodyTrees(figure);
    if (trees.size() > 1) {
        std::string list;
        for (const std::vector<int>& t : trees)
            list += (list.empty() ? "\"" : ", \"") + figure.bodies[static_cast<std::size_t>(t.front())].name + "\"";
        out.push_back({Subject::Figure, -1,
                       "the bodies form " + std::to_string(trees.size()) + " separate trees (containing " + list +
                           "); constraints join them into one in most figures"});
    }
    return out;
}

void checkFigure(FigureBuildContext& context, const Figure& figure) {
    for (const FigureWarning& w : figureWarnings(figure)) {
        const SourceLocation where = w.subject == FigureWarning::Subject::Body         ? figure.bodies[std::size_t(w.index)].where
                                     : w.subject == FigureWarning::Subject::Constraint ? figure.constraints[std::size_t(w.index)].where
                                                                                       : context.decl.where;
        context.diagnostics.warning(where, w.message);
    }
}

}  // namespace af
