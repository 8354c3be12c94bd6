// bullet-bench-scene: the ragdoll scenes of docs/bench-scene.md driven by Bullet as §5 prescribes.
// Variants: si10 (sequential impulse, 10 iterations), mlcp_dantzig (btMLCPSolver + btDantzigSolver,
// falling back to sequential impulse where Dantzig fails). Built against Debian's single- or
// double-precision libraries (btScalar = float or double).

#include "peer_common.h"

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h>
#include <BulletDynamics/MLCPSolvers/btDantzigSolver.h>
#include <BulletDynamics/MLCPSolvers/btMLCPSolver.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <vector>

#ifndef PEER_ENGINE
#define PEER_ENGINE "bullet"
#endif

namespace {

using benchscene::JointKind;
using namespace peers;

constexpr btScalar kMargin = 0.01;  // the default 0.04 exceeds the hand's half-thickness (0.02 m)
const btScalar kFriction = static_cast<btScalar>(std::sqrt(0.5));  // Bullet multiplies: 0.5 combined

btVector3 bt(const Vec3& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }
btQuaternion bt(const Quat& q) { return btQuaternion(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())); }
Vec3 toVec(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
Quat toQuat(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()); }

btMatrix3x3 bt(const Eigen::Matrix3d& m) {
    return btMatrix3x3(btScalar(m(0, 0)), btScalar(m(0, 1)), btScalar(m(0, 2)), btScalar(m(1, 0)), btScalar(m(1, 1)),
                       btScalar(m(1, 2)), btScalar(m(2, 0)), btScalar(m(2, 1)), btScalar(m(2, 2)));
}

// A joint frame in a body's local coordinates: in the T-pose body axes are model axes, so the
// anchor's local position is anchor − centre and the basis is the same for both bodies.
btTransform frameIn(const JointDef& j, int body, const btMatrix3x3& basis) {
    return btTransform(basis, bt(Vec3(j.anchor - benchscene::ragdollBodies()[body].centre)));
}
btTransform frameIn(const JointDef& j, int body, const Quat& rotation) {
    return btTransform(bt(rotation), bt(Vec3(j.anchor - benchscene::ragdollBodies()[body].centre)));
}

// Locked z (axis 1 × axis 2) is the middle Euler angle, so hip flexion may exceed π/2.
constexpr RotateOrder kUniversalOrder = RO_YZX;

std::unique_ptr<btGeneric6DofSpring2Constraint> makeUniversal(btRigidBody& a, btRigidBody& b, const JointDef& j) {
    const btMatrix3x3 basis = bt(universalBasis(j));
    return std::make_unique<btGeneric6DofSpring2Constraint>(a, b, frameIn(j, j.parent, basis),
                                                            frameIn(j, j.child, basis), kUniversalOrder);
}

std::unique_ptr<btHingeConstraint> makeHinge(btRigidBody& a, btRigidBody& b, const JointDef& j) {
    const btMatrix3x3 basis = bt(hingeBasis(j.axis1));
    return std::make_unique<btHingeConstraint>(a, b, frameIn(j, j.parent, basis), frameIn(j, j.child, basis));
}

// Per joint: the signs of Bullet's angles relative to §2, measured at start-up on two bodies whose
// relative rotation is known (getHingeAngle, and the 6-DoF constraint's Euler angles 0 and 1).
std::vector<ProbeRow> probe(std::vector<std::array<int, 2>>& signs) {
    std::vector<ProbeRow> rows;
    auto joints = benchscene::ragdollJoints();
    signs.assign(joints.size(), {1, 1});
    btBoxShape shape(btVector3(0.1, 0.1, 0.1));
    for (std::size_t i = 0; i < joints.size(); ++i) {
        const auto& j = joints[i];
        if (j.kind != JointKind::Hinge && j.kind != JointKind::Universal) continue;
        const auto& defs = benchscene::ragdollBodies();
        btRigidBody a(1, nullptr, &shape, btVector3(1, 1, 1)), b(1, nullptr, &shape, btVector3(1, 1, 1));
        a.setWorldTransform(btTransform(btQuaternion::getIdentity(), bt(defs[j.parent].centre)));
        b.setWorldTransform(btTransform(btQuaternion::getIdentity(), bt(defs[j.child].centre)));
        const Quat qB = probeRotation(j);
        // Turn the child about the anchor so that the anchors still coincide.
        const Vec3 xB = j.anchor + qB * (defs[j.child].centre - j.anchor);
        b.setWorldTransform(btTransform(bt(qB), bt(xB)));
        ProbeRow row{j.name, {}, {}};
        if (j.kind == JointKind::Hinge) {
            auto h = makeHinge(a, b, j);
            row.scene = {benchscene::hingeAngle(j, Quat::Identity(), qB)};
            row.engine = {h->getHingeAngle()};
        } else {
            auto u = makeUniversal(a, b, j);
            u->calculateTransforms();
            const auto s = benchscene::universalAngles(j, Quat::Identity(), qB);
            row.scene = {s[0], s[1]};
            row.engine = {u->getAngle(0), u->getAngle(1)};
        }
        judgeProbe(row);
        signs[i] = row.sign;
        rows.push_back(row);
    }
    return rows;
}

