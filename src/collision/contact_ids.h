#pragma once
// Ids of manifold points, built from the features that made each point so that the same point
// found again after a small motion keeps its id (the solver warm-starts by id).
//
// Bits 30–31: kind. Face contacts (kind 0): bit 29 set when the reference face is B's, bits 16–28
// the reference face, bits 8–15 and 0–7 the two lines meeting at the point, each an incident-face
// edge (its position in the incident loop) or, with bit 7 set, a side of the reference face (its
// position in the reference loop). An incident vertex that survives clipping is named by its two
// incident edges, a crossing by the incident edge and the reference side it crosses. Edge pairs
// (kind 1): A's edge in bits 15–29, B's in bits 0–14. Single points (kind 2): A's and B's support
// vertices likewise. Indices beyond the field widths wrap; only shapes far larger than any .af
// shape could then repeat an id within one manifold.

#include <cstdint>

namespace af::collision_detail {

inline std::uint8_t incidentLine(int loopPosition) { return std::uint8_t(loopPosition & 0x7F); }
inline std::uint8_t referenceSide(int loopPosition) { return std::uint8_t(0x80 | (loopPosition & 0x7F)); }

inline std::uint32_t faceContactId(bool referenceIsB, int referenceFace, std::uint8_t lineIn,
                                   std::uint8_t lineOut) {
    return (referenceIsB ? 1u << 29 : 0u) | (std::uint32_t(referenceFace) & 0x1FFF) << 16 |
           std::uint32_t(lineIn) << 8 | lineOut;
}

inline std::uint32_t edgePairId(int edgeA, int edgeB) {
    return 1u << 30 | (std::uint32_t(edgeA) & 0x7FFF) << 15 | (std::uint32_t(edgeB) & 0x7FFF);
}

inline std::uint32_t singlePointId(int vertexA, int vertexB) {
    return 2u << 30 | (std::uint32_t(vertexA) & 0x7FFF) << 15 | (std::uint32_t(vertexB) & 0x7FFF);
}

}  // namespace af::collision_detail
