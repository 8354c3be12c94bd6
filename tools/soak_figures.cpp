#include "soak_figures.h"

#include "af/text/af_parser.h"
#include "af/text/af_writer.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace af::soak {

namespace {

// A number as the .af lexer reads it: fixed notation (no exponent, no leading zeros).
std::string num(Real value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.4f", static_cast<double>(value));
    return buffer;
}

std::string vec(const Vec3& v) { return "( " + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + " )"; }

// The largest mass ratio across a constraint between two bodies of the figure.
Real largestMassRatio(const Figure& figure) {
    Real ratio = 1;
    for (const FigureConstraint& c : figure.constraints) {
        if (c.body2 == kWorld) continue;
        const Real a = figure.bodies[static_cast<std::size_t>(c.body1)].mass;
        const Real b = figure.bodies[static_cast<std::size_t>(c.body2)].mass;
        ratio = std::max(ratio, std::max(a / b, b / a));
    }
    return ratio;
}

// Parses `text` and builds its one decl on `afPose`: the text stage and the figure stage, as a
// user's file goes through them.
void build(MadeFigure& made, const Skeleton& afPose, const std::string& file) {
    AFParseResult parsed = parseAF(made.text, file);
    if (!parsed.ok() || parsed.file.decls.size() != 1) {
        made.error = "parse: " + parsed.diagnostics.formatAll();
        return;
    }
    FigureResult built = buildFigure(parsed.file.decls.front(), afPose, file);
    if (!built.ok()) {
        made.error = "build: " + built.formatDiagnostics();
        return;
    }
    made.notes.push_back(format("largest mass ratio across a joint 1:%.3g", static_cast<double>(largestMassRatio(*built.figure))));
    made.notes.push_back(format("total mass %.6g", static_cast<double>(built.figure->totalMass())));
    made.figure = std::make_shared<const Figure>(std::move(*built.figure));
}

}  // namespace

std::vector<SampleFigure> sampleFigures(const ResourceIndex& index) {
    std::vector<SampleFigure> samples;
    for (const std::shared_ptr<const FigureEntry>& entry : index.figures()) {
        const AFResources resources = index.resolveFigure(entry->decl.name);
        if (!resources.ok()) continue;
        samples.push_back({entry->decl.name, entry, afPoseSkeleton(resources)});
    }
    return samples;
}

MadeFigure editedSample(const SampleFigure& sample, Random& random) {
    MadeFigure made;
    made.label = sample.name;
    DeclAF decl = sample.entry->decl;
    if (random.chance(0.5)) {
        for (AFBody& body : decl.bodies) body.density *= random.decades(-1.5, 1.5);
        made.notes.push_back("densities scaled by 10^U(-1.5, 1.5) each");
    }
    if (random.chance(0.3)) {
        decl.settings.totalMass = random.decades(0, 4);
        made.notes.push_back(format("totalMass %.6g", static_cast<double>(decl.settings.totalMass)));
    }
    for (AFConstraint& c : decl.constraints) {
        if (c.type != ConstraintType::Spring || !random.chance(0.5)) continue;
        const Real stiffer = random.decades(0, 6);
        c.stretch *= stiffer;
        c.compress *= stiffer;
        made.notes.push_back("spring " + c.name + format(" stiffened x%.3g", static_cast<double>(stiffer)));
    }
    made.text = writeDecl(decl);
    build(made, sample.afPose, sample.entry->file);
    return made;
}