class BulletScene {
public:
    BulletScene(const Options& o, const std::vector<std::array<int, 2>>& signs) : signs_(signs) {
        config_ = std::make_unique<btDefaultCollisionConfiguration>();
        dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
        broadphase_ = std::make_unique<btDbvtBroadphase>();
        if (o.variant == "mlcp_dantzig") {
            dantzig_ = std::make_unique<btDantzigSolver>();
            auto mlcp = std::make_unique<btMLCPSolver>(dantzig_.get());
            mlcp_ = mlcp.get();
            solver_ = std::move(mlcp);
        } else {
            solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
        }
        world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                           config_.get());
        world_->setGravity(btVector3(0, 0, btScalar(-9.81)));
        btContactSolverInfo& info = world_->getSolverInfo();
        info.m_numIterations = 10;
        if (mlcp_) {
            // As in Bullet's own MLCP examples.
            info.m_minimumSolverBatchSize = 1;
            info.m_globalCfm = btScalar(1e-5);
        }
        sleep_ = o.sleep;

        planeShape_ = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), btScalar(0));
        btRigidBody::btRigidBodyConstructionInfo ground(0, nullptr, planeShape_.get());
        ground.m_friction = kFriction;
        ground.m_restitution = 0;
        ground_ = std::make_unique<btRigidBody>(ground);
        world_->addRigidBody(ground_.get());

        for (const auto& d : benchscene::ragdollBodies()) {
            auto shape = std::make_unique<btBoxShape>(bt(d.halfExtents));
            shape->setMargin(kMargin);  // btBoxShape keeps the margin inside the half-extents
            shapes_.push_back(std::move(shape));
        }
        for (const auto& p : benchscene::scenePlacements(o.scene, o.count)) addRagdoll(p);
    }

    ~BulletScene() {
        for (auto& c : constraints_) world_->removeConstraint(c.get());
        for (auto& b : bodies_) world_->removeRigidBody(b.get());
        world_->removeRigidBody(ground_.get());
    }
    BulletScene(const BulletScene&) = delete;
    BulletScene& operator=(const BulletScene&) = delete;

    int ragdolls() const { return static_cast<int>(bodies_.size()) / kBodiesPerRagdoll; }

    void step() { world_->stepSimulation(btScalar(kDt), 0); }

    // Deepest penetration among the contacts of the last step's manifolds.
    double contactDepth() const {
        double depth = 0;
        for (int m = 0; m < dispatcher_->getNumManifolds(); ++m) {
            const btPersistentManifold* pm = dispatcher_->getManifoldByIndexInternal(m);
            for (int k = 0; k < pm->getNumContacts(); ++k)
                depth = std::max(depth, -static_cast<double>(pm->getContactPoint(k).getDistance()));
        }
        return depth;
    }

    void read(std::span<benchscene::BodyState> out) const {
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            const btRigidBody& b = *bodies_[i];
            const btTransform& t = b.getCenterOfMassTransform();
            out[i] = {toVec(t.getOrigin()), toQuat(t.getRotation()), toVec(b.getLinearVelocity()),
                      toVec(b.getAngularVelocity())};
        }
    }

    bool asleep() const {
        return std::none_of(bodies_.begin(), bodies_.end(), [](const auto& b) { return b->isActive(); });
    }

    int mlcpFallbacks() const { return mlcp_ ? mlcp_->getNumFallbacks() : 0; }
    bool mlcp() const { return mlcp_ != nullptr; }

