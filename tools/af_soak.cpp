// af-soak: thousands of seeded drops of hostile figures in hostile starts (docs/soak.md), and a
// table of the worst cases, each with the seed that replays it.
//
// Exit status: 0 when no drop failed; 1 when a drop saw a NaN or an infinity, exploded (kinetic
// energy beyond kExplosionRatio times what the start and gravity could supply), had a figure put
// back by the world's guard, rested with a joint open or a contact deep, or the library threw or
// refused a figure the soak made valid (--fail-on narrows these to the kinds it names); 2 for bad
// usage or bad input (an unknown option, a map that does not load).

#include "command_line_usage.h"
#include "soak_drop.h"

#include "af/geometry/brush.h"
#include "af/text/map_file.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace {

using af::Real;
using af::soak::DropResult;

struct Options {
    std::uint64_t seed = 1;
    int drops = 100;
    double seconds = 5;
    int jobs = 1;
    std::optional<std::uint64_t> replay;
    std::vector<std::string> roots;
    std::string map;
    bool list = false;
    double maxWall = 20;
    std::vector<std::string> failOn;  // kinds of failure that set the exit status; empty: all
};

// The kinds of failure a drop can have: the table's name for each and the name --fail-on takes.
struct FailureKind {
    const char* row;
    const char* option;
    bool (*has)(const DropResult&);
};
constexpr FailureKind kFailureKinds[] = {
    {"NaN/inf", "nan", [](const DropResult& r) { return r.nonFinite; }},
    {"explosion", "explosion", [](const DropResult& r) { return r.exploded(); }},
    {"put back", "put-back", [](const DropResult& r) { return r.restored > 0; }},
    {"rested open", "rested-open", [](const DropResult& r) { return r.restedOpen(); }},
    {"threw", "threw", [](const DropResult& r) { return !r.threw.empty(); }},
    {"refused", "refused", [](const DropResult& r) { return !r.rejected.empty(); }},
};

bool failsExitStatus(const DropResult& r, const Options& o) {
    for (const FailureKind& kind : kFailureKinds)
        if ((o.failOn.empty() || std::find(o.failOn.begin(), o.failOn.end(), kind.option) != o.failOn.end()) &&
            kind.has(r))
            return true;
    return false;
}

std::vector<af::Polytope> loadBrushes(const std::string& path) {
    const af::MapParseResult parsed = af::loadMapFile(path);
    if (!parsed.ok()) throw std::runtime_error(parsed.diagnostics.formatAll());
    const af::MapEntity* world = parsed.map.worldspawn();
    if (!world) throw std::runtime_error(path + ": error: the map has no worldspawn entity");
    std::vector<af::Polytope> brushes;
    for (const af::MapPrimitive& primitive : world->primitives) {
        const af::BrushDef3* brush = primitive.brush();
        if (!brush) continue;
        const af::BrushPolytope solid = af::polytopeFromBrush(*brush);
        if (!solid.ok())
            throw std::runtime_error(path + ":" + std::to_string(primitive.where.line) + ": error: " + solid.message);
        brushes.push_back(*solid.polytope);
    }
    if (brushes.empty()) throw std::runtime_error(path + ": error: the worldspawn has no brushes");
    return brushes;
}

std::string number(Real value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", static_cast<double>(value));
    return buffer;
}

void printHeader() {
    std::printf("%-18s %10s %-16s %6s %8s %8s %9s %9s %9s %9s %6s %5s\n", "case", "seed", "figure", "bodies", "step",
                "energy", "joint", "joint end", "pen", "pen end", "rest", "fails");
}

// One drop's measures; --replay prints the same line as the table, so the two can be compared.
void printRow(const std::string& what, const DropResult& r) {
    std::string rest = r.restTime ? number(*r.restTime) : "-";
    std::string energy = number(r.energyRatio);
    if (!r.threw.empty()) energy = "threw";
    else if (!r.rejected.empty()) energy = "refused";
    else if (r.nonFinite) energy = "NaN@" + number(r.nonFiniteTime);
    std::printf("%-18s %10llu %-16s %6d %8s %8s %9s %9s %9s %9s %6s %5d\n", what.c_str(),
                static_cast<unsigned long long>(r.seed), r.figure.c_str(), r.bodies, ("1/" + number(1 / r.timeStep)).c_str(),
                energy.c_str(), number(r.peakJointError).c_str(), number(r.endJointError).c_str(),
                number(r.peakPenetration).c_str(), number(r.endPenetration).c_str(), rest.c_str(), r.solverFailures);
}

