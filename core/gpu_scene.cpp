#include "core/gpu_scene.h"

#include <glad/gl.h>

#include <cmath>

#include "core/error.h"
#include "core/shader_library.h"

namespace vgi {

shared::PackedLight packLight(const Light& l) {
  shared::PackedLight p;
  float type = l.type == LightType::Point  ? float(shared::LIGHT_POINT)
               : l.type == LightType::Spot ? float(shared::LIGHT_SPOT)
                                           : float(shared::LIGHT_DIRECTIONAL);
  p.positionType = glm::vec4(l.position, type);
  p.directionCosCone = glm::vec4(glm::normalize(l.direction), std::cos(glm::radians(l.coneHalfAngleDeg)));
  p.intensityFalloff = glm::vec4(l.intensity, l.falloff);
  return p;
}

shared::PackedMaterial packMaterial(const Material& m, int layer, bool twoSidedEmission) {
  shared::PackedMaterial p;
  p.albedoLayer = glm::vec4(m.albedo, float(layer));
  p.ksExponent = glm::vec4(m.ks, m.exponent);
  p.emission = glm::vec4(m.emission, twoSidedEmission ? 1.0f : 0.0f);
  return p;
}

static_assert(sizeof(shared::PackedLight) == 48, "std430 layout of PackedLight");
static_assert(sizeof(shared::PackedMaterial) == 48, "std430 layout of PackedMaterial");

namespace {
// Interleaved position, shading normal, uv, geometric (face) normal: 11 floats per vertex.
constexpr int kVertexFloats = int(shared::SCENE_VERTEX_FLOATS);
static_assert(shared::SCENE_VERTEX_UV == 6u, "interleave() writes the uv after position and normal");
// `verts` is resized, not reallocated where it is large enough (an animation's frames reuse it).
void interleave(const FlatScene& f, std::vector<float>& verts) {
  verts.resize(f.positions.size() * kVertexFloats);
  float* out = verts.data();
  for (size_t t = 0; t + 2 < f.positions.size(); t += 3) {
    const glm::vec3 face =
        glm::cross(f.positions[t + 1] - f.positions[t], f.positions[t + 2] - f.positions[t]);
    const bool flat = !(glm::length(face) > 0.0f);
    const glm::vec3 unit = flat ? face : glm::normalize(face);
    for (size_t i = t; i < t + 3; ++i, out += kVertexFloats) {
      const glm::vec3 &p = f.positions[i], &n = f.normals[i];
      const glm::vec2& uv = f.uvs[i];
      const glm::vec3 g = flat ? n : unit;  // a degenerate face takes each corner's shading normal
      const float v[kVertexFloats] = {p.x, p.y, p.z, n.x, n.y, n.z, uv.x, uv.y, g.x, g.y, g.z};
      std::copy(v, v + kVertexFloats, out);
    }
  }
}

unsigned makeSsbo(const void* data, size_t bytes) {
  unsigned b = 0;
  glCreateBuffers(1, &b);
  // A zero-sized buffer cannot be bound; keep one element of padding.
  glNamedBufferStorage(b, GLsizeiptr(std::max<size_t>(bytes, 64)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  if (bytes) glNamedBufferSubData(b, 0, GLsizeiptr(bytes), data);
  return b;
}
}  // namespace

GpuScene::GpuScene(const Scene& scene, float time) {
  FlatScene f = flatten(scene, time);
  triangles_ = f.triangleCount();
  bounds_ = scene.bounds(time);
  for (const Mesh& m : scene.meshes)
    if (!m.dynamic) {
      const glm::mat4 M = m.objectToWorld(time);
      for (const glm::vec3& p : m.positions) staticBounds_.extend(glm::vec3(M * glm::vec4(p, 1.0f)));
    }
  std::vector<float> verts;
  interleave(f, verts);
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &vbo_);
  glNamedBufferStorage(vbo_, GLsizeiptr(std::max<size_t>(verts.size(), kVertexFloats) * sizeof(float)),
                       verts.empty() ? nullptr : verts.data(), GL_DYNAMIC_STORAGE_BIT);
  glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, kVertexFloats * sizeof(float));
  const unsigned offsets[4] = {0, 3, 6, 8}, sizes[4] = {3, 3, 2, 3};
  for (unsigned a = 0; a < 4; ++a) {
    glEnableVertexArrayAttrib(vao_, a);
    glVertexArrayAttribFormat(vao_, a, int(sizes[a]), GL_FLOAT, GL_FALSE, offsets[a] * sizeof(float));
    glVertexArrayAttribBinding(vao_, a, 0);
  }

