#include "peer_common.h"

#include "counted_step.h"
#include "metrics.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace peers {

namespace {

void usage(const char* program, std::initializer_list<std::string_view> variants) {
    std::cerr << "usage: " << program
              << " [--scene single|grid4|grid16|pile] [--count N] --variant V [--steps N] [--max-seconds S]"
                 " [--sleep on|off] [--selftest]\n  variants:";
    for (auto v : variants) std::cerr << ' ' << v;
    std::cerr << '\n';
}

}  // namespace

std::optional<Options> parseOptions(int argc, char** argv, std::initializer_list<std::string_view> variants) {
    Options o;
    o.variant = std::string(*variants.begin());
    for (int i = 1; i < argc; ++i) {
        std::string_view a = argv[i];
        auto value = [&]() -> std::optional<std::string_view> {
            if (i + 1 >= argc) return std::nullopt;
            return std::string_view(argv[++i]);
        };
        std::optional<std::string_view> v;
        if (a == "--selftest") {
            o.selftest = true;
            continue;
        }
        if (!(v = value())) {
            usage(argv[0], variants);
            return std::nullopt;
        }
        char* end = nullptr;
        std::string s(*v);
        if (a == "--scene") {
            o.scene = s;
        } else if (a == "--count") {
            o.count = static_cast<int>(std::strtol(s.c_str(), &end, 10));
            if (*end || o.count < 1) v.reset();
        } else if (a == "--variant") {
            o.variant = s;
        } else if (a == "--steps") {
            o.steps = static_cast<int>(std::strtol(s.c_str(), &end, 10));
            if (*end || o.steps < 1) v.reset();
        } else if (a == "--max-seconds") {
            o.maxSeconds = std::strtod(s.c_str(), &end);
            if (*end || o.maxSeconds < 0) v.reset();
        } else if (a == "--sleep") {
            if (s != "on" && s != "off") v.reset();
            o.sleep = s == "on";
        } else {
            v.reset();
        }
        if (!v) {
            std::cerr << argv[0] << ": bad option " << a << ' ' << s << '\n';
            usage(argv[0], variants);
            return std::nullopt;
        }
    }
    bool known = false;
    for (auto v : variants) known = known || v == o.variant;
    if (!known) {
        std::cerr << argv[0] << ": unknown variant " << o.variant << '\n';
        usage(argv[0], variants);
        return std::nullopt;
    }
    return o;
}

Eigen::Matrix3d hingeBasis(const Vec3& axis) {
    Vec3 z = axis.normalized();
    Vec3 x = z.unitOrthogonal();
    Eigen::Matrix3d m;
    m << x, z.cross(x), z;
    return m;
}

Eigen::Matrix3d universalBasis(const JointDef& j) {
    Eigen::Matrix3d m;
    m << j.axis1, j.axis2, j.axis1.cross(j.axis2);
    return m;
}

ConeState coneState(const JointDef& j, const std::array<Quat, 2>& frames, const Quat& qA, const Quat& qB) {
    auto [swing, twist] = benchscene::swingTwist(j, qA, qB);
    Vec3 c = qA * (frames[0] * Vec3::UnitX());
    Vec3 b = qB * (frames[1] * Vec3::UnitX());
    Vec3 n = c.cross(b);
    // At zero swing any axis perpendicular to the bone will do: the cone limit is far away then.
    Vec3 swingAxis = n.norm() > 1e-9 ? Vec3(n.normalized()) : Vec3(b.unitOrthogonal());
    // Twist about the bone grows with (ω_B − ω_A)·(c + b)/(1 + c·b): rotating the child about the
    // cone axis c changes the twist as much as rotating it about the bone b.
    const Vec3 cb = c + b;
    return {swing, twist, swingAxis, cb.norm() > 1e-9 ? Vec3(cb.normalized()) : b};
}

Quat probeRotation(const JointDef& j) {
    using AA = Eigen::AngleAxisd;
    if (j.kind == benchscene::JointKind::Hinge) return Quat(AA(0.3, j.axis1.normalized()));
    return Quat(AA(0.3, j.axis1.normalized()) * AA(0.5, j.axis2.normalized()));
}

void judgeProbe(ProbeRow& row) {
    row.ok = row.scene.size() == row.engine.size();
    for (std::size_t k = 0; k < row.scene.size() && row.ok; ++k) {
        double s = row.scene[k], e = row.engine[k];
        row.sign[k] = s * e >= 0 ? 1 : -1;
        row.ok = std::abs(std::abs(s) - std::abs(e)) < 1e-4 && std::abs(s) > 0.1;
    }
}

bool probeOk(std::span<const ProbeRow> rows) {
    for (const auto& r : rows)
        if (!r.ok) return false;
    return true;
}

std::string probeReport(std::string_view engine, std::span<const ProbeRow> rows, std::string_view extraJsonFields) {
    std::ostringstream s;
    s.precision(6);
    auto list = [&](const auto& v) {
        s << '[';
        for (std::size_t k = 0; k < v.size(); ++k) s << (k ? ", " : "") << v[k];
        s << ']';
    };
    s << "{\"engine\": \"" << engine << "\", \"selftest\": [";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const auto& r = rows[i];
        s << (i ? ",\n  " : "\n  ") << "{\"joint\": \"" << r.joint << "\", \"scene_rad\": ";
        list(r.scene);
        s << ", \"engine_rad\": ";
        list(r.engine);
        s << ", \"sign\": ";
        list(std::vector<int>(r.sign.begin(), r.sign.begin() + static_cast<long>(r.scene.size())));
        s << ", \"ok\": " << (r.ok ? "true" : "false") << '}';
    }
    s << "],\n \"ok\": " << (probeOk(rows) ? "true" : "false");
    if (!extraJsonFields.empty()) s << ", " << extraJsonFields;
    s << "}\n";
    return s.str();
}

void runScene(const Options& o, std::string_view engine, int ragdolls, const RunHooks& hooks) {
    using Clock = std::chrono::steady_clock;
    benchscene::RunMetrics metrics(ragdolls);
    std::vector<benchscene::BodyState> states(static_cast<std::size_t>(ragdolls) * kBodiesPerRagdoll);
    hooks.read(states);
    metrics.setInitial(states);
    const auto start = Clock::now();
    bool partial = false;
    for (int s = 0; s < o.steps; ++s) {
        if (o.maxSeconds > 0 && std::chrono::duration<double>(Clock::now() - start).count() > o.maxSeconds) {
            partial = true;
            break;
        }
        const auto t0 = Clock::now();
        {
            const benchscene::CountedStep counted;
            hooks.step();
        }
        const auto t1 = Clock::now();
        hooks.read(states);
        metrics.addStep(states, std::chrono::duration<double>(t1 - t0).count(), hooks.contactDepth());
        if (o.sleep) metrics.addSleep(hooks.asleep());
    }
    const std::string extra = hooks.extraJson ? hooks.extraJson() : std::string();
    std::cout << metrics.json(engine, o.variant, o.scene, partial, extra) << std::endl;
}

}  // namespace peers