private:
    void addRagdoll(const benchscene::Placement& p) {
        const std::size_t base = bodies_.size();
        auto defs = benchscene::ragdollBodies();
        for (int i = 0; i < static_cast<int>(defs.size()); ++i) {
            const auto s = benchscene::placeBody(p, i);
            btRigidBody::btRigidBodyConstructionInfo info(btScalar(defs[i].mass), nullptr, shapes_[i].get(),
                                                          bt(benchscene::boxInertia(defs[i])));
            info.m_startWorldTransform = btTransform(bt(s.q), bt(s.x));
            info.m_friction = kFriction;
            info.m_restitution = 0;
            auto b = std::make_unique<btRigidBody>(info);
            b->setLinearVelocity(bt(s.v));
            b->setAngularVelocity(bt(s.w));
            if (!sleep_) b->setActivationState(DISABLE_DEACTIVATION);
            world_->addRigidBody(b.get());
            bodies_.push_back(std::move(b));
        }
        auto joints = benchscene::ragdollJoints();
        for (std::size_t k = 0; k < joints.size(); ++k) {
            const auto& j = joints[k];
            btRigidBody& a = *bodies_[base + j.parent];
            btRigidBody& b = *bodies_[base + j.child];
            const auto& sg = signs_[k];
            std::unique_ptr<btTypedConstraint> c;
            switch (j.kind) {
            case JointKind::Fixed: {
                const btMatrix3x3 identity = btMatrix3x3::getIdentity();
                c = std::make_unique<btFixedConstraint>(a, b, frameIn(j, j.parent, identity), frameIn(j, j.child, identity));
                break;
            }
            case JointKind::Hinge: {
                auto h = makeHinge(a, b, j);
                const auto l = engineLimits(j.lo1, j.hi1, sg[0]);
                h->setLimit(btScalar(l[0]), btScalar(l[1]));
                c = std::move(h);
                break;
            }
            case JointKind::Universal: {
                auto u = makeUniversal(a, b, j);
                const auto l1 = engineLimits(j.lo1, j.hi1, sg[0]);
                const auto l2 = engineLimits(j.lo2, j.hi2, sg[1]);
                u->setLinearLowerLimit(btVector3(0, 0, 0));
                u->setLinearUpperLimit(btVector3(0, 0, 0));
                u->setAngularLowerLimit(btVector3(btScalar(l1[0]), btScalar(l2[0]), 0));
                u->setAngularUpperLimit(btVector3(btScalar(l1[1]), btScalar(l2[1]), 0));
                c = std::move(u);
                break;
            }
            case JointKind::ConeTwist: {
                const auto frames = benchscene::coneTwistFrames(j);
                auto ct = std::make_unique<btConeTwistConstraint>(a, b, frameIn(j, j.parent, frames[0]),
                                                                  frameIn(j, j.child, frames[1]));
                ct->setLimit(btScalar(j.hi1), btScalar(j.hi1), btScalar(j.hi2));
                c = std::move(ct);
                break;
            }
            }
            world_->addConstraint(c.get(), true);
            constraints_.push_back(std::move(c));
        }
    }

    const std::vector<std::array<int, 2>>& signs_;
    bool sleep_ = false;
    std::unique_ptr<btDefaultCollisionConfiguration> config_;
    std::unique_ptr<btCollisionDispatcher> dispatcher_;
    std::unique_ptr<btBroadphaseInterface> broadphase_;
    std::unique_ptr<btDantzigSolver> dantzig_;
    std::unique_ptr<btConstraintSolver> solver_;
    btMLCPSolver* mlcp_ = nullptr;
    std::unique_ptr<btDiscreteDynamicsWorld> world_;
    std::unique_ptr<btCollisionShape> planeShape_;
    std::unique_ptr<btRigidBody> ground_;
    std::vector<std::unique_ptr<btBoxShape>> shapes_;  // one per ragdoll body, shared by all ragdolls
    std::vector<std::unique_ptr<btRigidBody>> bodies_;
    std::vector<std::unique_ptr<btTypedConstraint>> constraints_;
};

}  // namespace

int main(int argc, char** argv) {
    auto o = parseOptions(argc, argv, {"si10", "mlcp_dantzig"});
    if (!o) return 2;
    try {
        std::vector<std::array<int, 2>> signs;
        const auto rows = probe(signs);
        const std::string precision = std::string("\"btScalar_bytes\": ") + std::to_string(sizeof(btScalar));
        if (o->selftest) {
            std::cout << probeReport(PEER_ENGINE, rows, precision);
            return probeOk(rows) ? 0 : 1;
        }
        if (!probeOk(rows)) {
            std::cerr << "bullet-bench-scene: the sign probe failed; run with --selftest\n";
            return 1;
        }
        BulletScene scene(*o, signs);
        RunHooks hooks;
        hooks.step = [&] { scene.step(); };
        hooks.contactDepth = [&] { return scene.contactDepth(); };
        hooks.read = [&](std::span<benchscene::BodyState> s) { scene.read(s); };
        hooks.asleep = [&] { return scene.asleep(); };
        hooks.extraJson = [&] {
            std::string extra = precision;
            if (scene.mlcp()) extra += ", \"mlcp_fallbacks\": " + std::to_string(scene.mlcpFallbacks());
            return extra;
        };
        runScene(*o, PEER_ENGINE, scene.ragdolls(), hooks);
    } catch (const std::exception& e) {
        std::cerr << "bullet-bench-scene: " << e.what() << '\n';
        return 2;
    }
    return 0;
}
