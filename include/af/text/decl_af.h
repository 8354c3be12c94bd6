#pragma once
// Plain data for `.af` articulated-figure decls: what the file said, nothing resolved.
// Field meanings, defaults and quirks follow docs/formats.md §1.4–§1.9.
//
// Numbers are held at float precision (each value is a float widened to af::Real), because
// that is what Doom's lexer produces and what the canonical writer prints back exactly. Vectors
// stay symbolic (`joint( "J" )`, ...) until the figure stage resolves them against a skeleton.

#include "af/text/diagnostics.h"
#include "af/types.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace af {

// Contents and clip-mask bits, with Doom 3's values (Material.h).
using ContentsMask = std::uint32_t;
namespace contents {
constexpr ContentsMask Solid = 1u << 0;
constexpr ContentsMask Opaque = 1u << 1;
constexpr ContentsMask Water = 1u << 2;
constexpr ContentsMask PlayerClip = 1u << 3;
constexpr ContentsMask MonsterClip = 1u << 4;
constexpr ContentsMask MoveableClip = 1u << 5;
constexpr ContentsMask IkClip = 1u << 6;
constexpr ContentsMask Blood = 1u << 7;
constexpr ContentsMask Body = 1u << 8;
constexpr ContentsMask Projectile = 1u << 9;
constexpr ContentsMask Corpse = 1u << 10;
constexpr ContentsMask RenderModel = 1u << 11;
constexpr ContentsMask Trigger = 1u << 12;
constexpr ContentsMask AasSolid = 1u << 13;
constexpr ContentsMask AasObstacle = 1u << 14;
constexpr ContentsMask FlashlightTrigger = 1u << 15;
}  // namespace contents

// One vector value in its written form (docs/formats.md §1.4).
struct AFVector {
    enum class Kind : std::uint8_t { Coordinates, Joint, BoneCenter, BoneDir };

    Kind kind = Kind::Coordinates;
    bool negated = false;      // a leading `-`
    Real3 coordinates{};       // Kind::Coordinates
    std::string joint1;        // Joint, BoneCenter, BoneDir
    std::string joint2;        // BoneCenter, BoneDir
    SourceLocation where;      // not part of the value

    static AFVector literal(Real x, Real y, Real z) { return {Kind::Coordinates, false, {x, y, z}, {}, {}, {}}; }
    // Written as coordinates that are all zero (a symbolic vector is never known to be zero here).
    bool isZeroLiteral() const;

    friend bool operator==(const AFVector& a, const AFVector& b) {
        return a.kind == b.kind && a.negated == b.negated && a.coordinates == b.coordinates &&
               a.joint1 == b.joint1 && a.joint2 == b.joint2;
    }
};

enum class ShapeType : std::uint8_t { Box, Octahedron, Dodecahedron, Cylinder, Cone, Bone, Custom };

// A body's `model` (docs/formats.md §1.6). For box, octahedron, dodecahedron, cylinder and cone,
// v1 and v2 are the min and max corners in body-local coordinates; for bone they are the two
// model-space end points. numSides is kept as written (the shape builder clamps it), width is
// the bone's.
struct AFShape {
    ShapeType type = ShapeType::Box;
    AFVector v1 = AFVector::literal(-10, -10, -10);
    AFVector v2 = AFVector::literal(10, 10, 10);
    int numSides = 3;
    Real width = 0;
    std::string customName;  // custom( "NAME" ): parsed and kept, never built
    SourceLocation where;    // of the shape word; not part of the value (none for the default box)

    friend bool operator==(const AFShape& a, const AFShape& b) {
        return a.type == b.type && a.v1 == b.v1 && a.v2 == b.v2 && a.numSides == b.numSides &&
               a.width == b.width && a.customName == b.customName;
    }
};

// How a body drives its skeleton joint (docs/figures.md §3.6).
enum class JointMod : std::uint8_t { Orientation, Position, Both };

// Keywords of later id Tech 4 games (Quake 4, Enemy Territory: Quake Wars) that we read and
// write back but do not act on.
struct AFExtensions {
    bool fastEval = false;  // settings: a bare `fastEval`

    friend bool operator==(const AFExtensions&, const AFExtensions&) = default;
};

struct AFSettings {
    std::string model;
    std::string skin;
    Real linearFriction = Real(0.01f);
    Real angularFriction = Real(0.01f);
    Real contactFriction = Real(0.8f);
    // Seeds editor-made constraints only (docs/formats.md §1.7).
    Real constraintFriction = Real(0.5f);
    Real suspendLinearVelocity = 20;       // units/s
    Real suspendAngularVelocity = 30;      // rad/s
    Real suspendLinearAcceleration = 40;   // units/s²
    Real suspendAngularAcceleration = 60;  // rad/s²
    Real noMoveTime = 1;                   // s
    Real noMoveTranslation = 10;           // units
    Real noMoveRotation = 10;              // degrees
    Real minMoveTime = -1;                 // s; <= 0 disables
    Real maxMoveTime = -1;                 // s; <= 0 disables
    Real totalMass = -1;                   // > 0 rescales every body
    ContentsMask contents = contents::Corpse;
    ContentsMask clipMask = contents::Solid | contents::Corpse;
    // Names in the lists that are none of Doom 3's contents flags (later games of the engine
    // family add their own: `movableclip`, `flyerhiveclip`, ...), as written and in order: they
    // have no effect here and are written back after the known names (docs/formats.md §1.9).
    std::vector<std::string> unknownContents;
    std::vector<std::string> unknownClipMask;
    bool selfCollision = true;
    AFExtensions extensions;

    friend bool operator==(const AFSettings&, const AFSettings&) = default;
};

