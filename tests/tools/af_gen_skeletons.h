// Made-up skeletons for af-gen's tests, written as md5mesh text: a chain, a quadruped, and a
// 100-joint character. Included by af_gen_test.cpp alone.

#pragma once

#include "af/geometry/math.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace af::test::gen {

struct SynthJoint {
    std::string name;
    int parent = -1;
    af::Vec3 position = af::Vec3::Zero();
    double radius = 0;  // > 0: mesh vertices around its bone (or around it, at an end), weighted to it
    af::Vec3 skin = af::Vec3::Zero();  // the bone the skin is around, when not to its first child
};

inline std::string number(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6f", x);
    return buffer;
}

inline std::string tuple(const af::Vec3& v) { return "( " + number(v.x()) + " " + number(v.y()) + " " + number(v.z()) + " )"; }

// The joints with identity orientations; each joint with a radius gets rings of vertices around
// its bone (to its first child, or a short stub on from its parent's bone at an end), each vertex
// weighted wholly to it. Weights are in the joint's frame, which is the model's here.
inline std::string md5meshText(const std::vector<SynthJoint>& joints) {
    std::vector<af::Vec3> vertices;
    std::vector<int> owners;
    for (std::size_t j = 0; j < joints.size(); ++j) {
        const SynthJoint& joint = joints[j];
        if (joint.radius <= 0) continue;
        af::Vec3 bone = joint.skin;
        for (const SynthJoint& child : joints)
            if (bone.isZero() && child.parent == static_cast<int>(j)) {
                bone = child.position - joint.position;
                break;
            }
        if (bone.isZero()) {
            const af::Vec3 in = joint.position - joints[static_cast<std::size_t>(joint.parent)].position;
            bone = in.normalized() * 2 * joint.radius;
        }
        const af::Vec3 d = bone.normalized();
        const af::Vec3 a = (std::fabs(d.z()) < 0.9 ? af::Vec3::UnitZ() : af::Vec3::UnitX()).cross(d).normalized();
        const af::Vec3 b = d.cross(a);
        for (double t : {0.15, 0.5, 0.85})
            for (int k = 0; k < 6; ++k) {
                const double phi = k * std::acos(-1.0) / 3;
                vertices.push_back(joint.position + t * bone + joint.radius * (std::cos(phi) * a + std::sin(phi) * b));
                owners.push_back(static_cast<int>(j));
            }
    }
    std::string text = "MD5Version 10\ncommandline \"af_gen_test\"\n\nnumJoints " + std::to_string(joints.size()) +
                       "\nnumMeshes " + std::string(vertices.empty() ? "0" : "1") + "\n\njoints {\n";
    for (const SynthJoint& j : joints)
        text += "\t\"" + j.name + "\"\t" + std::to_string(j.parent) + " " + tuple(j.position) + " ( 0 0 0 )\n";
    text += "}\n";
    if (vertices.empty()) return text;
    text += "\nmesh {\n\tshader \"skin\"\n\n\tnumverts " + std::to_string(vertices.size()) + "\n";
    for (std::size_t v = 0; v < vertices.size(); ++v)
        text += "\tvert " + std::to_string(v) + " ( 0 0 ) " + std::to_string(v) + " 1\n";
    text += "\n\tnumtris 0\n\n\tnumweights " + std::to_string(vertices.size()) + "\n";
    for (std::size_t v = 0; v < vertices.size(); ++v)
        text += "\tweight " + std::to_string(v) + " " + std::to_string(owners[v]) + " 1 " +
                tuple(vertices[v] - joints[static_cast<std::size_t>(owners[v])].position) + "\n";
    return text + "}\n";
}

struct Builder {
    std::vector<SynthJoint> joints;
    int add(const std::string& name, int parent, const af::Vec3& position, double radius = 0,
            const af::Vec3& skin = af::Vec3::Zero()) {
        joints.push_back({name, parent, position, radius, skin});
        return static_cast<int>(joints.size()) - 1;
    }
};

// Eight links along +x, 64 units up, the skin 1.5 units round: nothing in their names says what
// they are.
inline std::vector<SynthJoint> chain() {
    Builder s;
    int parent = s.add("origin", -1, af::Vec3::Zero());
    for (int i = 1; i <= 8; ++i) parent = s.add("link" + std::to_string(i), parent, af::Vec3(6.0 * (i - 1), 0, 64), 1.5);
    return s.joints;
}

// A centipede without skin: a spine of 19 segments along +x, each with a leg and a foot on
// either side, 96 joints and 57 bodies. It lands flat, with a contact or more under most bodies:
// more rows between the figure and the floor than a pivoting solve can take (docs/solver.md).
inline std::vector<SynthJoint> centipede() {
    Builder s;
    int spine = s.add("origin", -1, af::Vec3::Zero());
    for (int i = 0; i < 19; ++i) {
        const double x = 8.0 * i;
        spine = s.add("seg" + std::to_string(i), spine, af::Vec3(x, 0, 20));
        for (const double side : {1.0, -1.0}) {
            const std::string name = side > 0 ? "L" : "R";
            const int leg = s.add("leg" + name + std::to_string(i), spine, af::Vec3(x, 6 * side, 20));
            s.add("foot" + name + std::to_string(i), leg, af::Vec3(x, 10 * side, 14));
        }
    }
    return s.joints;
}