  // Albedo textures: one array, each resampled (bilinear, as Texture::lookup) to the largest size.
  std::vector<int> layerOf(scene.textures.size(), -1);
  int tw = 1, th = 1, layers = 0;
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    int t = scene.materials[m].albedoTexture;
    if (t >= 0 && layerOf[size_t(t)] < 0) {
      layerOf[size_t(t)] = layers++;
      tw = std::max(tw, scene.textures[size_t(t)].width);
      th = std::max(th, scene.textures[size_t(t)].height);
    }
  }
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &albedoArray_);
  glTextureStorage3D(albedoArray_, 1, GL_RGB32F, tw, th, std::max(layers, 1));
  for (size_t t = 0; t < scene.textures.size(); ++t) {
    if (layerOf[t] < 0) continue;
    const Texture& tex = scene.textures[t];
    std::vector<glm::vec3> px(size_t(tw) * th);
    for (int y = 0; y < th; ++y)
      for (int x = 0; x < tw; ++x)
        px[size_t(y) * tw + x] = (tex.width == tw && tex.height == th)
                                     ? tex.texels[size_t(y) * tw + x]
                                     : tex.lookup({(x + 0.5f) / tw, 1.0f - (y + 0.5f) / th});
    glTextureSubImage3D(albedoArray_, 0, 0, 0, layerOf[t], tw, th, 1, GL_RGB, GL_FLOAT, px.data());
  }
  for (unsigned tex : {albedoArray_}) {
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
  }

  std::vector<shared::PackedMaterial> mats;
  for (auto& m : scene.materials)
    mats.push_back(packMaterial(m, m.albedoTexture >= 0 ? layerOf[size_t(m.albedoTexture)] : -1,
                                scene.twoSidedEmission));
  materials_ = makeSsbo(mats.data(), mats.size() * sizeof(mats[0]));
  triMaterial_ = makeSsbo(f.material.data(), f.material.size() * sizeof(int));
  setLights(scene.lights);

  const Environment& env = scene.environment;
  envColorScale_ = glm::vec4(env.color, env.scale);
  envHasMap_ = env.mapTexture >= 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &envMap_);
  if (envHasMap_) {
    const Texture& t = scene.textures[size_t(env.mapTexture)];
    glTextureStorage2D(envMap_, 1, GL_RGB32F, t.width, t.height);
    glTextureSubImage2D(envMap_, 0, 0, 0, t.width, t.height, GL_RGB, GL_FLOAT, t.texels.data());
  } else {
    glTextureStorage2D(envMap_, 1, GL_RGB32F, 1, 1);
  }
  glTextureParameteri(envMap_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(envMap_, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(envMap_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void GpuScene::setTime(const Scene& scene, float time) {
  if (scene.triangleCount() != triangles_)
    fail("GpuScene::setTime: the scene has ", scene.triangleCount(), " triangles, not ", triangles_);
  // Only the dynamic meshes move: the bounds are the static ones' (kept) and theirs; re-upload
  // their vertex ranges (through buffers kept between frames).
  bounds_ = staticBounds_;
  const Bounds moving = scene.dynamicBounds(time);
  if (!moving.empty()) bounds_.extend(moving.lo), bounds_.extend(moving.hi);
  size_t first = 0;  // the mesh's first triangle
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& m = scene.meshes[mi];
    if (m.dynamic && !m.triangles.empty()) {
      for (auto* v : {&flat_.positions, &flat_.normals}) v->clear();
      flat_.uvs.clear(), flat_.material.clear(), flat_.meshOfTriangle.clear();
      flattenMesh(scene, int(mi), time, flat_);
      interleave(flat_, verts_);
      glNamedBufferSubData(vbo_, GLintptr(first * 3 * kVertexFloats * sizeof(float)),
                           GLsizeiptr(verts_.size() * sizeof(float)), verts_.data());
    }
    first += m.triangles.size();
  }
}

void GpuScene::setLights(const std::vector<Light>& lights) {
  std::vector<shared::PackedLight> ls;
  for (auto& l : lights) ls.push_back(packLight(l));
  if (lights_ && ls.size() == lightCount_) {
    if (!ls.empty()) glNamedBufferSubData(lights_, 0, GLsizeiptr(ls.size() * sizeof(ls[0])), ls.data());
    return;
  }
  glDeleteBuffers(1, &lights_);
  lights_ = makeSsbo(ls.data(), ls.size() * sizeof(ls[0]));
  lightCount_ = ls.size();
}

GpuScene::~GpuScene() {
  unsigned bufs[] = {vbo_, materials_, triMaterial_, lights_};
  glDeleteBuffers(4, bufs);
  glDeleteVertexArrays(1, &vao_);
  unsigned texs[] = {albedoArray_, envMap_};
  glDeleteTextures(2, texs);
}

void GpuScene::bind(ShaderLibrary& shaders, unsigned program) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_MATERIALS, materials_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_TRI_MATERIAL, triMaterial_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_LIGHTS, lights_);
  glBindTextureUnit(TEXUNIT_ALBEDO_ARRAY, albedoArray_);
  glBindTextureUnit(TEXUNIT_ENV_MAP, envMap_);
  shaders.setUniform(program, "uEnvColorScale", envColorScale_);
  shaders.setUniform(program, "uEnvHasMap", envHasMap_ ? 1 : 0);
  shaders.setUniform(program, "uLightCount", int(lightCount_));
}

void GpuScene::bindVertices() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_SCENE_VERTICES, vbo_);
}

void GpuScene::draw() const {
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, GLsizei(3 * triangles_));
}

void GpuScene::drawInstanced(int instances) const {
  glBindVertexArray(vao_);
  glDrawArraysInstanced(GL_TRIANGLES, 0, GLsizei(3 * triangles_), GLsizei(instances));
}

}  // namespace vgi
