// OpenGL drawing of the viewer's scene: one stream buffer refilled per batch (a few thousand
// triangles for a map and a handful of ragdolls; nothing to cache yet).

#include "scene_renderer.h"

#include "gl_api.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace af::view {

namespace {

using render::Colour;

constexpr Colour kStaticColour = {0.56f, 0.56f, 0.54f};
constexpr Colour kFloorColour = {0.62f, 0.62f, 0.60f};
constexpr Colour kGridColour = {0.52f, 0.52f, 0.50f};
constexpr Colour kEdgeColour = {0.12f, 0.12f, 0.14f};
constexpr Colour kSkeletonColour = {0.97f, 0.97f, 0.95f};
constexpr Colour kDragColour = {0.95f, 0.95f, 0.20f};
constexpr Real kGridSpacing = 16;  // Doom's editor grid

const char* const kLitVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec4 colour;
uniform mat4 viewProjection;
out vec3 vNormal;
out vec4 vColour;
void main() {
    vNormal = normal;
    vColour = colour;
    gl_Position = viewProjection * vec4(position, 1.0);
})";

// A key light from above and in front-right, a weaker fill from the camera side, and sky light
// on faces turned up, so that every face of a hull reads apart from its neighbours.
const char* const kLitFragment = R"(#version 330 core
in vec3 vNormal;
in vec4 vColour;
uniform vec3 keyLight;
uniform vec3 fillLight;
out vec4 fragColour;
void main() {
    vec3 n = normalize(vNormal);
    float light = 0.30 + 0.55 * max(dot(n, keyLight), 0.0) + 0.25 * max(dot(n, fillLight), 0.0) + 0.08 * n.z;
    fragColour = vec4(vColour.rgb * clamp(light, 0.0, 1.15), vColour.a);
})";

const char* const kFlatVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 2) in vec4 colour;
uniform mat4 viewProjection;
uniform float pointSize;
out vec4 vColour;
void main() {
    vColour = colour;
    gl_PointSize = pointSize;
    gl_Position = viewProjection * vec4(position, 1.0);
})";

const char* const kFlatFragment = R"(#version 330 core
in vec4 vColour;
out vec4 fragColour;
void main() { fragColour = vColour; })";

unsigned compile(GLenum type, const char* source) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw std::runtime_error(std::string("af-view: shader does not compile: ") + log);
    }
    return shader;
}

unsigned link(const char* vertex, const char* fragment) {
    const GLuint v = compile(GL_VERTEX_SHADER, vertex), f = compile(GL_FRAGMENT_SHADER, fragment);
    const GLuint program = glCreateProgram();
    glAttachShader(program, v);
    glAttachShader(program, f);
    glLinkProgram(program);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) throw std::runtime_error("af-view: shader program does not link");
    return program;
}

// Vertex streams: lit (position, normal, colour: 10 floats) and flat (position, colour: 7).
struct LitStream {
    std::vector<float> data;
    void vertex(const Vec3& p, const Vec3& n, const Colour& c, float alpha = 1) {
        data.insert(data.end(), {float(p.x()), float(p.y()), float(p.z()), float(n.x()), float(n.y()), float(n.z()), c[0], c[1], c[2], alpha});
    }
    GLsizei count() const { return GLsizei(data.size() / 10); }
};

struct FlatStream {
    std::vector<float> data;
    void vertex(const Vec3& p, const Colour& c, float alpha = 1) {
        data.insert(data.end(), {float(p.x()), float(p.y()), float(p.z()), c[0], c[1], c[2], alpha});
    }
    void line(const Vec3& a, const Vec3& b, const Colour& c, float alpha = 1) {
        vertex(a, c, alpha);
        vertex(b, c, alpha);
    }
    GLsizei count() const { return GLsizei(data.size() / 7); }
};

