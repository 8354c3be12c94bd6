#include "af/text/decl_af.h"

#include "af/text/strings.h"

namespace af {

bool AFVector::isZeroLiteral() const {
    return kind == Kind::Coordinates && coordinates[0] == 0 && coordinates[1] == 0 && coordinates[2] == 0;
}

const AFBody* DeclAF::findBody(std::string_view bodyName) const {
    for (const AFBody& b : bodies)
        if (b.name == bodyName) return &b;
    return nullptr;
}

const AFConstraint* DeclAF::findConstraint(std::string_view constraintName) const {
    for (const AFConstraint& c : constraints)
        if (c.name == constraintName) return &c;
    return nullptr;
}

const DeclAF* AFFile::findDecl(std::string_view name) const {
    const std::string wanted = canonicalDeclName(name);
    for (const DeclAF& d : decls)
        if (d.name == wanted) return &d;
    return nullptr;
}

const char* toString(ShapeType type) {
    switch (type) {
    case ShapeType::Box: return "box";
    case ShapeType::Octahedron: return "octahedron";
    case ShapeType::Dodecahedron: return "dodecahedron";
    case ShapeType::Cylinder: return "cylinder";
    case ShapeType::Cone: return "cone";
    case ShapeType::Bone: return "bone";
    case ShapeType::Custom: return "custom";
    }
    return "?";
}

const char* toString(JointMod mod) {
    switch (mod) {
    case JointMod::Orientation: return "orientation";
    case JointMod::Position: return "position";
    case JointMod::Both: return "both";
    }
    return "?";
}

const char* toString(ConstraintType type) {
    switch (type) {
    case ConstraintType::Fixed: return "fixed";
    case ConstraintType::BallAndSocket: return "ballAndSocketJoint";
    case ConstraintType::Universal: return "universalJoint";
    case ConstraintType::Hinge: return "hinge";
    case ConstraintType::Slider: return "slider";
    case ConstraintType::Spring: return "spring";
    }
    return "?";
}

const char* toString(LimitType type) {
    switch (type) {
    case LimitType::None: return "none";
    case LimitType::Cone: return "cone";
    case LimitType::Pyramid: return "pyramid";
    }
    return "?";
}

}  // namespace af
