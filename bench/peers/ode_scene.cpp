// ode-bench-scene: the ragdoll scenes of docs/bench-scene.md driven by ODE as §5 prescribes.
// Variants: dantzig (dWorldStep), quickstep20 (dWorldQuickStep, 20 iterations).

#include "peer_common.h"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <vector>

#ifndef PEER_ENGINE
#define PEER_ENGINE "ode"
#endif

namespace {

using benchscene::JointKind;
using namespace peers;

constexpr int kMaxContactsPerPair = 8;

Vec3 toVec(const dReal* v) { return {v[0], v[1], v[2]}; }
Quat toQuat(const dReal* q) { return Quat(q[0], q[1], q[2], q[3]); }
void setQuat(dBodyID b, const Quat& q) {
    dQuaternion d = {q.w(), q.x(), q.y(), q.z()};
    dBodySetQuaternion(b, d);
}

// ODE recomputes a universal joint's reference rotation from both axes whenever one is set and
// complains when they are parallel at that moment: axis 1 first goes to a direction perpendicular
// to the new axis 2 and not parallel to the current one.
void setUniversalAxes(dJointID u, const Vec3& a1, const Vec3& a2) {
    dVector3 current;
    dJointGetUniversalAxis2(u, current);
    const Vec3 a3 = a1.cross(a2);
    const Vec3 via = std::abs(a3.normalized().dot(toVec(current))) > 0.9 ? a1 : a3;
    dJointSetUniversalAxis1(u, via.x(), via.y(), via.z());
    dJointSetUniversalAxis2(u, a2.x(), a2.y(), a2.z());
    dJointSetUniversalAxis1(u, a1.x(), a1.y(), a1.z());
}

// Signs of the engine's angles relative to §2, measured by the probe at start-up.
struct Signs {
    std::vector<std::array<int, 2>> joint;  // per ragdoll joint
    int amotor = 1;                          // +1: an AMotor angle grows with (ω1 − ω2)·axis
};

dBodyID probeBody(dWorldID w) {
    dBodyID b = dBodyCreate(w);
    dMass m;
    dMassSetBoxTotal(&m, 1.0, 0.2, 0.2, 0.2);
    dBodySetMass(b, &m);
    return b;
}

// Two bodies at the origin per hinge/universal joint of §2: the child is turned by a known rotation
// and ODE's angle compared with the §2 formula. The AMotor (user mode: we supply the angle) is probed
// dynamically: an angle beyond its high stop must be pushed back by one step.
std::vector<ProbeRow> probe(Signs& signs) {
    std::vector<ProbeRow> rows;
    auto joints = benchscene::ragdollJoints();
    signs.joint.assign(joints.size(), {1, 1});
    dWorldID w = dWorldCreate();
    for (std::size_t i = 0; i < joints.size(); ++i) {
        const auto& j = joints[i];
        if (j.kind != JointKind::Hinge && j.kind != JointKind::Universal) continue;
        dBodyID a = probeBody(w), b = probeBody(w);
        ProbeRow row{j.name, {}, {}};
        const Quat qB = probeRotation(j);
        if (j.kind == JointKind::Hinge) {
            dJointID h = dJointCreateHinge(w, nullptr);
            dJointAttach(h, a, b);
            dJointSetHingeAnchor(h, 0, 0, 0);
            dJointSetHingeAxis(h, j.axis1.x(), j.axis1.y(), j.axis1.z());
            setQuat(b, qB);
            row.scene = {benchscene::hingeAngle(j, Quat::Identity(), qB)};
            row.engine = {dJointGetHingeAngle(h)};
        } else {
            dJointID u = dJointCreateUniversal(w, nullptr);
            dJointAttach(u, a, b);
            dJointSetUniversalAnchor(u, 0, 0, 0);
            setUniversalAxes(u, j.axis1, j.axis2);
            setQuat(b, qB);
            auto s = benchscene::universalAngles(j, Quat::Identity(), qB);
            row.scene = {s[0], s[1]};
            row.engine = {dJointGetUniversalAngle1(u), dJointGetUniversalAngle2(u)};
        }
        judgeProbe(row);
        signs.joint[i] = row.sign;
        rows.push_back(row);
    }
    {
        dBodyID a = probeBody(w), b = probeBody(w);
        dJointID m = dJointCreateAMotor(w, nullptr);
        dJointAttach(m, a, b);
        dJointSetAMotorMode(m, dAMotorUser);
        dJointSetAMotorNumAxes(m, 1);
        dJointSetAMotorAxis(m, 0, 0, 0, 0, 1);
        dJointSetAMotorParam(m, dParamHiStop, 0.1);
        dJointSetAMotorAngle(m, 0, 0.5);
        dWorldStep(w, kDt);
        const double rate = dBodyGetAngularVel(a)[2] - dBodyGetAngularVel(b)[2];
        signs.amotor = rate < 0 ? 1 : -1;
        ProbeRow row{"amotor_user_stop", {0.5}, {0.5}};
        row.sign = {signs.amotor, 1};
        row.ok = std::abs(rate) > 1e-6;
        rows.push_back(row);
    }
    dWorldDestroy(w);
    return rows;
}

class OdeScene {
public:
    OdeScene(const Options& o, const Signs& signs) : quick_(o.variant == "quickstep20"), signs_(signs) {
        world_ = dWorldCreate();
        dWorldSetGravity(world_, 0, 0, -9.81);
        dWorldSetERP(world_, 0.2);
        dWorldSetCFM(world_, 1e-5);
        dWorldSetContactSurfaceLayer(world_, 0.001);
        dWorldSetQuickStepNumIterations(world_, 20);
        dWorldSetAutoDisableFlag(world_, o.sleep ? 1 : 0);
        space_ = dHashSpaceCreate(nullptr);
        contacts_ = dJointGroupCreate(0);
        dCreatePlane(space_, 0, 0, 1, 0);
        for (const auto& p : benchscene::scenePlacements(o.scene, o.count)) addRagdoll(p);
    }
    ~OdeScene() {
        dJointGroupDestroy(contacts_);
        dSpaceDestroy(space_);
        dWorldDestroy(world_);
    }
    OdeScene(const OdeScene&) = delete;
    OdeScene& operator=(const OdeScene&) = delete;