// A hull's faces as triangle fans (faces are convex), lit by their normals.
void addHull(LitStream& s, const Polytope& shape, const RigidPose& pose, const Colour& colour) {
    const Mat3& r = pose.rotation;
    for (const Face& face : shape.faces) {
        if (face.loop.size() < 3 || face.normal.isZero()) continue;
        const Vec3 n = r * face.normal;
        const Vec3 first = pose.position + r * shape.vertices[std::size_t(face.loop[0])];
        for (std::size_t i = 1; i + 1 < face.loop.size(); ++i) {
            s.vertex(first, n, colour);
            s.vertex(pose.position + r * shape.vertices[std::size_t(face.loop[i])], n, colour);
            s.vertex(pose.position + r * shape.vertices[std::size_t(face.loop[i + 1])], n, colour);
        }
    }
}

void addEdges(FlatStream& s, const Polytope& shape, const RigidPose& pose, const Colour& colour) {
    const Mat3& r = pose.rotation;
    for (const auto& [a, b] : shape.edges)
        s.line(pose.position + r * shape.vertices[std::size_t(a)], pose.position + r * shape.vertices[std::size_t(b)], colour);
}

// The floor around the bodies: a square, and its grid on it.
void addFloor(LitStream& lit, FlatStream& grid, const render::RenderScene& scene, Real z) {
    Vec3 lo = Vec3::Constant(-32), hi = Vec3::Constant(32);
    if (!scene.bodies.empty()) {
        lo = hi = scene.bodies.front().pose.position;
        for (const render::RenderShape& b : scene.bodies) {
            lo = lo.cwiseMin(b.pose.position);
            hi = hi.cwiseMax(b.pose.position);
        }
    }
    const Real half = std::max({Real(256), 2 * (hi - lo).x(), 2 * (hi - lo).y()});
    const Real spacing = kGridSpacing * std::pow(2, std::max(0.0, std::ceil(std::log2(half / (32 * kGridSpacing)))));
    const Real cx = std::round((lo.x() + hi.x()) / 2 / spacing) * spacing, cy = std::round((lo.y() + hi.y()) / 2 / spacing) * spacing;
    const Real h = std::ceil(half / spacing) * spacing;
    const Vec3 a(cx - h, cy - h, z), b(cx + h, cy - h, z), c(cx + h, cy + h, z), d(cx - h, cy + h, z);
    for (const Vec3& p : {a, b, c, a, c, d}) lit.vertex(p, Vec3::UnitZ(), kFloorColour);
    for (Real t = -h; t <= h + 1e-9; t += spacing) {
        grid.line({cx + t, cy - h, z}, {cx + t, cy + h, z}, kGridColour);
        grid.line({cx - h, cy + t, z}, {cx + h, cy + t, z}, kGridColour);
    }
}

void setMatrix(unsigned program, const Eigen::Matrix4f& m) {
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "viewProjection"), 1, GL_FALSE, m.data());
}

}  // namespace

SceneRenderer::SceneRenderer() {
    litProgram_ = link(kLitVertex, kLitFragment);
    flatProgram_ = link(kFlatVertex, kFlatFragment);
    glGenBuffers(1, &buffer_);
    glGenVertexArrays(1, &litVao_);
    glGenVertexArrays(1, &flatVao_);
    glBindBuffer(GL_ARRAY_BUFFER, buffer_);
    const auto offset = [](int floats) { return reinterpret_cast<const void*>(std::size_t(floats) * sizeof(float)); };
    glBindVertexArray(litVao_);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 10 * sizeof(float), offset(0));
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 10 * sizeof(float), offset(3));
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 10 * sizeof(float), offset(6));
    for (GLuint i : {0u, 1u, 2u}) glEnableVertexAttribArray(i);
    glBindVertexArray(flatVao_);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 7 * sizeof(float), offset(0));
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 7 * sizeof(float), offset(3));
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(2);
    glBindVertexArray(0);
}

SceneRenderer::~SceneRenderer() {
    glDeleteVertexArrays(1, &litVao_);
    glDeleteVertexArrays(1, &flatVao_);
    glDeleteBuffers(1, &buffer_);
    glDeleteProgram(litProgram_);
    glDeleteProgram(flatProgram_);
}

void SceneRenderer::upload(const std::vector<float>& data) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_STREAM_DRAW);
}

