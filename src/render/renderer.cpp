#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "render/gl.h"

namespace softsub::render {

namespace {

// ---- Shaders ------------------------------------------------------------------------

constexpr const char* kBackgroundVs = R"(#version 330 core
out float vHeight;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  vHeight = p.y * 0.5 + 0.5;
  gl_Position = vec4(p, 0.999, 1.0);
})";

constexpr const char* kBackgroundFs = R"(#version 330 core
in float vHeight;
out vec4 outColour;
void main() {
  vec3 bottom = vec3(0.09, 0.10, 0.12);
  vec3 top = vec3(0.26, 0.29, 0.34);
  outColour = vec4(mix(bottom, top, clamp(vHeight, 0.0, 1.0)), 1.0);
})";

// Sphere impostors: one quad per particle, facing the camera, centred on the ray to the
// particle and grown by 1/cos of the ray's angle so the sphere's outline always fits; the
// fragment shader intersects the view ray with the true sphere for depth and normal.
constexpr const char* kSphereVs = R"(#version 330 core
layout(location = 0) in vec2 corner;
layout(location = 1) in vec3 centre;
uniform mat4 view;
uniform mat4 proj;
uniform float radius;
uniform float mirrorY;   // 0: as is; otherwise mirror about the plane y = mirrorY
uniform int mirrored;
out vec3 vCentre;
out vec3 vPoint;
void main() {
  vec3 c = centre;
  if (mirrored != 0) c.y = 2.0 * mirrorY - c.y;
  vec3 vc = (view * vec4(c, 1.0)).xyz;
  vCentre = vc;
  float dist = length(vc);
  vec3 toward = dist > 0.0 ? vc / dist : vec3(0.0, 0.0, -1.0);
  vec3 q = vc - toward * min(radius, 0.5 * dist);
  float grow = 1.1 * dist / max(-vc.z, 1e-6 * dist + 1e-12);
  vPoint = q + vec3(corner * radius * min(grow, 4.0), 0.0);
  gl_Position = proj * vec4(vPoint, 1.0);
})";

constexpr const char* kSphereFs = R"(#version 330 core
in vec3 vCentre;
in vec3 vPoint;
uniform mat4 proj;
uniform float radius;
uniform vec3 colour;
uniform vec3 lightView;
out vec4 outColour;
void main() {
  vec3 d = normalize(vPoint);
  float b = dot(d, vCentre);
  float disc = b * b - (dot(vCentre, vCentre) - radius * radius);
  if (disc < 0.0) discard;
  float t = b - sqrt(disc);
  if (t <= 0.0) discard;
  vec3 hit = d * t;
  vec3 n = (hit - vCentre) / radius;
  vec4 clip = proj * vec4(hit, 1.0);
  gl_FragDepth = clip.z / clip.w * 0.5 + 0.5;
  float diffuse = max(dot(n, lightView), 0.0);
  vec3 h = normalize(lightView - d);
  float specular = pow(max(dot(n, h), 0.0), 48.0);
  float rim = pow(1.0 - max(dot(n, -d), 0.0), 3.0);
  vec3 c = colour * (0.3 + 0.7 * diffuse) + vec3(0.32) * specular + colour * 0.15 * rim;
  outColour = vec4(c, 1.0);
})";

constexpr const char* kMeshVs = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 model;
uniform mat4 view;
uniform mat4 proj;
uniform vec4 clipPlane;   // world plane: keep where dot(plane, (p, 1)) >= 0
out vec3 vNormal;
out vec3 vPoint;
void main() {
  vec4 world = model * vec4(position, 1.0);
  gl_ClipDistance[0] = dot(clipPlane, world);
  vec4 v = view * world;
  vPoint = v.xyz;
  // model is a rotation times a uniform scale (times the floor mirror): it keeps normals'
  // directions, so no inverse-transpose per vertex; the fragment shader normalises.
  vNormal = mat3(view) * (mat3(model) * normal);
  gl_Position = proj * v;
})";

