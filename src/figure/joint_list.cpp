// containedJoints lists and the joint → body table (docs/formats.md §1.6, docs/figures.md §3.7).

#include "af/text/strings.h"
#include "figure_build_context.h"

#include <algorithm>
#include <sstream>

namespace af {

std::vector<int> expandJointList(const Skeleton& skeleton, std::string_view list, std::vector<std::string>* unknown) {
    std::vector<int> joints;
    std::istringstream items{std::string(list)};
    for (std::string item; items >> item;) {
        std::string_view name = item;
        const bool remove = name.starts_with('-');
        if (remove) name.remove_prefix(1);
        const bool subtree = name.starts_with('*');
        if (subtree) name.remove_prefix(1);
        const int first = skeleton.find(name);
        if (first < 0) {
            if (unknown) unknown->push_back(item);
            continue;
        }
        // Parents precede children, so a joint's descendants are the run of joints after it
        // whose parents are at or after it.
        std::size_t last = static_cast<std::size_t>(first) + 1;
        if (subtree)
            while (last < skeleton.size() && skeleton.parents[last] >= first) ++last;
        for (std::size_t j = static_cast<std::size_t>(first); j < last; ++j) {
            const auto at = std::find(joints.begin(), joints.end(), static_cast<int>(j));
            if (remove && at != joints.end()) joints.erase(at);
            if (!remove && at == joints.end()) joints.push_back(static_cast<int>(j));
        }
    }
    return joints;
}

void claimJoints(FigureBuildContext& context, Figure& figure) {
    figure.jointBody.assign(context.skeleton.size(), -1);
    for (std::size_t b = 0; b < figure.bodies.size(); ++b) {
        FigureBody& body = figure.bodies[b];
        const AFBody* decl = context.decl.findBody(body.name);
        std::vector<std::string> unknown;
        body.containedJoints = expandJointList(context.skeleton, decl->containedJoints, &unknown);
        for (const std::string& u : unknown)
            context.diagnostics.warning(body.where, "body \"" + body.name + "\": containedJoints names \"" + u +
                                                        "\", which is not in the skeleton");
        for (int j : body.containedJoints) {
            int& owner = figure.jointBody[static_cast<std::size_t>(j)];
            if (owner >= 0)
                context.diagnostics.warning(body.where, "joint \"" + context.skeleton.names[static_cast<std::size_t>(j)] +
                                                            "\" is in the containedJoints of both \"" +
                                                            figure.bodies[static_cast<std::size_t>(owner)].name +
                                                            "\" and \"" + body.name + "\"; \"" + body.name + "\" gets it");
            owner = static_cast<int>(b);
        }
    }
    std::string unclaimed;
    for (std::size_t j = 0; j < figure.jointBody.size(); ++j)
        if (figure.jointBody[j] < 0) unclaimed += (unclaimed.empty() ? "" : ", ") + context.skeleton.names[j];
    if (!unclaimed.empty())
        context.diagnostics.warning(context.decl.where, "no body's containedJoints holds these joints: " + unclaimed);
}

}  // namespace af