    int ragdolls() const { return static_cast<int>(bodies_.size()) / kBodiesPerRagdoll; }

    // One step: cone motors, collision, solve, contact clean-up.
    void step() {
        updateCones();
        depth_ = 0;
        dSpaceCollide(space_, this, &OdeScene::nearCallback);
        if (quick_)
            dWorldQuickStep(world_, kDt);
        else
            dWorldStep(world_, kDt);
        dJointGroupEmpty(contacts_);
    }

    // Deepest penetration among the last step's contacts.
    double contactDepth() const { return depth_; }

    void read(std::span<benchscene::BodyState> out) const {
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            dBodyID b = bodies_[i];
            out[i] = {toVec(dBodyGetPosition(b)), toQuat(dBodyGetQuaternion(b)), toVec(dBodyGetLinearVel(b)),
                      toVec(dBodyGetAngularVel(b))};
        }
    }

    bool asleep() const {
        return std::none_of(bodies_.begin(), bodies_.end(), [](dBodyID b) { return dBodyIsEnabled(b) != 0; });
    }

private:
    struct Cone {
        const JointDef* def;
        std::array<Quat, 2> frames;
        dBodyID a, b;
        dJointID motor;
    };

    void addRagdoll(const benchscene::Placement& p) {
        const std::size_t base = bodies_.size();
        auto defs = benchscene::ragdollBodies();
        for (int i = 0; i < static_cast<int>(defs.size()); ++i) {
            const auto& d = defs[i];
            const auto s = benchscene::placeBody(p, i);
            dBodyID b = dBodyCreate(world_);
            const Vec3 I = benchscene::boxInertia(d);
            dMass m;
            dMassSetParameters(&m, d.mass, 0, 0, 0, I.x(), I.y(), I.z(), 0, 0, 0);
            dBodySetMass(b, &m);
            dBodySetPosition(b, s.x.x(), s.x.y(), s.x.z());
            setQuat(b, s.q);
            dBodySetLinearVel(b, s.v.x(), s.v.y(), s.v.z());
            dBodySetAngularVel(b, s.w.x(), s.w.y(), s.w.z());
            const Vec3 e = 2 * d.halfExtents;
            dGeomSetBody(dCreateBox(space_, e.x(), e.y(), e.z()), b);
            bodies_.push_back(b);
        }
        auto joints = benchscene::ragdollJoints();
        for (std::size_t k = 0; k < joints.size(); ++k) {
            const auto& j = joints[k];
            dBodyID a = bodies_[base + j.parent], b = bodies_[base + j.child];
            const Vec3 x = benchscene::placePoint(p, j.anchor);
            const Vec3 a1 = p.R * j.axis1, a2 = p.R * j.axis2;
            const auto& sg = signs_.joint[k];
            switch (j.kind) {
            case JointKind::Fixed: {
                dJointID f = dJointCreateFixed(world_, nullptr);
                dJointAttach(f, a, b);
                dJointSetFixed(f);
                break;
            }
            case JointKind::Hinge: {
                dJointID h = dJointCreateHinge(world_, nullptr);
                dJointAttach(h, a, b);
                dJointSetHingeAnchor(h, x.x(), x.y(), x.z());
                dJointSetHingeAxis(h, a1.x(), a1.y(), a1.z());
                const auto l = engineLimits(j.lo1, j.hi1, sg[0]);
                dJointSetHingeParam(h, dParamLoStop, l[0]);
                dJointSetHingeParam(h, dParamHiStop, l[1]);
                break;
            }
            case JointKind::Universal: {
                dJointID u = dJointCreateUniversal(world_, nullptr);
                dJointAttach(u, a, b);
                dJointSetUniversalAnchor(u, x.x(), x.y(), x.z());
                setUniversalAxes(u, a1, a2);
                const auto l1 = engineLimits(j.lo1, j.hi1, sg[0]);
                const auto l2 = engineLimits(j.lo2, j.hi2, sg[1]);
                dJointSetUniversalParam(u, dParamLoStop, l1[0]);
                dJointSetUniversalParam(u, dParamHiStop, l1[1]);
                dJointSetUniversalParam(u, dParamLoStop2, l2[0]);
                dJointSetUniversalParam(u, dParamHiStop2, l2[1]);
                break;
            }
            case JointKind::ConeTwist: {
                dJointID ball = dJointCreateBall(world_, nullptr);
                dJointAttach(ball, a, b);
                dJointSetBallAnchor(ball, x.x(), x.y(), x.z());
                // ODE has no cone limit: a user-mode motor whose axes and angles we set every step.
                dJointID m = dJointCreateAMotor(world_, nullptr);
                dJointAttach(m, a, b);
                dJointSetAMotorMode(m, dAMotorUser);
                dJointSetAMotorNumAxes(m, 2);
                dJointSetAMotorParam(m, dParamHiStop, j.hi1);
                dJointSetAMotorParam(m, dParamLoStop2, j.lo2);
                dJointSetAMotorParam(m, dParamHiStop2, j.hi2);
                cones_.push_back({&j, benchscene::coneTwistFrames(j), a, b, m});
                break;
            }
            }
        }
    }

