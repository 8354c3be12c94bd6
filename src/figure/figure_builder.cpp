// From decl to figure: the load sequence of docs/figures.md §3.1–§3.5.

#include "af/geometry/mass_properties.h"
#include "af/text/strings.h"
#include "figure_build_context.h"

#include <cmath>

namespace af {

namespace {

ShapeKind shapeKindOf(ShapeType type) {
    switch (type) {
    case ShapeType::Octahedron: return ShapeKind::octahedron;
    case ShapeType::Dodecahedron: return ShapeKind::dodecahedron;
    case ShapeType::Cylinder: return ShapeKind::cylinder;
    case ShapeType::Cone: return ShapeKind::cone;
    case ShapeType::Bone: return ShapeKind::bone;
    case ShapeType::Box:
    case ShapeType::Custom: break;
    }
    return ShapeKind::box;
}

// The joint a body drives (docs/figures.md §3.6): its own, except the root body, which drives the first child
// of the `origin` joint (or of the skeleton's root when there is no `origin` joint).
int drivenJoint(const Skeleton& skeleton, const AFBody& body) {
    if (body.joint != "origin") return skeleton.find(body.joint);
    int origin = skeleton.find("origin");
    if (origin < 0) origin = 0;
    for (std::size_t k = 0; k < skeleton.size(); ++k)
        if (skeleton.parents[k] == origin) return static_cast<int>(k);
    return origin;
}

}  // namespace

Vec3 FigureBuildContext::jointPosition(const std::string& name, SourceLocation where) {
    const int j = skeleton.find(name);
    if (j >= 0) return skeleton.joints[static_cast<std::size_t>(j)].position;
    diagnostics.warning(where, "joint \"" + name + "\" is not in the skeleton; (0, 0, 0) is used, as in Doom 3");
    return Vec3::Zero();
}

Vec3 FigureBuildContext::resolve(const AFVector& v) {
    Vec3 out;
    switch (v.kind) {
    case AFVector::Kind::Coordinates: out = Vec3(v.coordinates[0], v.coordinates[1], v.coordinates[2]); break;
    case AFVector::Kind::Joint: out = jointPosition(v.joint1, v.where); break;
    case AFVector::Kind::BoneCenter:
        out = 0.5 * (jointPosition(v.joint1, v.where) + jointPosition(v.joint2, v.where));
        break;
    case AFVector::Kind::BoneDir: out = jointPosition(v.joint2, v.where) - jointPosition(v.joint1, v.where); break;
    }
    return v.negated ? Vec3(-out) : out;
}

Vec3 FigureBuildContext::worldDirection(const AFVector& v, const std::string& what) {
    const Vec3 d = placement.rotation * resolve(v);
    const Real length = d.norm();
    if (!(length > 1e-9)) {
        diagnostics.error(v.where, what + " is a zero vector on this skeleton, so the joint cannot be simulated");
        return Vec3::UnitZ();
    }
    return d / length;
}

void buildBodies(FigureBuildContext& context, Figure& figure) {
    std::vector<MassProperties> masses;
    std::vector<const AFBody*> declBody;  // of each figure body: custom ones are skipped
    for (const AFBody& b : context.decl.bodies) {
        const std::string label = "body \"" + b.name + "\"";
        if (b.shape.type == ShapeType::Custom) {
            context.diagnostics.error(b.where, label + ": custom models are not supported; use box, octahedron, "
                                                       "dodecahedron, cylinder, cone or bone");
            continue;
        }
        ShapeSpec spec;
        spec.kind = shapeKindOf(b.shape.type);
        spec.v1 = context.resolve(b.shape.v1);
        spec.v2 = context.resolve(b.shape.v2);
        spec.sides = b.shape.numSides;
        spec.width = b.shape.width;
        spec.origin = context.resolve(b.origin);
        spec.angles = Vec3(b.angles[0], b.angles[1], b.angles[2]);
        const BodyShape built = buildShape(spec);
        const SourceLocation shapeWhere = b.shape.where.line ? b.shape.where : b.where;
        for (const std::string& w : built.warnings) context.diagnostics.warning(shapeWhere, label + ": " + w);
        // Doom's trace model raises too few sides to its minimum and says so; so do we.
        if ((spec.kind == ShapeKind::cylinder || spec.kind == ShapeKind::cone) && built.sides > spec.sides)
            context.diagnostics.warning(shapeWhere, label + ": " + toString(b.shape.type) + " has " +
                                                        std::to_string(spec.sides) + " sides; " +
                                                        std::to_string(built.sides) + " are used, as in Doom 3");

        MassProperties mp = massProperties(built.local, b.density);
        guardShape(context, b, built.local, mp.status);
        const Mat3 scale = Eigen::Map<const Eigen::Matrix<Real, 3, 3, Eigen::RowMajor>>(b.inertiaScale.data());
        mp.inertia = applyInertiaScale(mp.inertia, scale);
        const BodyShape centred = recentred(built, mp.centreOfMass);

        FigureBody body;
        body.name = b.name;
        body.shapeKind = spec.kind;
        body.sides = built.sides;
        body.shape = centred.local;
        body.volume = volumeProperties(centred.local).volume;
        body.inertia = mp.inertia;
        const RigidPose modelPose{centred.origin, centred.rotation};
        body.pose = context.placement * modelPose;
        body.mod = b.mod;
        body.joint = drivenJoint(context.skeleton, b);
        if (body.joint >= 0) {
            const JointTransform& j = context.skeleton.joints[static_cast<std::size_t>(body.joint)];
            body.bodyInJoint = RigidPose{j.position, j.rotation}.inverse() * modelPose;
        } else {
            context.diagnostics.warning(b.where, label + ": joint \"" + b.joint +
                                                     "\" is not in the skeleton; the body drives no joint");
        }
        if (b.joint == "origin") body.mod = JointMod::Orientation;
        body.linearFriction = b.linearFriction;
        body.angularFriction = b.angularFriction;
        body.contactFriction = b.contactFriction;
        body.contents = b.contents;
        body.clipMask = b.clipMask;
        body.selfCollision = b.selfCollision;
        // Directions are fixed to the body: store them in its frame.
        if (b.frictionDirection) body.frictionDirection = modelPose.rotation.transpose() * context.resolve(*b.frictionDirection);
        if (b.contactMotorDirection)
            body.contactMotorDirection = modelPose.rotation.transpose() * context.resolve(*b.contactMotorDirection);
        body.where = b.where;
        figure.bodies.push_back(std::move(body));
        masses.push_back(mp);
        declBody.push_back(&b);
    }
    const Real scale = totalMassScale(masses, context.decl.settings.totalMass);
    for (std::size_t i = 0; i < figure.bodies.size(); ++i) {
        figure.bodies[i].mass = masses[i].mass * scale;
        figure.bodies[i].inertia = masses[i].inertia * scale;
        guardInertia(context, *declBody[i], figure.bodies[i].mass, figure.bodies[i].inertia);
    }
}

Real Figure::totalMass() const {
    Real sum = 0;
    for (const FigureBody& b : bodies) sum += b.mass;
    return sum;
}

int Figure::findBody(std::string_view bodyName) const {
    for (std::size_t i = 0; i < bodies.size(); ++i)
        if (bodies[i].name == bodyName) return static_cast<int>(i);
    return -1;
}

std::string FigureResult::formatDiagnostics() const {
    std::string out;
    for (const Diagnostic& d : diagnostics) out += d.format() + "\n";
    return out;
}

FigureResult buildFigure(const DeclAF& decl, const Skeleton& afPose, const std::string& afFile,
                         const RigidPose& placement) {
    FigureBuildContext context{decl, afPose, placement, Diagnostics(afFile)};
    Figure figure;
    figure.name = decl.name;
    figure.settings = decl.settings;
    figure.afPose = afPose;
    figure.placement = placement;
    if (decl.bodies.empty() || decl.bodies[0].joint != "origin")
        context.diagnostics.error(decl.where, "figure \"" + decl.name + "\" has no root body with joint \"origin\"");
    buildBodies(context, figure);
    buildConstraints(context, figure);
    claimJoints(context, figure);
    if (!context.diagnostics.hasErrors()) checkFigure(context, figure);
    context.diagnostics.sortByPosition();

    FigureResult result;
    result.diagnostics = context.diagnostics.all();
    if (!context.diagnostics.hasErrors()) result.figure = std::move(figure);
    return result;
}

}  // namespace af