// The drop that maximises `key` (the first of equals), if any drop has a key.
const DropResult* worst(const std::vector<DropResult>& results, const std::function<std::optional<Real>(const DropResult&)>& key) {
    const DropResult* found = nullptr;
    std::optional<Real> best;
    for (const DropResult& r : results) {
        const std::optional<Real> k = key(r);
        if (k && (!best || *k > *best)) best = k, found = &r;
    }
    return found;
}

void printTable(const std::vector<DropResult>& results) {
    auto ran = [](const DropResult& r) { return r.threw.empty() && r.rejected.empty(); };
    printHeader();
    const std::pair<const char*, std::function<std::optional<Real>(const DropResult&)>> cases[] = {
        {"energy ratio", [&](const DropResult& r) { return ran(r) ? std::optional(r.energyRatio) : std::nullopt; }},
        {"joint error", [&](const DropResult& r) { return ran(r) ? std::optional(r.peakJointError) : std::nullopt; }},
        {"joint error end", [&](const DropResult& r) { return ran(r) ? std::optional(r.endJointError) : std::nullopt; }},
        {"penetration", [&](const DropResult& r) { return ran(r) ? std::optional(r.peakPenetration) : std::nullopt; }},
        {"penetration end", [&](const DropResult& r) { return ran(r) ? std::optional(r.endPenetration) : std::nullopt; }},
        // A drop that never rested is slower than any that did.
        {"slowest rest", [&](const DropResult& r) {
             return ran(r) && !r.tooSlow ? std::optional(r.restTime.value_or(1e300)) : std::nullopt;
         }},
        {"failed solves", [&](const DropResult& r) { return ran(r) ? std::optional(Real(r.solverFailures)) : std::nullopt; }},
    };
    for (const auto& [what, key] : cases)
        if (const DropResult* r = worst(results, key)) printRow(what, *r);
    constexpr int kShown = 10;
    for (const FailureKind& kind : kFailureKinds) {
        int shown = 0, more = 0;
        for (const DropResult& r : results) {
            if (!kind.has(r)) continue;
            if (shown++ < kShown) printRow(kind.row, r);
            else ++more;
        }
        if (more) std::printf("%-18s and %d more\n", kind.row, more);
    }
    for (const DropResult& r : results)
        if (r.tooSlow)
            std::printf("%-18s %10llu %-16s %6d bodies, stopped after %d steps (%s s simulated), %.1f s wall, %.2f s the dearest step\n",
                        "too slow", static_cast<unsigned long long>(r.seed), r.figure.c_str(), r.bodies, r.steps,
                        number(r.simulated).c_str(), r.wallSeconds, r.slowestStep);
}

void printTotals(const std::vector<DropResult>& results, Real seconds, double wall) {
    int nan = 0, explosions = 0, putBack = 0, restedOpen = 0, stuck = 0, threw = 0, refused = 0, rested = 0, failedDrops = 0, bodies = 0, slow = 0;
    long failedSolves = 0, steps = 0;
    for (const DropResult& r : results) {
        nan += r.nonFinite;
        explosions += r.exploded();
        putBack += r.restored > 0;
        restedOpen += r.restedOpen();
        stuck += r.stuck > 0;
        threw += !r.threw.empty();
        refused += !r.rejected.empty();
        rested += r.restTime.has_value();
        failedDrops += r.solverFailures > 0;
        failedSolves += r.solverFailures;
        steps += r.steps;
        bodies += r.bodies;
        slow += r.tooSlow;
    }
    std::printf("totals: %zu drops, %d bodies, %ld steps, %d NaN/inf, %d explosions, %d put back by the guard, %d threw, %d refused, "
                "%d rested (%d with joints open or contacts deep, %zu still moving at %s s), %d with a figure found stuck, %d too slow, %ld failed solves in %d drops, wall %.1f s\n",
                results.size(), bodies, steps, nan, explosions, putBack, threw, refused, rested,
                restedOpen, results.size() - static_cast<std::size_t>(rested + slow), number(seconds).c_str(), stuck, slow, failedSolves,
                failedDrops, wall);
}

// With --list, each drop's row is printed as soon as the drops before it are done, in seed
// order: a long soak shows its progress, and what it found so far survives an interruption.
std::vector<DropResult> runAll(const af::soak::SoakInputs& inputs, const Options& o) {
    std::vector<DropResult> results(static_cast<std::size_t>(o.drops));
    std::vector<bool> done(results.size());
    std::size_t printed = 0;
    std::mutex mutex;
    std::atomic<int> next = 0;
    if (o.list) printHeader();
    auto worker = [&] {
        for (int i = next++; i < o.drops; i = next++) {
            DropResult r = af::soak::runDrop(inputs, o.seed + static_cast<std::uint64_t>(i));
            const std::lock_guard lock(mutex);
            results[static_cast<std::size_t>(i)] = std::move(r);
            done[static_cast<std::size_t>(i)] = true;
            for (; o.list && printed < done.size() && done[printed]; ++printed) printRow("drop", results[printed]);
            std::fflush(stdout);
        }
    };
    std::vector<std::jthread> pool;
    for (int j = 1; j < o.jobs; ++j) pool.emplace_back(worker);
    worker();
    pool.clear();
    return results;
}

