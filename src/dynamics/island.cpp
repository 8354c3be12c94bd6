// An island's local arrays: copying in and out, and writing its rows.

#include "island.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace af {

namespace {

// Row keys of joints (see warm_start.h): the joint's world number and the row's place in it.
// Contact keys are hashes (contact_set.cpp) and rows of the extra source are keyed by their
// order in it.
constexpr std::uint64_t kJointKeyTag = 0x4a4full << 48;
constexpr std::uint64_t kExtraKeyTag = 0x4558ull << 48;

// Equal bits: what a row written from the same inputs needs, and cheaper than comparing
// element by element (one wide compare of the bytes).
template <class T>
bool sameBits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

int renumber(int body, std::span<const int> localOf) {
    return body == kWorldBody ? kWorldBody : localOf[static_cast<std::size_t>(body)];
}

}  // namespace

void Island::gather(std::span<const int> bodyIds, std::span<const int> jointIds, std::span<const int> pointIds,
                    const IslandWorld& world) {
    const std::span<const int> localOf = world.localOf;
    const bool sameJoints = std::equal(bodyIds.begin(), bodyIds.end(), bodyIds_.begin(), bodyIds_.end()) &&
                            std::equal(jointIds.begin(), jointIds.end(), jointIds_.begin(), jointIds_.end());
    if (!sameJoints) {
        bodyIds_.assign(bodyIds.begin(), bodyIds.end());
        jointIds_.assign(jointIds.begin(), jointIds.end());
        joints_.clear();
        for (const int j : jointIds) {
            Joint joint = world.joints[static_cast<std::size_t>(j)];
            joint.bodyA = renumber(joint.bodyA, localOf);
            joint.bodyB = renumber(joint.bodyB, localOf);
            joints_.push_back(std::move(joint));
        }
        treeReady_ = false;
        blocksReady_ = false;
        restRowsHeld_ = false;
    } else {
        for (std::size_t k = 0; k < jointIds.size(); ++k)
            joints_[k].lastImpulse = world.joints[static_cast<std::size_t>(jointIds[k])].lastImpulse;
    }
    // Written in place through local pointers: push_back's capacity checks and the copy through
    // a temporary cost more than the copies themselves.
    points_.resize(pointIds.size());
    ContactPoint* point = points_.data();
    for (const int p : pointIds) {
        *point = world.points[static_cast<std::size_t>(p)];
        point->bodyA = renumber(point->bodyA, localOf);
        point->bodyB = renumber(point->bodyB, localOf);
        ++point;
    }
    localOf_ = localOf;
    bodies_.resize(bodyIds.size());
    RigidBody* body = bodies_.data();
    for (const int b : bodyIds) *body++ = world.bodies[static_cast<std::size_t>(b)];
}

void Island::scatter(std::vector<RigidBody>& worldBodies, std::vector<Joint>& worldJoints) const {
    for (std::size_t i = 0; i < bodyIds_.size(); ++i) worldBodies[static_cast<std::size_t>(bodyIds_[i])] = bodies_[i];
    for (std::size_t k = 0; k < jointIds_.size(); ++k)
        worldJoints[static_cast<std::size_t>(jointIds_[k])].lastImpulse = joints_[k].lastImpulse;
}

// The sparse path has summed its answer's velocity change already, checking it (resting bench
// ragdoll: 6.6k of a step's 219k instructions to sum it again).
void Island::applyImpulses() {
    if (!sparseAnswered_) {
        system_.applyImpulses(rows_, bodies_);
        return;
    }
    const std::span<const Vec3> linear = sparse_.answerLinearChange();
    const std::span<const Vec3> angular = sparse_.answerAngularChange();
    for (std::size_t k = 0; k < bodies_.size(); ++k) {
        bodies_[k].linearVelocity += linear[k];
        bodies_[k].angularVelocity += angular[k];
    }
}

// The extra source sees the world's bodies (with this island's current poses written back);
// its rows that touch this island are kept, renumbered. localOf_ gives a body's index in its own
// island, whichever that is: a row's body belongs to this one only where that index names it here.
void Island::writeRows(IslandContext& context, bool atStepStart) {
    farPointsApart_ = false;  // a projection pass may move the bodies next
    rows_.clear();
    ranges_.clear();
    rowKeys_.clear();
    if (restRowsHold(context)) {
        std::swap(rows_, restRows_);
        std::swap(ranges_, restRanges_);
        rowInertia_ = restInertia_;
        restRowsHeld_ = false;
    } else {
        writeJointRowsOnly(context);
    }
    // The joints' keys written in place: push_back's capacity check per key cost more than the key.
    std::size_t jointRows = 0;
    for (const JointRowRange& range : ranges_) jointRows += static_cast<std::size_t>(range.total());
    rowKeys_.resize(jointRows);
    std::uint64_t* key = rowKeys_.data();
    for (std::size_t k = 0; k < joints_.size(); ++k) {
        const JointRowRange& range = ranges_[k];
        const std::uint64_t joint = kJointKeyTag | (static_cast<std::uint64_t>(jointIds_[k]) << 8);
        for (int r = 0; r < range.equalityRows; ++r) *key++ = joint | static_cast<std::uint64_t>(r);
        for (int r = 0; r < range.limitRows; ++r) *key++ = joint | static_cast<std::uint64_t>(64 + r);
        for (int r = 0; r < range.frictionRows; ++r) *key++ = joint | static_cast<std::uint64_t>(128 + r);
    }
    writeContactRows(nearPointsOnly_ ? nearPoints_ : points_, bodies_, rowInertia_, context.settings.contact, rows_, rowKeys_,
                     atStepStart);
    if (!context.extraRows) return;
    for (std::size_t i = 0; i < bodyIds_.size(); ++i)
        context.worldBodies[static_cast<std::size_t>(bodyIds_[i])] = bodies_[i];
    extra_.clear();
    context.extraRows(context.worldBodies, extra_);
    extraIndex_.assign(extra_.size(), -1);
    const auto localHere = [this](int body) {
        const int local = renumber(body, localOf_);
        return local == kWorldBody || (local >= 0 && static_cast<std::size_t>(local) < bodyIds_.size() &&
                                       bodyIds_[static_cast<std::size_t>(local)] == body)
                   ? local
                   : kOutsideIsland;
    };
    for (std::size_t r = 0; r < extra_.size(); ++r) {
        ConstraintRow row = extra_[r];
        const int a = localHere(row.bodyA);
        const int b = localHere(row.bodyB);
        if ((a < 0 && b < 0) || a == kOutsideIsland || b == kOutsideIsland) continue;
        row.bodyA = a;
        row.bodyB = b;
        if (row.frictionSource >= 0) row.frictionSource = extraIndex_[static_cast<std::size_t>(row.frictionSource)];
        extraIndex_[r] = rows_.add(row);
        rowKeys_.push_back(kExtraKeyTag | r);
    }
}