constexpr const char* kMeshFs = R"(#version 330 core
in vec3 vNormal;
in vec3 vPoint;
uniform vec3 colour;
uniform vec3 lightView;
out vec4 outColour;
void main() {
  vec3 n = normalize(vNormal);
  vec3 toEye = normalize(-vPoint);
  if (dot(n, toEye) < 0.0) n = -n;  // two-sided: open meshes and mirrored copies
  float diffuse = max(dot(n, lightView), 0.0);
  vec3 h = normalize(lightView + toEye);
  float specular = pow(max(dot(n, h), 0.0), 32.0);
  outColour = vec4(colour * (0.25 + 0.75 * diffuse) + vec3(0.18) * specular, 1.0);
})";

constexpr const char* kFloorVs = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 view;
uniform mat4 proj;
out vec3 vWorld;
void main() {
  vWorld = position;
  gl_Position = proj * view * vec4(position, 1.0);
})";

constexpr const char* kFloorFs = R"(#version 330 core
in vec3 vWorld;
uniform float cell;
uniform float alpha;
uniform vec3 tone;
out vec4 outColour;
void main() {
  vec2 k = floor(vWorld.xz / cell);
  float checker = mod(k.x + k.y, 2.0);
  vec3 c = tone * (0.82 + 0.18 * checker);
  outColour = vec4(c, alpha);
})";

constexpr const char* kLineVs = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 view;
uniform mat4 proj;
void main() { gl_Position = proj * view * vec4(position, 1.0); })";

constexpr const char* kLineFs = R"(#version 330 core
uniform vec4 colour;
out vec4 outColour;
void main() { outColour = colour; })";

/// A shader's or program's log (glGetShaderInfoLog / glGetProgramInfoLog).
std::string infoLog(GLuint object, void (*get)(GLuint, GLsizei, GLsizei*, GLchar*)) {
  std::string log(4096, '\0');
  GLsizei n = 0;
  get(object, static_cast<GLsizei>(log.size()), &n, log.data());
  log.resize(static_cast<std::size_t>(std::max<GLsizei>(n, 0)));
  return log;
}

GLuint compile(GLenum type, const char* source, const char* name) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (ok == 0) {
    const std::string log = infoLog(s, glGetShaderInfoLog);
    glDeleteShader(s);
    throw std::runtime_error(fmt::format("OpenGL: the {} shader does not compile: {}", name, log));
  }
  return s;
}

GLuint link(const char* vs, const char* fs, const char* name) {
  const GLuint v = compile(GL_VERTEX_SHADER, vs, name);
  const GLuint f = compile(GL_FRAGMENT_SHADER, fs, name);
  const GLuint p = glCreateProgram();
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (ok == 0) {
    const std::string log = infoLog(p, glGetProgramInfoLog);
    glDeleteProgram(p);
    throw std::runtime_error(fmt::format("OpenGL: the {} program does not link: {}", name, log));
  }
  return p;
}

// Uniform setters by name (a handful per draw call; locations are cached by the driver).
void setMat4(GLuint p, const char* n, const Eigen::Matrix4f& m) {
  glUniformMatrix4fv(glGetUniformLocation(p, n), 1, GL_FALSE, m.data());
}
void setVec3(GLuint p, const char* n, const Eigen::Vector3f& v) {
  glUniform3f(glGetUniformLocation(p, n), v.x(), v.y(), v.z());
}
void setVec4(GLuint p, const char* n, const Eigen::Vector4f& v) {
  glUniform4f(glGetUniformLocation(p, n), v.x(), v.y(), v.z(), v.w());
}
void setFloat(GLuint p, const char* n, float v) { glUniform1f(glGetUniformLocation(p, n), v); }
void setInt(GLuint p, const char* n, int v) { glUniform1i(glGetUniformLocation(p, n), v); }

Eigen::Vector3f toF(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

/// A "nice" checker cell: 1, 2 or 5 times a power of ten, about a twentieth of `extent`.
float niceCell(double extent) {
  const double raw = std::max(extent / 20.0, 1e-6);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / p;
  return static_cast<float>(p * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10));
}

Eigen::Matrix4f objectModel(const ObjectSnapshot& o) {
  const Eigen::Quaterniond q(o.rotation[0], o.rotation[1], o.rotation[2], o.rotation[3]);
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  m.translate(Eigen::Vector3d(o.position[0], o.position[1], o.position[2]));
  m.rotate(q.normalized());
  m.scale(o.uniformScale);
  return m.matrix().cast<float>();
}

struct MeshBuffers {
  GLuint vao = 0;
  GLuint vbo = 0;
  GLsizei vertices = 0;
  Eigen::Vector3f colour;
};

}  // namespace

