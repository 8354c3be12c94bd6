// World::contactImpulses: the last velocity solve's impulses at the contact points, read from the
// world's warm-start cache by the keys the points' rows were written with (contact_set.h), so the
// step itself keeps nothing more for it.

#include "world_state.h"

namespace af {

std::vector<ContactImpulse> World::contactImpulses() const {
    const State& s = *state_;
    const std::vector<BodyContact>& manifolds = s.found();
    // Per point: its normal row's key and its two friction rows' (a point with one friction row,
    // or none, has no entry under the others, which read as zero).
    std::vector<std::uint64_t> keys;
    for (const BodyContact& c : manifolds) {
        const std::uint64_t pair = contactPairKey(c);
        for (int k = 0; k < c.manifold.count; ++k) {
            const std::uint64_t key = contactPointKey(pair, c.manifold.points[static_cast<std::size_t>(k)]);
            for (std::uint64_t row = 0; row < 3; ++row) keys.push_back(key + row);
        }
    }
    std::vector<Real> lambda(keys.size());
    s.warmStart.impulsesOf(keys, lambda);

    std::vector<ContactImpulse> out;
    out.reserve(keys.size() / 3);
    for (const BodyContact& c : manifolds) {
        const Vec3& n = c.manifold.normal;
        const std::optional<Vec3>& along = s.materials[static_cast<std::size_t>(c.bodyA)].frictionDirection;
        const Vec3 alongWorld = along ? Vec3(s.bodies[static_cast<std::size_t>(c.bodyA)].orientation * *along) : Vec3::Zero();
        Vec3 directions[2];
        const int count = frictionDirections(n, along ? &alongWorld : nullptr, directions);
        for (int k = 0; k < c.manifold.count; ++k) {
            const Real* l = &lambda[3 * out.size()];
            ContactImpulse& impulse = out.emplace_back();
            impulse.normal = l[0];
            for (int d = 0; d < count; ++d) impulse.friction += l[1 + d] * directions[d];
        }
    }
    return out;
}

}  // namespace af
