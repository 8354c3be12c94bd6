#pragma once
// The skin of an `.md5mesh` (docs/formats.md §2.1): each mesh block's vertices and their weights,
// read by the same parser as the skeleton. Figures never need it, so parseMd5Mesh drops it; a
// tool that sizes bodies from the mesh (af-gen) reads it through these functions.
//
// A vertex's position in a pose is Σ bias · (joint position + joint rotation · weight position)
// over its weights, with the joints' model-space transforms (in the bind pose: the mesh's joints).

#include "af/text/md5.h"

#include <string>
#include <string_view>
#include <vector>

namespace af {

// A vertex: its weights are the block's weights[firstWeight .. firstWeight + weightCount).
struct Md5Vertex {
    int firstWeight = 0;
    int weightCount = 0;
};

struct Md5Weight {
    int joint = 0;
    Real bias = 0;
    Real3 position{};  // in the joint's frame
};

struct Md5SkinSection {
    std::vector<Md5Vertex> vertices;
    std::vector<Md5Weight> weights;
};

struct Md5MeshWithSkin {
    Md5MeshParseResult parsed;            // as parseMd5Mesh gives it
    std::vector<Md5SkinSection> skin;     // one per mesh block; incomplete unless parsed.ok()
};

Md5MeshWithSkin parseMd5MeshWithSkin(std::string_view text, std::string fileName);
Md5MeshWithSkin loadMd5MeshWithSkin(const std::string& path);

}  // namespace af