void Island::measureJointErrors(const IslandContext& context, bool keepRows) {
    if (!keepRows) {
        restRowsHeld_ = false;
        jointErrors_.clear();
        errorRanges_.clear();
        // Each body's rotation once, not once per joint side.
        rowRotations_.resize(bodies_.size());
        for (std::size_t b = 0; b < bodies_.size(); ++b) rowRotations_[b] = bodies_[b].rotation();
        for (const Joint& joint : joints_)
            errorRanges_.push_back(writeJointErrors(joint, bodies_, rowRotations_, context.settings.rows, jointErrors_));
        return;
    }
    restRows_.clear();
    restRanges_.clear();
    // Each body's rotation once, not once per joint side (the bench ragdoll's 30 sides: 1.1k of a
    // resting step's 204k instructions), and not at all for a body whose orientation and inertia
    // are those of the last resting write: its rotation and world inertia, functions of those
    // alone, are kept (resting bench ragdoll: 0.8k of a step's 147k).
    const std::size_t written = restPoses_.size();
    restRotations_.resize(bodies_.size());
    restInertia_.resize(bodies_.size());
    restPoses_.resize(bodies_.size());
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
        const RigidBody& body = bodies_[b];
        RestPose& pose = restPoses_[b];
        if (b >= written || !sameBits(body.orientation, pose.orientation) ||
            !sameBits(body.inverseInertia, pose.inverseInertia)) {
            restRotations_[b] = body.rotation();
            restInertia_[b] = body.inverseInertiaWorld(restRotations_[b]);
        }
        pose = {body.position, body.orientation, body.inverseMass, body.inverseInertia};
    }
    restImpulses_.resize(joints_.size());
    for (std::size_t k = 0; k < joints_.size(); ++k) {
        restRanges_.push_back(
            writeJointRows(joints_[k], bodies_, restRotations_, restInertia_, context.settings.rows, restRows_));
        restImpulses_[k] = joints_[k].lastImpulse;
    }
    restSettings_ = context.settings.rows;
    restRowsHeld_ = true;
}

// The joint rows depend on the bodies' poses, masses and inertias, the joints' impulses (the
// friction bounds) and the settings; equal bits give equal rows.
bool Island::restRowsHold(const IslandContext& context) const {
    if (!restRowsHeld_ || restPoses_.size() != bodies_.size() || restImpulses_.size() != joints_.size() ||
        context.settings.rows != restSettings_)
        return false;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
        const RigidBody& body = bodies_[b];
        const RestPose& p = restPoses_[b];
        if (!sameBits(body.position, p.position) || !sameBits(body.orientation, p.orientation) ||
            !sameBits(body.inverseMass, p.inverseMass) || !sameBits(body.inverseInertia, p.inverseInertia))
            return false;
    }
    for (std::size_t k = 0; k < joints_.size(); ++k)
        if (joints_[k].lastImpulse != restImpulses_[k]) return false;
    return true;
}

// The contact rows' errors are those writeContactRows gives their normal rows (the others,
// friction, have none). A far point that stays apart (farPointsApart_) has a positive gap,
// which cannot be the worst (the resting bench ragdoll: 34 of its 45 points).
Real Island::measuredViolation(const IslandContext& context) const {
    Real worst = 0;
    const auto jointViolation = [&worst](const auto& errors) {
        for (const auto& r : errors) {
            if (r.lo == 0 && r.hi == 0) continue;
            worst = std::max(worst, r.lo == 0 ? -r.error : std::abs(r.error));
        }
    };
    if (restRowsHeld_)
        jointViolation(restRows_.all());
    else
        jointViolation(jointErrors_);
    std::size_t far = 0;  // farPoints_ are in the order of points_
    for (std::size_t k = 0; k < points_.size(); ++k) {
        if (farPointsApart_ && far < farPoints_.size() && farPoints_[far].point == k) {
            if (farPoints_[far++].staysApart) continue;
        }
        worst = std::max(worst, -(context.settings.contact.slop - currentDepth(points_[k], bodies_)));
    }
    return worst;
}

}  // namespace af