struct Renderer::Gl {
  GLuint background = 0, sphere = 0, mesh = 0, floor = 0, line = 0;
  GLuint emptyVao = 0;
  GLuint quadVbo = 0, sphereVao = 0, instanceVbo = 0;
  GLuint floorVao = 0, floorVbo = 0;
  GLuint lineVao = 0, lineVbo = 0;
  GLsizei lineVertices = 0;
  GLuint surfaceVao = 0, surfaceVbo = 0, surfaceEbo = 0;  // the frame's surfaces, streamed
  std::unordered_map<std::string, MeshBuffers> meshes;

  ~Gl() {
    for (auto& [name, m] : meshes) {
      glDeleteBuffers(1, &m.vbo);
      glDeleteVertexArrays(1, &m.vao);
    }
    const GLuint buffers[] = {quadVbo, instanceVbo, floorVbo, lineVbo, surfaceVbo, surfaceEbo};
    glDeleteBuffers(6, buffers);
    const GLuint arrays[] = {emptyVao, sphereVao, floorVao, lineVao, surfaceVao};
    glDeleteVertexArrays(5, arrays);
    for (GLuint p : {background, sphere, mesh, floor, line}) glDeleteProgram(p);
  }
};

Renderer::Renderer() : gl_(std::make_unique<Gl>()) {
  Gl& g = *gl_;
  g.background = link(kBackgroundVs, kBackgroundFs, "background");
  g.sphere = link(kSphereVs, kSphereFs, "sphere");
  g.mesh = link(kMeshVs, kMeshFs, "mesh");
  g.floor = link(kFloorVs, kFloorFs, "floor");
  g.line = link(kLineVs, kLineFs, "line");
  glGenVertexArrays(1, &g.emptyVao);

  const float quad[] = {-1, -1, 1, -1, -1, 1, 1, 1};
  glGenVertexArrays(1, &g.sphereVao);
  glBindVertexArray(g.sphereVao);
  glGenBuffers(1, &g.quadVbo);
  glBindBuffer(GL_ARRAY_BUFFER, g.quadVbo);
  glBufferData(GL_ARRAY_BUFFER, sizeof(quad), quad, GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glGenBuffers(1, &g.instanceVbo);
  glBindBuffer(GL_ARRAY_BUFFER, g.instanceVbo);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glVertexAttribDivisor(1, 1);

  // Surfaces: positions then normals of each, one after another in one stream buffer;
  // attribute offsets are set per surface when drawing.
  glGenVertexArrays(1, &g.surfaceVao);
  glBindVertexArray(g.surfaceVao);
  glGenBuffers(1, &g.surfaceVbo);
  glBindBuffer(GL_ARRAY_BUFFER, g.surfaceVbo);
  glGenBuffers(1, &g.surfaceEbo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.surfaceEbo);  // part of the VAO's state
  glEnableVertexAttribArray(0);
  glEnableVertexAttribArray(1);

  glGenVertexArrays(1, &g.floorVao);
  glBindVertexArray(g.floorVao);
  glGenBuffers(1, &g.floorVbo);
  glBindBuffer(GL_ARRAY_BUFFER, g.floorVbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);

  glGenVertexArrays(1, &g.lineVao);
  glBindVertexArray(g.lineVao);
  glGenBuffers(1, &g.lineVbo);
  glBindBuffer(GL_ARRAY_BUFFER, g.lineVbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);
}

Renderer::~Renderer() = default;

void Renderer::setScene(const RenderScene& scene) {
  Gl& g = *gl_;
  scene_ = scene;
  for (auto& [name, m] : g.meshes) {
    glDeleteBuffers(1, &m.vbo);
    glDeleteVertexArrays(1, &m.vao);
  }
  g.meshes.clear();
  // Meshes: flat-shaded triangles (position, face normal) per vertex.
  std::vector<float> data;
  for (const RenderMesh& mesh : scene.meshes) {
    data.clear();
    for (const auto& t : mesh.triangles) {
      if (t[0] >= mesh.vertices.size() || t[1] >= mesh.vertices.size() || t[2] >= mesh.vertices.size())
        continue;
      const Eigen::Vector3f a = toF(mesh.vertices[t[0]]), b = toF(mesh.vertices[t[1]]),
                            c = toF(mesh.vertices[t[2]]);
      Eigen::Vector3f n = (b - a).cross(c - a);
      const float len = n.norm();
      if (len > 0) n /= len;
      for (const Eigen::Vector3f* p : {&a, &b, &c}) {
        data.insert(data.end(), {p->x(), p->y(), p->z(), n.x(), n.y(), n.z()});
      }
    }
    MeshBuffers& m = g.meshes[mesh.name];
    m.colour = toF(mesh.colour);
    m.vertices = static_cast<GLsizei>(data.size() / 6);
    glGenVertexArrays(1, &m.vao);
    glBindVertexArray(m.vao);
    glGenBuffers(1, &m.vbo);
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<const void*>(3 * sizeof(float)));
  }
  glBindVertexArray(0);

  // Container: its floor rectangle and its twelve edges (the four top edges only when
  // it is closed: an open box shows its rim as the walls' tops anyway).
  std::vector<float> floorData, lineData;
  if (scene.container) {
    const auto& lo = scene.container->lo;
    const auto& hi = scene.container->hi;
    floorData = {lo[0], lo[1], lo[2], hi[0], lo[1], lo[2], lo[0], lo[1], hi[2], hi[0], lo[1], hi[2]};
    const float x[2] = {lo[0], hi[0]}, y[2] = {lo[1], hi[1]}, z[2] = {lo[2], hi[2]};
    auto edge = [&](float x0, float y0, float z0, float x1, float y1, float z1) {
      lineData.insert(lineData.end(), {x0, y0, z0, x1, y1, z1});
    };
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        edge(x[0], y[i], z[j], x[1], y[i], z[j]);
        edge(x[i], y[0], z[j], x[i], y[1], z[j]);
        edge(x[i], y[j], z[0], x[i], y[j], z[1]);
      }
  }
  glBindBuffer(GL_ARRAY_BUFFER, g.floorVbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(floorData.size() * sizeof(float)), floorData.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, g.lineVbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(lineData.size() * sizeof(float)), lineData.data(),
               GL_STATIC_DRAW);
  g.lineVertices = static_cast<GLsizei>(lineData.size() / 3);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

