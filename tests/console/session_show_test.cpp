// The af_show* cvars through scripts (session_show.h): what each prints after a clock command is
// checked against the figure and the world it describes.

#include "console/session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <sstream>

namespace af::console {
namespace {

struct ShowConsole {
    std::string info, errors;
    CommandSystem commands{Output([this](std::string_view l) { info += std::string(l) + "\n"; },
                                  [this](std::string_view l) { errors += std::string(l) + "\n"; })};
    Session session{{AF_SOURCE_DIR}, commands};

    // Runs `text` and returns what it printed.
    std::string run(std::string_view text) {
        info.clear();
        errors.clear();
        const ExecuteResult r = commands.execute(text, "test.cfg");
        EXPECT_TRUE(r.ok()) << errors;
        return info;
    }
    const Figure& figure() const { return session.world().definition(session.world().figureIds().front()); }
};

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

// The indented lines of the block whose heading starts with `heading`.
std::vector<std::string> block(const std::string& text, const std::string& heading) {
    std::vector<std::string> out;
    bool inside = false;
    for (const std::string& line : lines(text)) {
        if (line.rfind(heading, 0) == 0) inside = true;
        else if (inside && line.rfind("  ", 0) == 0) out.push_back(line);
        else if (inside) break;
    }
    return out;
}

// "  name  value" lines as a map.
std::map<std::string, double> namedNumbers(const std::vector<std::string>& blockLines) {
    std::map<std::string, double> out;
    for (const std::string& line : blockLines) {
        std::istringstream in(line);
        std::string name;
        double value = 0;
        in >> name >> value;
        out[name] = value;
    }
    return out;
}

TEST(SessionShow, NothingIsPrintedWhileEveryShowCvarIsOff) {
    ShowConsole c;
    c.run("spawn ragdoll_humanoid");
    EXPECT_EQ(c.run("step 3"), "");
}

TEST(SessionShow, MassesAreTheFiguresAndTheTotalIsTheirSum) {
    ShowConsole c;
    c.run("spawn ragdoll_humanoid");
    const std::string out = c.run("af_showMass 1; af_showTotalMass 1; step 0");
    const std::map<std::string, double> masses = namedNumbers(block(out, "af_showMass ragdoll_humanoid_1:"));
    const Figure& f = c.figure();
    ASSERT_EQ(masses.size(), f.bodies.size()) << out;
    double sum = 0;
    for (const FigureBody& b : f.bodies) {
        ASSERT_TRUE(masses.count(b.name)) << b.name << "\n" << out;
        EXPECT_NEAR(masses.at(b.name), b.mass, 0.005) << b.name;
        sum += masses.at(b.name);
    }
    std::smatch total;
    ASSERT_TRUE(std::regex_search(out, total, std::regex("af_showTotalMass ragdoll_humanoid_1: ([0-9.]+)\n"))) << out;
    EXPECT_NEAR(std::stod(total[1]), f.totalMass(), 0.005);
    EXPECT_NEAR(std::stod(total[1]), sum, 0.01 * double(f.bodies.size()));
}

TEST(SessionShow, BodiesVelocitiesAndNamesDescribeTheWorldAfterTheStep) {
    ShowConsole c;
    c.run("spawn ragdoll_humanoid origin \"0 0 100\"");
    const std::string out = c.run("af_showBodies 1; af_showVelocity 1; af_showBodyNames 1; step 2");
    const World& w = c.session.world();
    const Figure& f = c.figure();
    const std::vector<std::string> bodies = block(out, "af_showBodies ragdoll_humanoid_1:");
    const std::vector<std::string> velocities = block(out, "af_showVelocity ragdoll_humanoid_1");
    ASSERT_EQ(bodies.size(), f.bodies.size()) << out;
    ASSERT_EQ(velocities.size(), f.bodies.size()) << out;
    const std::regex vector3("\\((-?[0-9.]+) (-?[0-9.]+) (-?[0-9.]+)\\)");
    for (std::size_t b = 0; b < f.bodies.size(); ++b) {
        const RigidBody& body = w.bodies()[b];
        std::smatch m;
        ASSERT_TRUE(std::regex_search(bodies[b], m, vector3)) << bodies[b];
        EXPECT_NEAR(std::stod(m[3]), body.position.z(), 0.006) << bodies[b];
        EXPECT_NE(bodies[b].find(f.bodies[b].name), std::string::npos);
        // Two steps of a free fall: every body is falling.
        ASSERT_TRUE(std::regex_search(velocities[b], m, vector3)) << velocities[b];
        EXPECT_NEAR(std::stod(m[3]), body.linearVelocity.z(), 0.006) << velocities[b];
        EXPECT_LT(body.linearVelocity.z(), -10);
    }
    std::string names = "af_showBodyNames ragdoll_humanoid_1:";
    for (const FigureBody& b : f.bodies) names += " " + b.name;
    EXPECT_NE(out.find(names + "\n"), std::string::npos) << out;
}

TEST(SessionShow, ConstraintsAndTheirLimitsAreListedWithTheDeclsIntervals) {
    ShowConsole c;
    c.run("spawn ragdoll_humanoid\nwaitRest 5");
    const std::string out = c.run("af_showConstraints 1; af_showConstraintNames 1; af_showLimits 1; step 0");
    const Figure& f = c.figure();
    const std::vector<std::string> constraints = block(out, "af_showConstraints ragdoll_humanoid_1:");
    ASSERT_EQ(constraints.size(), f.constraints.size()) << out;
    for (std::size_t k = 0; k < f.constraints.size(); ++k) {
        const FigureConstraint& fc = f.constraints[k];
        const std::regex line("  " + fc.name + " +" + toString(fc.type) + " +" + f.bodies[std::size_t(fc.body1)].name + " - " +
                              f.bodies[std::size_t(fc.body2)].name + "  at \\(.*\\)");
        EXPECT_TRUE(std::regex_match(constraints[k], line)) << constraints[k];
    }
    // humanoid.af: the neck's cone is 70° wide (35° from its axis), a knee's V is `limit 70, 150, 0`
    // (centre 0 − 70, half width 75). At rest every angle is within its interval.
    const std::vector<std::string> limits = block(out, "af_showLimits ragdoll_humanoid_1");
    std::map<std::string, std::string> byName;
    for (const std::string& line : limits) byName[line.substr(2, line.find(' ', 2) - 2)] = line;
    ASSERT_TRUE(byName.count("neck") && byName.count("lknee")) << out;
    EXPECT_NE(byName["neck"].find("cone "), std::string::npos) << byName["neck"];
    EXPECT_NE(byName["neck"].find(" in [0.0, 35.0]"), std::string::npos) << byName["neck"];
    EXPECT_NE(byName["lknee"].find("hinge "), std::string::npos) << byName["lknee"];
    EXPECT_NE(byName["lknee"].find(" in [-145.0, 5.0]"), std::string::npos) << byName["lknee"];
    EXPECT_EQ(out.find("PAST"), std::string::npos) << out;
    const std::regex reading("(-?[0-9.]+) in \\[(-?[0-9.]+), (-?[0-9.]+)\\]");
    for (const std::string& line : limits)
        for (std::sregex_iterator m(line.begin(), line.end(), reading), end; m != end; ++m) {
            EXPECT_GE(std::stod((*m)[1]), std::stod((*m)[2]) - 0.6) << line;
            EXPECT_LE(std::stod((*m)[1]), std::stod((*m)[3]) + 0.6) << line;
        }
    std::string names = "af_showConstraintNames ragdoll_humanoid_1:";
    for (const FigureConstraint& fc : f.constraints) names += " " + fc.name;
    EXPECT_NE(out.find(names + "\n"), std::string::npos) << out;
}

TEST(SessionShow, TreesIndentEachChildUnderItsParent) {
    ShowConsole c;
    c.run("spawn ragdoll_humanoid");
    const std::vector<std::string> tree = block(c.run("af_showTrees 1; step 0"), "af_showTrees ragdoll_humanoid_1:");
    const Figure& f = c.figure();
    ASSERT_EQ(tree.size(), f.bodies.size());
    EXPECT_EQ(tree.front(), "  " + f.bodies.front().name) << "the root first";
    // Every constraint joins a body to the nearest line above it indented one step less.
    std::map<std::string, std::string> parent;
    std::vector<std::string> path;
    for (const std::string& line : tree) {
        const std::size_t depth = line.find_first_not_of(' ') / 2 - 1;
        path.resize(depth);
        if (depth > 0) parent[line.substr(line.find_first_not_of(' '))] = path.back();
        path.push_back(line.substr(line.find_first_not_of(' ')));
    }
    for (const FigureConstraint& fc : f.constraints) {
        const std::string a = f.bodies[std::size_t(fc.body1)].name, b = f.bodies[std::size_t(fc.body2)].name;
        EXPECT_TRUE(parent[a] == b || parent[b] == a) << fc.name;
    }
}

// Each line: "  BODY - OTHER  at (x y z)  NORMAL, |FRICTION|". The step the humanoid came to rest
// in is the last the clock ran: its floor contacts' normal impulses hold its weight over the step.
TEST(SessionShow, ContactsOfARestingRagdollHoldItsWeight) {
    ShowConsole c;
    c.run("spawn ragdoll_humanoid; waitRest 5");
    const std::vector<std::string> contacts = block(c.run("af_showContacts 1; step 0"), "af_showContacts ragdoll_humanoid_1 ");
    ASSERT_FALSE(contacts.empty());
    const std::regex line(" +(\\w+) +- (\\w+)  at \\(.*\\)  ([0-9.]+), ([0-9.]+)");
    double floor = 0;
    int onFloor = 0;
    for (const std::string& text : contacts) {
        std::smatch m;
        ASSERT_TRUE(std::regex_match(text, m, line)) << text;
        EXPECT_GE(c.figure().findBody(m[1].str()), 0) << text;
        if (m[2].str() == "world") {
            floor += std::stod(m[3].str());
            ++onFloor;
        }
    }
    const World& world = c.session.world();
    Real mass = 0;
    for (const RigidBody& b : world.bodies()) mass += b.mass();
    const Real weight = mass * world.settings().gravity.norm() * world.settings().timeStep;
    // Each value is printed to 0.005; measured: 17 points, 3.7e-6 of the weight off.
    EXPECT_NEAR(floor, weight, 0.005 * onFloor);
}

TEST(SessionShow, ActiveLimitsTheBlocksToRagdollsNotAtRest) {
    ShowConsole c;
    c.run("spawn ragdoll_humanoid\nwaitRest 5\nspawn ragdoll_humanoid origin \"200 0 60\"");
    const std::string out = c.run("af_showTotalMass 1; af_showActive 1; step 1");
    EXPECT_EQ(out.find("ragdoll_humanoid_1"), std::string::npos) << out;
    EXPECT_NE(out.find("af_showTotalMass ragdoll_humanoid_2:"), std::string::npos) << out;
}

TEST(SessionShow, HighlightsNameTheirBodyAndConstraintOrSayThereIsNone) {
    ShowConsole c;
    c.run("spawn ragdoll_humanoid");
    std::string out = c.run("af_highlightBody rhand; af_highlightConstraint relbow; step 0");
    EXPECT_TRUE(std::regex_search(out, std::regex("af_highlightBody ragdoll_humanoid_1 rhand: [a-z]+ at \\(.*\\), mass [0-9.]+, v \\(")))
        << out;
    EXPECT_TRUE(std::regex_search(out, std::regex("af_highlightConstraint ragdoll_humanoid_1 relbow: hinge  rloarm - ruparm  at \\(")))
        << out;
    EXPECT_NE(out.find("; hinge "), std::string::npos) << out;
    out = c.run("af_highlightBody tail; reset af_highlightConstraint; step 0");
    EXPECT_EQ(out, "af_highlightBody: no ragdoll shown has a body named tail\n");
}

TEST(SessionShow, TimingsSummariseTheStepsOfEachClockCommand) {
    ShowConsole c;
    c.run("spawn ragdoll_humanoid");
    const std::regex summary("af_showTimings: ([0-9]+) steps?, [0-9]+\\.[0-9]{2} ms \\([0-9]+\\.[0-9]{2} ms a step, longest [0-9]+\\.[0-9]{2}\\)\n");
    std::smatch m;
    std::string out = c.run("af_showTimings 1; step 3");
    ASSERT_TRUE(std::regex_match(out, m, summary)) << out;
    EXPECT_EQ(m[1], "3");
    out = c.run("run 0.5");
    ASSERT_TRUE(std::regex_match(out, m, summary)) << out;
    EXPECT_EQ(m[1], "30");
    EXPECT_EQ(c.run("step 0"), "af_showTimings: 0 steps, 0.00 ms\n");
    out = c.run("step");
    EXPECT_TRUE(std::regex_match(out, std::regex("af_showTimings: 1 step, .*\n"))) << out;
}

TEST(SessionShow, ShowCvarsAreBoolsAndRefuseOtherValues) {
    ShowConsole c;
    const ExecuteResult r = c.commands.execute("af_showMass maybe", "test.cfg");
    EXPECT_EQ(r.errors, 1u);
    EXPECT_EQ(std::count(c.errors.begin(), c.errors.end(), '\n'), 1) << c.errors;
    EXPECT_FALSE(c.commands.cvars().find("af_showMass")->asBool());
}

}  // namespace
}  // namespace af::console
