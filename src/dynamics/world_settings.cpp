// Which WorldSettings a world accepts (World's constructor and setSettings): every number finite
// and in the range where it means something, so that a bad value is refused where it is given
// instead of turning into NaN poses steps later.

#include "world_state.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace af {

namespace {

bool finiteAtLeastZero(Real v) { return std::isfinite(v) && v >= 0; }
// A velocity cap: +∞ (no cap) or a finite speed ≥ 0.
bool cap(Real v) { return !std::isnan(v) && v >= 0; }

std::string problemOf(const WorldSettings& s) {
    if (!s.gravity.allFinite()) return "gravity is not finite";
    if (!(std::isfinite(s.timeStep) && s.timeStep > 0 && s.timeStep <= 1)) return "timeStep must be in (0, 1] s";
    if (s.substeps < 1 || s.substeps > 1000) return "substeps must be in [1, 1000]";
    if (s.positionIterations < 0) return "positionIterations must be ≥ 0";
    if (!finiteAtLeastZero(s.positionTolerance)) return "positionTolerance must be finite and ≥ 0";
    if (!finiteAtLeastZero(s.contactMargin)) return "contactMargin must be finite and ≥ 0";
    if (!finiteAtLeastZero(s.impulseThreshold)) return "impulseThreshold must be finite and ≥ 0";
    if (!cap(s.integration.maxLinearSpeed) || !cap(s.integration.maxAngularSpeed))
        return "the velocity caps must be ≥ 0 (+∞: no cap)";
    const ContactSettings& c = s.contact;
    if (!finiteAtLeastZero(c.restitutionThreshold) || !finiteAtLeastZero(c.slop) || !finiteAtLeastZero(c.relativeCfm))
        return "contact restitutionThreshold, slop and relativeCfm must be finite and ≥ 0";
    const JointRowSettings& r = s.rows;
    for (Real v : {r.jointCfm, r.limitCfm, r.frictionCfm, r.limitMargin, r.springLimitMargin})
        if (!finiteAtLeastZero(v)) return "joint row CFMs and margins must be finite and ≥ 0";
    if (!std::isfinite(r.forcedFriction)) return "forcedFriction is not finite";
    if (s.threads < 1 || s.threads > 256) return "threads must be in [1, 256]";
    return {};
}

}  // namespace

void checkSettings(const WorldSettings& settings, const char* caller) {
    if (const std::string problem = problemOf(settings); !problem.empty())
        throw std::invalid_argument(std::string(caller) + ": " + problem);
}

// The rules changed: every cache made under the old ones is forgotten (as after a removal), and
// every figure wakes, since a rest judged under the old rules (gravity, limits) says nothing now.
void World::setSettings(const WorldSettings& settings) {
    checkSettings(settings, "World::setSettings");
    State& s = *state_;
    s.settings = settings;
    s.collision.setSettings(settings.collision);
    s.startThreads();
    s.renumber();
    for (std::size_t f = 0; f < s.figures.size(); ++f) s.wake(static_cast<int>(f));
}

}  // namespace af