    void updateCones() {
        const double s = signs_.amotor;
        for (const auto& c : cones_) {
            const auto st = coneState(*c.def, c.frames, toQuat(dBodyGetQuaternion(c.a)), toQuat(dBodyGetQuaternion(c.b)));
            // The motor's angle grows with s·(ω1 − ω2)·u; swing and twist grow with (ω2 − ω1)·axis.
            const Vec3 u0 = -s * st.swingAxis, u1 = -s * st.twistAxis;
            dJointSetAMotorAxis(c.motor, 0, 0, u0.x(), u0.y(), u0.z());
            dJointSetAMotorAxis(c.motor, 1, 0, u1.x(), u1.y(), u1.z());
            dJointSetAMotorAngle(c.motor, 0, st.swing);
            dJointSetAMotorAngle(c.motor, 1, st.twist);
        }
    }

    static void nearCallback(void* data, dGeomID g1, dGeomID g2) {
        auto* self = static_cast<OdeScene*>(data);
        dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
        if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
        dContact c[kMaxContactsPerPair];
        const int n = dCollide(g1, g2, kMaxContactsPerPair, &c[0].geom, sizeof(dContact));
        for (int i = 0; i < n; ++i) {
            c[i].surface = {};
            c[i].surface.mode = dContactApprox1;
            c[i].surface.mu = 0.5;
            self->depth_ = std::max(self->depth_, static_cast<double>(c[i].geom.depth));
            dJointID cj = dJointCreateContact(self->world_, self->contacts_, &c[i]);
            dJointAttach(cj, b1, b2);
        }
    }

    bool quick_;
    const Signs& signs_;
    dWorldID world_;
    dSpaceID space_;
    dJointGroupID contacts_;
    std::vector<dBodyID> bodies_;
    std::vector<Cone> cones_;
    double depth_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
    auto o = parseOptions(argc, argv, {"dantzig", "quickstep20"});
    if (!o) return 2;
    dInitODE2(0);
    int rc = 0;
    try {
        Signs signs;
        const auto rows = probe(signs);
        if (o->selftest) {
            std::cout << probeReport(PEER_ENGINE, rows, {});
            rc = probeOk(rows) ? 0 : 1;
        } else if (!probeOk(rows)) {
            std::cerr << "ode-bench-scene: the sign probe failed; run with --selftest\n";
            rc = 1;
        } else {
            OdeScene scene(*o, signs);
            RunHooks hooks;
            hooks.step = [&] { scene.step(); };
            hooks.contactDepth = [&] { return scene.contactDepth(); };
            hooks.read = [&](std::span<benchscene::BodyState> s) { scene.read(s); };
            hooks.asleep = [&] { return scene.asleep(); };
            runScene(*o, PEER_ENGINE, scene.ragdolls(), hooks);
        }
    } catch (const std::exception& e) {
        std::cerr << "ode-bench-scene: " << e.what() << '\n';
        rc = 2;
    }
    dCloseODE();
    return rc;
}