MadeFigure generatedChain(Random& random) {
    const int count = random.between(2, 8);
    MadeFigure made;
    made.label = "chain" + std::to_string(count);
    Skeleton skeleton;
    skeleton.names = {"origin"};
    skeleton.parents = {-1};
    skeleton.joints = {JointTransform{}};

    std::ostringstream text;
    text << "articulatedFigure soakchain {\nsettings {\n\tmodel \"\"\n";
    if (random.chance(0.3)) text << "\ttotalMass " << num(random.decades(0, 4)) << "\n";
    text << "\tcontents corpse\n\tclipMask solid, corpse\n\tselfCollision " << (random.chance(0.5) ? 1 : 0) << "\n}\n";

    const bool lopsided = random.chance(0.5);
    std::vector<Real> halfLength(static_cast<std::size_t>(count));
    std::vector<Vec3> centre(static_cast<std::size_t>(count));
    std::vector<Real> gapAfter(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) {
        const auto i = static_cast<std::size_t>(k);
        halfLength[i] = random.uniform(0.5, 6);
        const Real hy = random.uniform(0.25, 4), hz = random.uniform(0.25, 4);
        gapAfter[i] = random.uniform(-1, 1);  // negative: the next body starts inside this one
        centre[i] = k == 0 ? Vec3(Vec3::Zero())
                           : Vec3(centre[i - 1] + Vec3(halfLength[i - 1] + gapAfter[i - 1] + halfLength[i], 0, 0));
        const std::string joint = "b" + std::to_string(k);
        skeleton.names.push_back(joint);
        skeleton.parents.push_back(k);  // b0's parent is origin, bk's is b(k-1)
        skeleton.joints.push_back(JointTransform{centre[i], Mat3::Identity()});

        text << "body \"" << joint << "\" {\n\tjoint \"" << (k == 0 ? "origin" : joint.c_str()) << "\"\n\tmod orientation\n";
        const Vec3 h(halfLength[i], hy, hz);
        switch (random.between(0, 5)) {
        case 0: text << "\tmodel box( " << vec(-h) << ", " << vec(h) << " )\n"; break;
        case 1: text << "\tmodel octahedron( " << vec(-h) << ", " << vec(h) << " )\n"; break;
        case 2: text << "\tmodel dodecahedron( " << vec(-h) << ", " << vec(h) << " )\n"; break;
        case 3: text << "\tmodel cylinder( " << vec(-h) << ", " << vec(h) << ", " << random.between(3, 10) << " )\n"; break;
        case 4: text << "\tmodel cone( " << vec(-h) << ", " << vec(h) << ", " << random.between(3, 15) << " )\n"; break;
        default:
            text << "\tmodel bone( " << vec(centre[i] - Vec3(halfLength[i], 0, 0)) << ", "
                 << vec(centre[i] + Vec3(halfLength[i], 0, 0)) << ", " << num(2 * hy) << " )\n";
        }
        text << "\torigin " << vec(centre[i]) << "\n";
        if (random.chance(0.3))
            text << "\tangles ( " << num(random.uniform(-90, 90)) << ", " << num(random.uniform(0, 360)) << ", "
                 << num(random.uniform(0, 360)) << " )\n";
        text << "\tdensity " << num(lopsided ? 0.2 * random.decades(-1.5, 1.5) : random.uniform(0.1, 1)) << "\n";
        text << "\tcontainedJoints \"" << (k == 0 ? "origin b0" : joint.c_str()) << "\"\n}\n";
    }
    if (lopsided) made.notes.push_back("densities 0.2 x 10^U(-1.5, 1.5) each");

    static constexpr const char* kKinds[] = {"ball", "ball+cone", "ball+pyramid", "universal", "universal+cone",
                                             "hinge", "hinge+limit", "fixed", "slider", "spring"};
    std::string kinds;
    for (int k = 1; k < count; ++k) {
        const auto i = static_cast<std::size_t>(k);
        const Vec3 anchor = centre[i - 1] + Vec3(halfLength[i - 1] + gapAfter[i - 1] / 2, 0, 0);
        const std::string name = "j" + std::to_string(k);
        const std::string bodies = "\tbody1 \"b" + std::to_string(k) + "\"\n\tbody2 \"b" + std::to_string(k - 1) + "\"\n";
        const int kind = random.between(0, 9);
        kinds += std::string(kinds.empty() ? "" : " ") + kKinds[kind];
        switch (kind) {
        case 0: case 1: case 2:
            text << "ballAndSocketJoint \"" << name << "\" {\n" << bodies << "\tanchor " << vec(anchor) << "\n";
            if (kind == 1) text << "\tconeLimit ( 1, 0, 0 ), " << num(random.uniform(5, 170)) << ", ( 1, 0, 0 )\n";
            if (kind == 2)
                text << "\tpyramidLimit ( 1, 0, 0 ), " << num(random.uniform(5, 170)) << ", " << num(random.uniform(5, 170))
                     << ", " << num(random.uniform(-90, 90)) << ", ( 1, 0, 0 )\n";
            break;
        case 3: case 4:
            text << "universalJoint \"" << name << "\" {\n" << bodies << "\tanchor " << vec(anchor)
                 << "\n\tshafts ( 1, 0, 0 ), ( -1, 0, 0 )\n";
            if (kind == 4) text << "\tconeLimit ( 1, 0, 0 ), " << num(random.uniform(5, 170)) << "\n";
            break;
        case 5: case 6:
            text << "hinge \"" << name << "\" {\n" << bodies << "\tanchor " << vec(anchor) << "\n\taxis "
                 << vec(random.direction()) << "\n";
            if (kind == 6)
                text << "\tlimit " << num(random.uniform(-90, 90)) << ", " << num(random.uniform(5, 300)) << ", 0\n";
            break;
        case 7: text << "fixed \"" << name << "\" {\n" << bodies; break;
        case 8: text << "slider \"" << name << "\" {\n" << bodies << "\taxis " << vec(random.direction()) << "\n"; break;
        default: {
            const Vec3 a1 = centre[i], a2 = centre[i - 1];
            const Real length = (a1 - a2).norm();
            const Real stiffness = random.decades(1, 8);
            text << "spring \"" << name << "\" {\n" << bodies << "\tanchor1 " << vec(a1) << "\n\tanchor2 " << vec(a2)
                 << "\n\tstretch " << num(stiffness) << "\n\tcompress " << num(stiffness) << "\n\tdamping "
                 << num(random.uniform(0, 100)) << "\n\trestLength " << num(length * random.uniform(0.5, 1.5))
                 << "\n\tminLength " << num(length * 0.25) << "\n\tmaxLength " << num(length * 2) << "\n";
            made.notes.push_back(name + format(" spring stiffness %.3g", static_cast<double>(stiffness)));
        }
        }
        text << "}\n";
    }
    if (random.chance(0.25)) {
        text << "ballAndSocketJoint \"hook\" {\n\tbody1 \"b0\"\n\tbody2 \"world\"\n\tanchor "
             << vec(centre[0] - Vec3(halfLength[0], 0, 0)) << "\n}\n";
        kinds += " +hook";
    }
    text << "}\n";
    made.notes.push_back("joints: " + kinds);
    made.text = text.str();
    build(made, skeleton, "soakchain.af");
    return made;
}

}  // namespace af::soak