int soak(const Options& o) {
    af::soak::SoakInputs inputs;
    inputs.seconds = o.seconds;
    inputs.wallBudget = o.maxWall;
    inputs.brushes = loadBrushes(o.map.empty() ? std::string(AF_DATA_DIR) + "/maps/default.map" : o.map);
    std::vector<std::filesystem::path> roots(o.roots.begin(), o.roots.end());
    if (roots.empty()) roots.emplace_back(AF_DATA_DIR);
    const af::ResourceIndex index(roots);
    inputs.samples = af::soak::sampleFigures(index);

    if (o.replay) {
        const DropResult r = af::soak::runDrop(inputs, *o.replay);
        std::printf("drop %llu: %s, %d bodies, %d steps, %s s simulated, peak kinetic energy %s, start joint error %s, wall %.2f s\n",
                    static_cast<unsigned long long>(r.seed), r.figure.c_str(), r.bodies, r.steps, number(r.simulated).c_str(),
                    number(r.peakKinetic).c_str(), number(r.startJointError).c_str(), r.wallSeconds);
        if (r.tooSlow) std::printf("  too slow: stopped by --max-wall after %.1f s (the dearest step %.2f s)\n", r.wallSeconds, r.slowestStep);
        for (const std::string& d : r.details) std::printf("  %s\n", d.c_str());
        if (!r.threw.empty()) std::printf("  threw: %s\n", r.threw.c_str());
        if (!r.rejected.empty()) std::printf("  refused: %s\n", r.rejected.c_str());
        printHeader();
        printRow("replay", r);
        return failsExitStatus(r, o) ? 1 : 0;
    }

    std::string names;
    for (const af::soak::SampleFigure& s : inputs.samples) names += (names.empty() ? "" : ", ") + s.name;
    std::printf("af-soak: %d drops from seed %llu, up to %s s each; figures: %s and generated chains\n", o.drops,
                static_cast<unsigned long long>(o.seed), number(o.seconds).c_str(), names.empty() ? "none" : names.c_str());
    const auto start = std::chrono::steady_clock::now();
    const std::vector<DropResult> results = runAll(inputs, o);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (o.list) std::printf("\n");
    printTable(results);
    printTotals(results, o.seconds, wall);
    const bool failed = std::any_of(results.begin(), results.end(), [&](const DropResult& r) { return failsExitStatus(r, o); });
    return failed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Drops hostile figures in hostile starts, thousands of seeded times, and reports the worst cases."};
    app.add_option("--drops", o.drops, "drops to run")->check(CLI::Range(1, 10000000))->capture_default_str();
    app.add_option("--seed", o.seed, "the first drop's seed (the others follow it)")->capture_default_str();
    app.add_option("--seconds", o.seconds, "simulated time limit per drop, seconds")->check(CLI::Range(0.01, 3600.0))->capture_default_str();
    app.add_option("--jobs", o.jobs, "drops run side by side (the same results on any count)")->check(CLI::Range(1, 256))->capture_default_str();
    app.add_option("--replay", o.replay, "rerun the drop of this seed alone and print how it was made");
    app.add_option("--root", o.roots, "a mod folder laid out like Doom's base/ (repeat: lowest priority first)");
    app.add_option("--map", o.map, ".map file whose worldspawn brushes are the world (default: maps/default.map)");
    app.add_option("--max-wall", o.maxWall, "wall seconds a drop may take before it stops as too slow (0: no limit; "
                                            "results then depend on the machine)")->check(CLI::Range(0.0, 1e9))->capture_default_str();
    app.add_flag("--list", o.list, "print every drop's row before the table");
    std::vector<std::string> kindNames;
    for (const FailureKind& kind : kFailureKinds) kindNames.emplace_back(kind.option);
    app.add_option("--fail-on", o.failOn, "kinds of failure that make the exit status 1 (default: all)")
        ->delimiter(',')
        ->check(CLI::IsMember(kindNames));
    if (const auto exitStatus = af::tools::parseCommandLine(app, argc, argv, "af-soak")) return *exitStatus;
    try {
        return soak(o);
    } catch (const std::exception& e) {
        std::cerr << "af-soak: " << e.what() << '\n';
        return 2;
    }
}