struct AFBody {
    std::string name;
    std::string joint;  // the skeleton joint it drives; "origin" marks the root body
    JointMod mod = JointMod::Orientation;
    AFShape shape;
    AFVector origin;
    Real3 angles{};  // pitch, yaw, roll in degrees; ignored for bones
    Real density = Real(0.2f);
    std::array<Real, 9> inertiaScale{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major
    Real linearFriction = 0;
    Real angularFriction = 0;
    Real contactFriction = 0;
    ContentsMask contents = 0;
    ContentsMask clipMask = 0;  // MoveableClip is always added by the parser
    std::vector<std::string> unknownContents;  // as AFSettings::unknownContents
    std::vector<std::string> unknownClipMask;
    bool selfCollision = true;
    std::string containedJoints = "*origin";
    std::optional<AFVector> frictionDirection;      // fixed to the body
    std::optional<AFVector> contactMotorDirection;  // fixed to the body; inert for .af figures
    SourceLocation where;                           // of the body's name
    SourceLocation densityWhere;                    // of its value; none when not written
    SourceLocation inertiaScaleWhere;               // of its `(`; none when not written

    friend bool operator==(const AFBody& a, const AFBody& b) {
        return a.name == b.name && a.joint == b.joint && a.mod == b.mod && a.shape == b.shape &&
               a.origin == b.origin && a.angles == b.angles && a.density == b.density &&
               a.inertiaScale == b.inertiaScale && a.linearFriction == b.linearFriction &&
               a.angularFriction == b.angularFriction && a.contactFriction == b.contactFriction &&
               a.contents == b.contents && a.clipMask == b.clipMask && a.unknownContents == b.unknownContents &&
               a.unknownClipMask == b.unknownClipMask && a.selfCollision == b.selfCollision &&
               a.containedJoints == b.containedJoints && a.frictionDirection == b.frictionDirection &&
               a.contactMotorDirection == b.contactMotorDirection;
    }
};

enum class ConstraintType : std::uint8_t { Fixed, BallAndSocket, Universal, Hinge, Slider, Spring };
enum class LimitType : std::uint8_t { None, Cone, Pyramid };

// One constraint block (docs/formats.md §1.7). Which fields mean something depends on the type:
//  fixed        body1, body2
//  ball/socket  anchor, friction, limit (cone: limitAxis, limitAngles[0], shafts[0];
//               pyramid: limitAxis, limitAngles[0..2], shafts[0])
//  universal    anchor, shafts[0..1], friction, limit (cone: limitAxis, limitAngles[0];
//               pyramid: limitAxis, limitAngles[0..2]); the limit acts on shafts[0]
//  hinge        anchor, axis, friction, limit Cone with limitAngles = (centre, width, shaft)
//  slider       axis, friction (parsed, unused by Doom)
//  spring       anchor (anchor1), anchor2, friction (unused), the spring values
struct AFConstraint {
    ConstraintType type = ConstraintType::Fixed;
    std::string name;
    std::string body1;  // the constrained body, normally the child
    std::string body2;  // the body it hangs on, or "world"
    AFVector anchor;
    AFVector anchor2;
    std::array<AFVector, 2> shafts{AFVector::literal(0, 0, -1), AFVector::literal(0, 0, 1)};
    AFVector axis = AFVector::literal(1, 0, 0);
    LimitType limit = LimitType::None;
    AFVector limitAxis = AFVector::literal(0, 0, -1);
    Real3 limitAngles{};  // degrees
    Real friction = Real(0.5f);
    Real stretch = 0;
    Real compress = 0;
    Real damping = 0;
    Real restLength = 0;
    Real minLength = 0;
    Real maxLength = 0;
    SourceLocation where;        // of the constraint's name
    SourceLocation body1Where;   // of the body1 value, or of the name when defaulted
    SourceLocation body2Where;

    friend bool operator==(const AFConstraint& a, const AFConstraint& b) {
        return a.type == b.type && a.name == b.name && a.body1 == b.body1 && a.body2 == b.body2 &&
               a.anchor == b.anchor && a.anchor2 == b.anchor2 && a.shafts == b.shafts && a.axis == b.axis &&
               a.limit == b.limit && a.limitAxis == b.limitAxis && a.limitAngles == b.limitAngles &&
               a.friction == b.friction && a.stretch == b.stretch && a.compress == b.compress &&
               a.damping == b.damping && a.restLength == b.restLength && a.minLength == b.minLength &&
               a.maxLength == b.maxLength;
    }
};

// One `articulatedFigure NAME { ... }` decl. The body whose joint is "origin" is at index 0.
struct DeclAF {
    std::string name;  // canonical: lower case, `/` separators, no extension
    AFSettings settings;
    std::vector<AFBody> bodies;
    std::vector<AFConstraint> constraints;
    SourceLocation where;

    const AFBody* findBody(std::string_view bodyName) const;
    const AFConstraint* findConstraint(std::string_view constraintName) const;

    friend bool operator==(const DeclAF& a, const DeclAF& b) {
        return a.name == b.name && a.settings == b.settings && a.bodies == b.bodies &&
               a.constraints == b.constraints;
    }
};

// Every decl of one file, in file order.
struct AFFile {
    std::string path;
    std::vector<DeclAF> decls;

    const DeclAF* findDecl(std::string_view name) const;  // case-insensitive, extension ignored

    friend bool operator==(const AFFile& a, const AFFile& b) { return a.decls == b.decls; }
};

const char* toString(ShapeType type);
const char* toString(JointMod mod);
const char* toString(ConstraintType type);
const char* toString(LimitType type);

}  // namespace af
