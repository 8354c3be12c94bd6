#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace benchscene {
namespace {

constexpr double kRestLinear = 0.05;   // m/s
constexpr double kRestAngular = 0.1;   // rad/s
constexpr double kExplodeSpeed = 50;   // m/s
constexpr double kFellThrough = -0.5;  // m

// Anchor in a body's local frame: in the T-pose every body's axes are the model axes.
Vec3 localAnchor(const JointDef& j, int body) { return j.anchor - ragdollBodies()[body].centre; }

// The locked rotational DOFs' drift (rad).
double angularError(const JointDef& j, const Quat& qA, const Quat& qB) {
    const Quat q = (qA.conjugate() * qB).normalized();
    switch (j.kind) {
        case JointKind::Fixed: return 2 * std::atan2(q.vec().norm(), std::abs(q.w()));
        case JointKind::Hinge: {
            const Vec3 moved = q * j.axis1;
            return std::atan2(j.axis1.cross(moved).norm(), j.axis1.dot(moved));
        }
        case JointKind::Universal: return std::abs(std::asin(std::clamp(j.axis1.dot(q * j.axis2), -1.0, 1.0)));
        case JointKind::ConeTwist: return 0;
    }
    return 0;
}

double beyond(double angle, double lo, double hi) { return std::max({0.0, lo - angle, angle - hi}); }

double limitViolation(const JointDef& j, const Quat& qA, const Quat& qB) {
    switch (j.kind) {
        case JointKind::Fixed: return 0;
        case JointKind::Hinge: return beyond(hingeAngle(j, qA, qB), j.lo1, j.hi1);
        case JointKind::Universal: {
            const auto [t1, t2] = universalAngles(j, qA, qB);
            return std::max(beyond(t1, j.lo1, j.hi1), beyond(t2, j.lo2, j.hi2));
        }
        case JointKind::ConeTwist: {
            const auto [swing, twist] = swingTwist(j, qA, qB);
            return std::max(beyond(swing, -j.hi1, j.hi1), beyond(twist, j.lo2, j.hi2));
        }
    }
    return 0;
}

bool finite(const BodyState& s) {
    return s.x.allFinite() && s.q.coeffs().allFinite() && s.v.allFinite() && s.w.allFinite();
}

void appendNumber(std::string& out, const char* name, double value) {
    char buf[96];
    if (std::isfinite(value)) {
        std::snprintf(buf, sizeof buf, "\"%s\": %.9g", name, value);
    } else {
        std::snprintf(buf, sizeof buf, "\"%s\": null", name);
    }
    out += ", ";
    out += buf;
}

void appendOptionalInt(std::string& out, const char* name, std::optional<int> value) {
    out += ", \"";
    out += name;
    out += "\": ";
    out += value ? std::to_string(*value) : "null";
}

void appendString(std::string& out, const char* name, std::string_view value, bool first = false) {
    if (!first) out += ", ";
    out += '"';
    out += name;
    out += "\": \"";
    for (char c : value) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    out += '"';
}

}  // namespace

StateMeasures measureStates(std::span<const BodyState> states, int ragdolls) {
    if (states.size() != static_cast<std::size_t>(ragdolls) * kBodiesPerRagdoll) {
        throw std::invalid_argument("measureStates: expected 16 states per ragdoll");
    }
    StateMeasures m;
    m.atRest = true;
    const auto bodies = ragdollBodies();
    for (std::size_t i = 0; i < states.size(); ++i) {
        const BodyState& s = states[i];
        const BoxBody& box = bodies[i % kBodiesPerRagdoll];
        if (!finite(s)) {
            m.exploded = true;
            m.atRest = false;
            continue;
        }
        const Eigen::Matrix3d R = s.q.normalized().toRotationMatrix();
        const double lowest = s.x.z() - R.row(2).cwiseAbs().dot(box.halfExtents);
        m.groundPen = std::max(m.groundPen, -lowest);
        const Vec3 wLocal = R.transpose() * s.w;
        m.kinetic += 0.5 * box.mass * s.v.squaredNorm() + 0.5 * wLocal.dot(boxInertia(box).cwiseProduct(wLocal));
        m.potential += box.mass * kGravity * s.x.z();
        if (s.v.norm() > kExplodeSpeed || s.x.z() < kFellThrough) m.exploded = true;
        if (!(s.v.norm() < kRestLinear && s.w.norm() < kRestAngular)) m.atRest = false;
    }
    for (int r = 0; r < ragdolls; ++r) {
        const BodyState* rs = states.data() + static_cast<std::size_t>(r) * kBodiesPerRagdoll;
        for (const JointDef& j : ragdollJoints()) {
            const BodyState& a = rs[j.parent];
            const BodyState& b = rs[j.child];
            if (!finite(a) || !finite(b)) continue;
            const Vec3 pa = a.x + a.q * localAnchor(j, j.parent);
            const Vec3 pb = b.x + b.q * localAnchor(j, j.child);
            m.jointErr = std::max(m.jointErr, (pa - pb).norm());
            m.jointAngErr = std::max(m.jointAngErr, angularError(j, a.q, b.q));
            m.limitViol = std::max(m.limitViol, limitViolation(j, a.q, b.q));
        }
    }
    return m;
}

RunMetrics::RunMetrics(int ragdolls) : ragdolls_(ragdolls) { stepSeconds_.reserve(kSteps); }