Aabb sceneBounds(const RenderScene& scene, const FrameSnapshot& frame) {
  Aabb box;
  if (scene.container) {
    box.add(scene.container->lo[0], scene.container->lo[1], scene.container->lo[2]);
    box.add(scene.container->hi[0], scene.container->hi[1], scene.container->hi[2]);
  }
  for (const FluidSnapshot& f : frame.fluids) {
    const double r = 0.5 * f.particleSize;
    for (std::size_t k = 0; k < f.count(); ++k) {
      const float* p = &f.positions[3 * k];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
      box.add(p[0] - r, p[1] - r, p[2] - r);
      box.add(p[0] + r, p[1] + r, p[2] + r);
    }
  }
  for (const ObjectSnapshot& o : frame.objects) box.add(o.position[0], o.position[1], o.position[2]);
  return box;
}

void Renderer::draw(const FrameSnapshot& frame, const Camera& camera, int width, int height,
                    const DrawOptions& options, std::span<const RenderSurface> surfaces) {
  Gl& g = *gl_;
  bounds_ = sceneBounds(scene_, frame);
  for (const RenderSurface& s : surfaces)
    for (const auto& v : s.vertices)
      if (std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2])) bounds_.add(v[0], v[1], v[2]);

  const auto [near, far] = clipRange(camera, bounds_);
  const Eigen::Matrix4f view = camera.view();
  const Eigen::Matrix4f proj = perspective(camera.fovY, static_cast<double>(width) / std::max(height, 1), near, far);
  const Eigen::Vector3f lightWorld = Eigen::Vector3f(-0.35f, 1.0f, 0.55f).normalized();
  const Eigen::Vector3f lightView = view.block<3, 3>(0, 0) * lightWorld;

  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClearColor(0, 0, 0, 1);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  // Background gradient, behind everything.
  glDepthMask(GL_FALSE);
  glUseProgram(g.background);
  glBindVertexArray(g.emptyVao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);

  // Every fluid's positions go up once per draw; the mirrored pass reuses them.
  std::size_t totalBytes = 0;
  for (const FluidSnapshot& f : frame.fluids) totalBytes += f.positions.size() * sizeof(float);
  glBindBuffer(GL_ARRAY_BUFFER, g.instanceVbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(totalBytes), nullptr, GL_STREAM_DRAW);
  std::size_t uploaded = 0;
  for (const FluidSnapshot& f : frame.fluids) {
    const std::size_t bytes = f.positions.size() * sizeof(float);
    if (bytes > 0)
      glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(uploaded), static_cast<GLsizeiptr>(bytes),
                      f.positions.data());
    uploaded += bytes;
  }

  // The surfaces go up once too: per surface its positions, then its normals, and its
  // triangles' indices in the element buffer (skipped if malformed: a normal missing or an
  // index out of range).
  struct SurfaceRange {
    const RenderSurface* surface;
    std::size_t vertexBytes, normalBytes, indexBytes;
  };
  std::vector<SurfaceRange> surfaceRanges;
  std::vector<bool> asSurface(frame.fluids.size(), false);  // drawn as a surface, not particles
  {
    std::size_t vbytes = 0, ibytes = 0;
    for (const RenderSurface& s : surfaces) {
      if (s.fluid >= frame.fluids.size() || s.normals.size() != s.vertices.size() || s.triangles.empty()) continue;
      const bool inRange = std::all_of(s.triangles.begin(), s.triangles.end(), [&](const auto& t) {
        return t[0] < s.vertices.size() && t[1] < s.vertices.size() && t[2] < s.vertices.size();
      });
      if (!inRange) continue;
      const std::size_t n = s.vertices.size() * sizeof(s.vertices[0]);
      surfaceRanges.push_back({&s, vbytes, vbytes + n, ibytes});
      asSurface[s.fluid] = true;
      vbytes += 2 * n;
      ibytes += s.triangles.size() * sizeof(s.triangles[0]);
    }
    glBindVertexArray(g.surfaceVao);
    glBindBuffer(GL_ARRAY_BUFFER, g.surfaceVbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vbytes), nullptr, GL_STREAM_DRAW);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(ibytes), nullptr, GL_STREAM_DRAW);
    for (const SurfaceRange& r : surfaceRanges) {
      const RenderSurface& s = *r.surface;
      const auto n = static_cast<GLsizeiptr>(s.vertices.size() * sizeof(s.vertices[0]));
      glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(r.vertexBytes), n, s.vertices.data());
      glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(r.normalBytes), n, s.normals.data());
      glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLintptr>(r.indexBytes),
                      static_cast<GLsizeiptr>(s.triangles.size() * sizeof(s.triangles[0])), s.triangles.data());
    }
    glBindVertexArray(0);
  }

  const bool haveFloor = options.floor && scene_.container.has_value();
  const float floorY = haveFloor ? scene_.container->lo[1] : 0.0f;

  auto drawParticles = [&](bool mirrored) {
    glUseProgram(g.sphere);
    setMat4(g.sphere, "view", view);
    setMat4(g.sphere, "proj", proj);
    setVec3(g.sphere, "lightView", lightView);
    setInt(g.sphere, "mirrored", mirrored ? 1 : 0);
    setFloat(g.sphere, "mirrorY", floorY);
    glBindVertexArray(g.sphereVao);
    glBindBuffer(GL_ARRAY_BUFFER, g.instanceVbo);
    std::size_t offset = 0;  // bytes: every fluid's positions, one after another (uploaded above)
    for (const FluidSnapshot& f : frame.fluids) {
      const std::size_t bytes = f.positions.size() * sizeof(float);
      const std::size_t at = offset;
      offset += bytes;
      if (f.count() == 0 || asSurface[static_cast<std::size_t>(&f - frame.fluids.data())]) continue;
      glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, reinterpret_cast<const void*>(at));
      setFloat(g.sphere, "radius", 0.5f * f.particleSize * options.particleScale);
      Eigen::Vector3f colour = toF(f.colour);
      if (mirrored) colour *= 0.8f;
      setVec3(g.sphere, "colour", colour);
      glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(f.count()));
    }
  };

  // The mesh program for objects and surfaces, with clipping on; returns the floor mirror
  // (identity for the upright pass). The mirrored copy keeps only what lies below the floor.
  auto useMeshProgram = [&](bool mirrored) {
    glUseProgram(g.mesh);
    setMat4(g.mesh, "view", view);
    setMat4(g.mesh, "proj", proj);
    setVec3(g.mesh, "lightView", lightView);
    setVec4(g.mesh, "clipPlane", mirrored ? Eigen::Vector4f(0, -1, 0, floorY) : Eigen::Vector4f(0, 0, 0, 1));
    Eigen::Matrix4f mirror = Eigen::Matrix4f::Identity();
    if (mirrored) {
      mirror(1, 1) = -1;
      mirror(1, 3) = 2 * floorY;
    }
    glEnable(GL_CLIP_DISTANCE0);
    return mirror;
  };

  auto drawObjects = [&](bool mirrored) {
    if (!options.objects) return;
    const Eigen::Matrix4f mirror = useMeshProgram(mirrored);
    for (const ObjectSnapshot& o : frame.objects) {
      const auto it = g.meshes.find(o.name);
      if (it == g.meshes.end() || it->second.vertices == 0) continue;
      setMat4(g.mesh, "model", mirror * objectModel(o));
      setVec3(g.mesh, "colour", mirrored ? Eigen::Vector3f(it->second.colour * 0.8f) : it->second.colour);
      glBindVertexArray(it->second.vao);
      glDrawArrays(GL_TRIANGLES, 0, it->second.vertices);
    }
    glDisable(GL_CLIP_DISTANCE0);
  };

  auto drawSurfaces = [&](bool mirrored) {
    if (surfaceRanges.empty()) return;
    setMat4(g.mesh, "model", useMeshProgram(mirrored));  // surfaces are in world coordinates
    glBindVertexArray(g.surfaceVao);
    glBindBuffer(GL_ARRAY_BUFFER, g.surfaceVbo);  // attribute pointers read this binding
    for (const SurfaceRange& r : surfaceRanges) {
      Eigen::Vector3f colour = toF(frame.fluids[r.surface->fluid].colour);
      if (mirrored) colour *= 0.8f;
      setVec3(g.mesh, "colour", colour);
      glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, reinterpret_cast<const void*>(r.vertexBytes));
      glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, reinterpret_cast<const void*>(r.normalBytes));
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * r.surface->triangles.size()), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(r.indexBytes));
    }
    glDisable(GL_CLIP_DISTANCE0);
  };

  const double extent = bounds_.empty() ? 20.0
                                        : std::max({bounds_.hi[0] - bounds_.lo[0], bounds_.hi[2] - bounds_.lo[2], 1e-6});
  auto drawFloor = [&](float alpha) {
    glUseProgram(g.floor);
    setMat4(g.floor, "view", view);
    setMat4(g.floor, "proj", proj);
    setFloat(g.floor, "cell", niceCell(extent));
    setFloat(g.floor, "alpha", alpha);
    setVec3(g.floor, "tone", Eigen::Vector3f(0.55f, 0.56f, 0.58f));
    glBindVertexArray(g.floorVao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  };

  // The reflection: the scene mirrored in the floor plane, seen only where the camera is
  // above the floor, then the floor blended over it.
  const bool reflect = haveFloor && scene_.reflective && camera.eye.y() > floorY;
  if (reflect) {
    // Mark the floor's pixels in the stencil, draw the mirrored scene only there, then
    // blend the floor over it.
    glEnable(GL_STENCIL_TEST);
    glClearStencil(0);
    glClear(GL_STENCIL_BUFFER_BIT);
    glStencilFunc(GL_ALWAYS, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    drawFloor(1.0f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glStencilFunc(GL_EQUAL, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    drawParticles(true);
    drawObjects(true);
    drawSurfaces(true);
    glDisable(GL_STENCIL_TEST);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    drawFloor(0.55f);
    glDisable(GL_BLEND);
  } else if (haveFloor) {
    drawFloor(1.0f);
  }

  drawParticles(false);
  drawObjects(false);
  drawSurfaces(false);

  if (options.container && g.lineVertices > 0) {
    glUseProgram(g.line);
    setMat4(g.line, "view", view);
    setMat4(g.line, "proj", proj);
    setVec4(g.line, "colour", Eigen::Vector4f(0.78f, 0.80f, 0.84f, 1.0f));
    glBindVertexArray(g.lineVao);
    glDrawArrays(GL_LINES, 0, g.lineVertices);
  }
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace softsub::render