// A dog standing on four legs, facing +x, with a jaw and eyes in its head, toes on its paws and a
// tail: the grouping folds the end parts into their parents and the names give the joint kinds.
inline std::vector<SynthJoint> quadruped() {
    Builder s;
    const int origin = s.add("origin", -1, af::Vec3::Zero());
    const int hips = s.add("hips", origin, af::Vec3(-14, 0, 24), 5);
    const int spine = s.add("spine", hips, af::Vec3(0, 0, 25), 5);
    const int chest = s.add("chest", spine, af::Vec3(14, 0, 25), 5.5);
    const int neck = s.add("neck", chest, af::Vec3(20, 0, 30), 3);
    const int head = s.add("head", neck, af::Vec3(24, 0, 36), 3.5);
    s.add("jaw", head, af::Vec3(27, 0, 33), 1.5);
    s.add("eye_l", head, af::Vec3(28, 2, 37));
    s.add("eye_r", head, af::Vec3(28, -2, 37));
    const int tail1 = s.add("tail1", hips, af::Vec3(-22, 0, 26), 1.5);
    const int tail2 = s.add("tail2", tail1, af::Vec3(-30, 0, 28), 1);
    s.add("tail3", tail2, af::Vec3(-37, 0, 31));
    for (const char side : {'l', 'r'}) {
        const double y = side == 'l' ? 5 : -5;
        const std::string sfx = std::string("_") + side;
        int j = s.add("shoulder" + sfx, chest, af::Vec3(14, y, 22), 2.5);
        j = s.add("elbow" + sfx, j, af::Vec3(13, y, 12), 2);
        j = s.add("frontpaw" + sfx, j, af::Vec3(13, y, 2), 1.5);
        s.add("fronttoe" + sfx, j, af::Vec3(16, y, 0.5));
        j = s.add("thigh" + sfx, hips, af::Vec3(-14, y, 21), 3);
        j = s.add("knee" + sfx, j, af::Vec3(-12, y, 11), 2);
        j = s.add("hindpaw" + sfx, j, af::Vec3(-14, y, 2), 1.5);
        s.add("hindtoe" + sfx, j, af::Vec3(-11, y, 0.5));
    }
    return s.joints;
}

// 100 joints, as a game's character has them: most are fingers, toes, the face, attachment tags
// and a ponytail of short bones, which the grouping folds into 18 bodies (a spine of three, a
// neck, a head, the limbs). The face, the ears and the tags carry no skin.
inline std::vector<SynthJoint> detailedHumanoid() {
    Builder s;
    const int origin = s.add("origin", -1, af::Vec3::Zero());
    const int pelvis = s.add("pelvis", origin, af::Vec3(0, 0, 37), 5);
    const int spine1 = s.add("spine1", pelvis, af::Vec3(0, 0, 41), 4.5);
    const int spine2 = s.add("spine2", spine1, af::Vec3(0, 0, 46), 4.5);
    const int spine3 = s.add("spine3", spine2, af::Vec3(0, 0, 51), 5);
    const int neck = s.add("neck", spine3, af::Vec3(0, 0, 58), 2);
    const int head = s.add("head", neck, af::Vec3(0, 0, 62), 3.5, af::Vec3(0, 0, 8));
    for (const char* face : {"jaw", "tongue", "eye_l", "eye_r", "lid_l_up", "lid_l_dn", "lid_r_up", "lid_r_dn",
                             "brow_l", "brow_r", "lip_up", "lip_dn", "lip_l", "lip_r", "cheek_l", "cheek_r", "nose"})
        s.add(face, head, af::Vec3(3.5, 0, 64));
    for (const char* ear : {"ear_l", "ear_r"}) s.add(ear, head, af::Vec3(0, 0, 63));
    int tail = head;
    for (int i = 1; i <= 5; ++i) tail = s.add("ponytail" + std::to_string(i), tail, af::Vec3(-3.5 - 1.5 * i, 0, 66 - 1.5 * i), 0.5);
    for (const char* tag : {"tag_back", "tag_belt", "tag_head"}) s.add(tag, spine3, af::Vec3(-4, 0, 50));
    for (const double y : {1.0, -1.0}) {
        const std::string sfx = y > 0 ? "_l" : "_r";
        const int clavicle = s.add("clavicle" + sfx, spine3, af::Vec3(0, 3 * y, 55));
        const int upper = s.add("upperarm" + sfx, clavicle, af::Vec3(0, 8 * y, 55), 2.5);
        const int fore = s.add("forearm" + sfx, upper, af::Vec3(0, 20 * y, 55), 2);
        const int hand = s.add("hand" + sfx, fore, af::Vec3(0, 30 * y, 55), 1.5);
        s.add("tag_weapon" + sfx, hand, af::Vec3(1, 31 * y, 55));
        const char* fingers[] = {"thumb", "index", "middle", "ring", "pinky"};
        for (int f = 0; f < 5; ++f) {
            int bone = hand;
            const double x = 1.2 - 0.6 * f;
            for (int k = 1; k <= 4; ++k)  // three bones and an end nub without skin
                bone = s.add(std::string(fingers[f]) + std::to_string(k) + sfx, bone,
                             af::Vec3(x, (32 + 1.2 * k) * y, 55), k < 4 ? 0.3 : 0);
        }
        const int thigh = s.add("thigh" + sfx, pelvis, af::Vec3(0, 5.5 * y, 34), 3);
        const int calf = s.add("calf" + sfx, thigh, af::Vec3(0, 5.5 * y, 19), 2.5);
        const int foot = s.add("foot" + sfx, calf, af::Vec3(0, 5.5 * y, 3), 1.5);
        for (int t = 1; t <= 5; ++t) s.add("toe" + std::to_string(t) + sfx, foot, af::Vec3(6, (5.5 + 0.5 * (t - 3)) * y, 1), 0.3);
    }
    return s.joints;
}

// A mod folder holding models/NAME/NAME.md5mesh.

}  // namespace af::test::gen
