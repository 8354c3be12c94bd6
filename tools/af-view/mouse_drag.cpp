#include "mouse_drag.h"

#include "body_picker.h"

#include <cstdio>

namespace af::view {

namespace {

std::string numbers(const Vec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "%.4f %.4f %.4f", v.x(), v.y(), v.z());
    return text;
}

// The figure and body of the world's body `index` (figures' bodies follow each other in spawn order).
std::optional<BodyRef> bodyAt(const World& world, int index) {
    for (const FigureId f : world.figureIds()) {
        const int count = int(world.definition(f).bodies.size());
        if (index < count) return BodyRef{f, index};
        index -= count;
    }
    return std::nullopt;
}

}  // namespace

bool MouseDrag::press(const render::RenderScene& scene, const Ray& ray, const Vec3& viewForward) {
    const std::optional<BodyHit> hit = pickBody(scene.bodies, ray);
    if (!hit) return false;
    const World& world = session_.world();
    const std::optional<BodyRef> ref = bodyAt(world, hit->body);
    if (!ref) return false;
    const std::string entity = session_.entityName(ref->figure);
    if (entity.empty()) return false;
    const RigidBody& body = world.body(*ref);
    const Vec3 local = body.rotation().transpose() * (hit->point - body.position);
    const std::string name = world.definition(ref->figure).bodies[std::size_t(ref->body)].name;
    // Names are quoted: an entity or body name may hold spaces.
    const auto result = console_.execute("drag \"" + entity + "\" \"" + name + "\" " + numbers(hit->point) + " " + numbers(local), "mouse");
    if (!result.ok()) return false;
    grab_ = Grab{entity, name, hit->point, viewForward.normalized(), hit->point};
    return true;
}

void MouseDrag::move(const Ray& ray) {
    if (!grab_) return;
    const Real along = grab_->planeNormal.dot(ray.direction);
    if (std::abs(along) < 1e-9) return;
    const Real t = grab_->planeNormal.dot(grab_->planePoint - ray.origin) / along;
    if (t <= 0) return;
    grab_->target = ray.origin + t * ray.direction;
    console_.execute("drag " + numbers(grab_->target), "mouse");
}

void MouseDrag::release() {
    if (!grab_) return;
    grab_.reset();
    console_.execute("drag off", "mouse");
}

std::optional<std::pair<Vec3, Vec3>> MouseDrag::pull() const {
    const std::optional<Drag>& drag = session_.world().drag();
    if (!grab_ || !drag) return std::nullopt;
    const RigidBody& body = session_.world().body(drag->body);
    return std::pair{body.position + body.rotation() * drag->localPoint, drag->target};
}

}  // namespace af::view