void SceneRenderer::draw(const render::RenderScene& scene, const ViewMarks& marks, const OrbitCamera& camera, int width, int height, int bottom) {
    LitStream solid;
    FlatStream edges, grid;
    if (scene.floorZ) addFloor(solid, grid, scene, *scene.floorZ);
    for (const render::RenderShape& s : scene.statics) {
        addHull(solid, s.shape, s.pose, s.colour.value_or(kStaticColour));
        addEdges(edges, s.shape, s.pose, {0.40f, 0.40f, 0.38f});
    }
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const render::RenderShape& b = scene.bodies[i];
        addHull(solid, b.shape, b.pose, b.colour.value_or(render::bodyColour(int(i))));
        addEdges(edges, b.shape, b.pose, kEdgeColour);
    }

    // Marks over everything: translucent polygons, then lines, then dots.
    FlatStream fills, lines, dots;
    for (const auto& [a, b] : marks.skeleton) lines.line(a, b, kSkeletonColour);
    for (const auto& [a, b] : marks.skeleton) {
        dots.vertex(a, kSkeletonColour);
        dots.vertex(b, kSkeletonColour);
    }
    for (const render::OverlayPolygon& p : scene.overlay.polygons)
        for (std::size_t i = 1; i + 1 < p.points.size(); ++i)
            for (const Vec3& v : {p.points[0], p.points[i], p.points[i + 1]}) fills.vertex(v, p.colour, float(p.alpha));
    for (const render::OverlayLine& l : scene.overlay.lines) {
        lines.line(l.from, l.to, l.colour);
        const Vec3 d = l.to - l.from;
        if (l.arrow && d.norm() > 1e-9) {
            // A head in the plane that faces the camera, a fifth of the shaft long.
            Vec3 side = d.cross(camera.forward());
            if (side.norm() < 1e-9) side = camera.right();
            side = side.normalized() * d.norm() * 0.1;
            lines.line(l.to, l.to - 0.2 * d + side, l.colour);
            lines.line(l.to, l.to - 0.2 * d - side, l.colour);
        }
    }
    for (const render::OverlayDot& d : scene.overlay.dots) dots.vertex(d.at, d.colour);
    for (const auto& [a, b] : marks.dragPull) {
        lines.line(a, b, kDragColour);
        dots.vertex(a, kDragColour);
        dots.vertex(b, kDragColour);
    }

    const Eigen::Matrix4f viewProjection = camera.projectionMatrix(Real(width) / std::max(height, 1)) * camera.viewMatrix();
    glViewport(0, bottom, width, height);
    glClearColor(kSkyColour[0], kSkyColour[1], kSkyColour[2], 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1, 1);  // edges and grid lines in front of the faces they lie on
    glDisable(GL_BLEND);

    setMatrix(litProgram_, viewProjection);
    const Vec3 key = Vec3(0.45, -0.35, 0.82).normalized(), fill = (-camera.forward() + Vec3(0, 0, 0.3)).normalized();
    glUniform3f(glGetUniformLocation(litProgram_, "keyLight"), float(key.x()), float(key.y()), float(key.z()));
    glUniform3f(glGetUniformLocation(litProgram_, "fillLight"), float(fill.x()), float(fill.y()), float(fill.z()));
    glBindVertexArray(litVao_);
    upload(solid.data);
    glDrawArrays(GL_TRIANGLES, 0, solid.count());

    setMatrix(flatProgram_, viewProjection);
    glUniform1f(glGetUniformLocation(flatProgram_, "pointSize"), 6.0f);
    glBindVertexArray(flatVao_);
    glLineWidth(1);
    for (FlatStream* s : {&grid, &edges}) {
        upload(s->data);
        glDrawArrays(GL_LINES, 0, s->count());
    }

    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    upload(fills.data);
    glDrawArrays(GL_TRIANGLES, 0, fills.count());
    glLineWidth(2);
    upload(lines.data);
    glDrawArrays(GL_LINES, 0, lines.count());
    glLineWidth(1);
    glEnable(GL_PROGRAM_POINT_SIZE);
    upload(dots.data);
    glDrawArrays(GL_POINTS, 0, dots.count());
    glBindVertexArray(0);
    glDisable(GL_POLYGON_OFFSET_FILL);
}

}  // namespace af::view