void RunMetrics::setInitial(std::span<const BodyState> states) {
    const StateMeasures m = measureStates(states, ragdolls_);
    energyInitial_ = m.kinetic + m.potential;
    energyMin_ = *energyInitial_;
}

void RunMetrics::addStep(std::span<const BodyState> states, double stepSeconds, double engineContactDepth) {
    const StateMeasures m = measureStates(states, ragdolls_);
    const int step = stepsDone();
    stepSeconds_.push_back(stepSeconds);
    jointErrMax_ = std::max(jointErrMax_, m.jointErr);
    jointAngErrMax_ = std::max(jointAngErrMax_, m.jointAngErr);
    limitViolMax_ = std::max(limitViolMax_, m.limitViol);
    groundPenMax_ = std::max(groundPenMax_, m.groundPen);
    if (std::isfinite(engineContactDepth) && engineContactDepth >= 0) {
        contactDepthMax_ = std::max(contactDepthMax_, engineContactDepth);
    }
    const double energy = m.kinetic + m.potential;
    if (!energyInitial_) {
        energyInitial_ = energy;
        energyMin_ = energy;
    }
    if (std::isfinite(energy)) {
        energyMin_ = std::min(energyMin_, energy);
        energyGainMax_ = std::max(energyGainMax_, energy - energyMin_);
    }
    if (!m.atRest) lastNotAtRest_ = step;
    exploded_ = exploded_ || m.exploded;
    last_ = m;
}

void RunMetrics::addSleep(bool everyBodyAsleep) {
    sleepReported_ = true;
    if (!everyBodyAsleep) lastAwake_ = stepsDone() - 1;
}

std::optional<int> RunMetrics::restStep() const {
    if (stepsDone() == 0 || lastNotAtRest_ == stepsDone() - 1) return std::nullopt;
    return lastNotAtRest_ + 1;
}

std::string RunMetrics::json(std::string_view engine, std::string_view variant, std::string_view scene,
                             bool partial, std::string_view extraJsonFields) const {
    std::vector<double> sorted = stepSeconds_;
    std::sort(sorted.begin(), sorted.end());
    double wall = 0;
    for (double s : sorted) wall += s;
    const std::size_t n = sorted.size();
    const double mean = n ? wall / static_cast<double>(n) : NAN;
    const double median = n == 0 ? NAN : n % 2 ? sorted[n / 2] : (sorted[n / 2 - 1] + sorted[n / 2]) / 2;
    const double max = n ? sorted.back() : NAN;
    const bool any = n > 0;

    std::string out = "{";
    appendString(out, "engine", engine, true);
    appendString(out, "variant", variant);
    appendString(out, "scene", scene);
    out += ", \"ragdolls\": " + std::to_string(ragdolls_);
    out += ", \"steps_done\": " + std::to_string(n);
    out += partial ? ", \"partial\": true" : ", \"partial\": false";
    appendNumber(out, "wall_s", wall);
    appendNumber(out, "us_per_step_mean", mean * 1e6);
    appendNumber(out, "us_per_step_median", median * 1e6);
    appendNumber(out, "us_per_step_max", max * 1e6);
    // The mean before and after rest_step: where an engine's time goes (falling and settling, or
    // holding a figure at rest), which the whole run's mean weighs by how soon the figure rests.
    const std::size_t rest = static_cast<std::size_t>(restStep().value_or(static_cast<int>(n)));
    const auto meanOf = [&](std::size_t begin, std::size_t end) {
        double sum = 0;
        for (std::size_t i = begin; i < end; ++i) sum += stepSeconds_[i];
        return end > begin ? sum / static_cast<double>(end - begin) : NAN;
    };
    appendNumber(out, "us_per_step_mean_until_rest", meanOf(0, rest) * 1e6);
    appendNumber(out, "us_per_step_mean_at_rest", meanOf(rest, n) * 1e6);
    appendNumber(out, "joint_err_max_m", jointErrMax_);
    appendNumber(out, "joint_err_final_m", any ? last_.jointErr : NAN);
    appendNumber(out, "joint_ang_err_max_rad", jointAngErrMax_);
    appendNumber(out, "limit_viol_max_rad", limitViolMax_);
    appendNumber(out, "limit_viol_final_rad", any ? last_.limitViol : NAN);
    appendNumber(out, "ground_pen_max_m", groundPenMax_);
    appendNumber(out, "ground_pen_final_m", any ? last_.groundPen : NAN);
    appendNumber(out, "contact_depth_max_m", contactDepthMax_ >= 0 ? contactDepthMax_ : NAN);
    appendNumber(out, "ke_final_J", any ? last_.kinetic : NAN);
    appendNumber(out, "energy_initial_J", energyInitial_ ? *energyInitial_ : NAN);
    appendNumber(out, "energy_gain_max_J", energyGainMax_);
    appendOptionalInt(out, "rest_step", restStep());
    if (sleepReported_) {
        appendOptionalInt(out, "sleep_step",
                          n == 0 || lastAwake_ == static_cast<int>(n) - 1 ? std::nullopt
                                                                          : std::optional<int>(lastAwake_ + 1));
    }
    out += exploded_ ? ", \"exploded\": true" : ", \"exploded\": false";
    if (!extraJsonFields.empty()) {
        out += ", ";
        out += extraJsonFields;
    }
    out += "}";
    return out;
}

}  // namespace benchscene
