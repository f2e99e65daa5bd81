#include "illum/resources/light_maps.h"

#include <glad/gl.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/gpu_memory.h"
#include "core/gpu_scene.h"
#include "core/profiler.h"
#include "core/shader_library.h"
#include "illum/framework/sample_loop.h"
#include "illum/resources/gpu_scene.h"

namespace vgi {

LightFaceLayout layoutLightFaces(const std::vector<Light>& lights, const Bounds& b, int resolution) {
  LightFaceLayout out;
  const float diag = std::max(b.diagonal(), 1e-6f);
  const glm::vec3 center = 0.5f * (b.lo + b.hi);
  // rays: a matrix with the face's x, y mapping whose inverse is well
  // conditioned (the face's own, with its near plane at 1e-5 of the range,
  // loses the rays' directions to cancellation).
  auto add = [&](const glm::mat4& vp, const glm::mat4& rays, glm::vec3 eye, bool ortho, glm::vec3 axis,
                 float texel) {
    shared::LightFace f;
    f.viewProj = vp;
    f.rayUnproject = glm::inverse(rays);
    f.eyeOrtho = glm::vec4(eye, ortho ? 1.0f : 0.0f);
    f.axisTexel = glm::vec4(axis, texel);
    out.faces.push_back(f);
    out.drawn.push_back(true);
  };
  for (const Light& l : lights) {
    const int first = int(out.faces.size());
    if (l.type == LightType::Directional) {
      glm::vec3 d = glm::normalize(l.direction);
      glm::vec3 up = std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
      float r = 0.5f * diag * 1.01f;
      glm::vec3 origin = center - d * r;
      glm::mat4 vp = glm::ortho(-r, r, -r, r, 0.0f, 2.0f * r) * glm::lookAt(origin, center, up);
      add(vp, vp, origin, true, d, 2.0f * r / float(resolution));
    } else {
      float maxDist =
          glm::length(glm::max(glm::abs(b.lo - l.position), glm::abs(b.hi - l.position))) * 1.01f + 1e-6f;
      float nearP = std::max(maxDist * 1e-5f, 1e-7f);
      if (l.type == LightType::Spot && l.coneHalfAngleDeg <= kSingleFaceSpotDeg) {
        // One face with a 2 % margin, so texels on the cone's edge are inside.
        float fov = 2.0f * glm::radians(l.coneHalfAngleDeg) * 1.02f;
        glm::vec3 axis = glm::normalize(l.direction);
        glm::vec3 up = std::abs(axis.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        glm::mat4 view = glm::lookAt(l.position, l.position + axis, up);
        add(glm::perspective(fov, 1.0f, nearP, maxDist) * view,
            glm::perspective(fov, 1.0f, 1.0f, 2.0f) * view, l.position, false, axis,
            2.0f * std::tan(0.5f * fov) / float(resolution));
      } else {
        // Cube faces in GL's order with their conventional up vectors.
        const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
        glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, nearP, maxDist),
                  unit = glm::perspective(glm::radians(90.0f), 1.0f, 1.0f, 2.0f);
        for (int f = 0; f < 6; ++f) {
          glm::mat4 view = glm::lookAt(l.position, l.position + dirs[f], ups[f]);
          add(proj * view, unit * view, l.position, false, dirs[f], 2.0f / float(resolution));
          // A face's frustum lies within atan(√2) of its axis: wholly outside
          // a spot's cone when its axis is farther than that from the cone
          // (a small margin keeps faces that merely touch the cone).
          if (l.type == LightType::Spot) {
            float angle = std::acos(glm::clamp(glm::dot(dirs[f], glm::normalize(l.direction)), -1.0f, 1.0f));
            out.drawn.back() = angle <= glm::radians(l.coneHalfAngleDeg) + std::atan(std::sqrt(2.0f)) + 1e-3f;
          }
        }
      }
    }
    out.ranges.push_back(glm::ivec4(first, int(out.faces.size()) - first, 0, 0));
  }
  return out;
}

LightMaps::LightMaps(const std::vector<Light>& lights, const GpuScene& gpu, int resolution, bool reflective)
    : resolution_(resolution), reflective_(reflective) {
  GLint maxTex = 0, maxLayers = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTex);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  if (resolution > maxTex)
    fail("parameter 'shadow_res': ", resolution, " exceeds GL_MAX_TEXTURE_SIZE ", maxTex);
  layout_ = layoutLightFaces(lights, gpu.bounds(), resolution);
  const int layers = std::max(1, faceCount());
  if (layers > maxLayers)
    fail("the scene's ", lights.size(), " lights need ", layers, " light-map faces; this GL allows ",
         maxLayers);

  const GLenum formats[4] = {GL_R32F, GL_RGBA32F, GL_RGBA16F, GL_RGBA16F};
  const int channels = reflective ? 4 : 1;
  // Distance (4 bytes a texel), and for RSMs position, normal, radiance (16 + 8 + 8), per face; the depth buffer.
  const double texel = reflective ? 36.0 : 4.0;
  checkGpuAllocation((double(layers) * texel + 4.0) * double(resolution) * double(resolution),
                     "parameter 'shadow_res' = " + std::to_string(resolution) + " with " +
                         std::to_string(lights.size()) + " light(s) (" + std::to_string(layers) +
                         " light-map faces" + (reflective ? ", reflective" : "") + ")");
  bytes_ = (double(layers) * texel + 4.0) * double(resolution) * double(resolution);
  glCreateTextures(GL_TEXTURE_2D_ARRAY, channels, textures_);
  for (int c = 0; c < channels; ++c) {
    glTextureStorage3D(textures_[c], 1, formats[c], resolution, resolution, layers);
    glTextureParameteri(textures_[c], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(textures_[c], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(textures_[c], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(textures_[c], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  glCreateBuffers(1, &faceBuffer_);
  glNamedBufferStorage(faceBuffer_,
                       GLsizeiptr(std::max<size_t>(1, layout_.faces.size()) * sizeof(shared::LightFace)),
                       nullptr, GL_DYNAMIC_STORAGE_BIT);
  glCreateBuffers(1, &rangeBuffer_);
  glNamedBufferStorage(rangeBuffer_,
                       GLsizeiptr(std::max<size_t>(1, layout_.ranges.size()) * sizeof(glm::ivec4)), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
  uploadLayout();

  glCreateFramebuffers(1, &fbo_);
  glCreateRenderbuffers(1, &depth_);
  glNamedRenderbufferStorage(depth_, GL_DEPTH_COMPONENT32F, resolution, resolution);
  glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum bufs[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                          GL_COLOR_ATTACHMENT3};
  glNamedFramebufferDrawBuffers(fbo_, channels, bufs);
}

void LightMaps::uploadLayout() {
  if (!layout_.faces.empty())
    glNamedBufferSubData(faceBuffer_, 0, GLsizeiptr(layout_.faces.size() * sizeof(shared::LightFace)),
                         layout_.faces.data());
  if (!layout_.ranges.empty())
    glNamedBufferSubData(rangeBuffer_, 0, GLsizeiptr(layout_.ranges.size() * sizeof(glm::ivec4)),
                         layout_.ranges.data());
}

void LightMaps::setLights(const std::vector<Light>& lights, const GpuScene& gpu) {
  LightFaceLayout l = layoutLightFaces(lights, gpu.bounds(), resolution_);
  if (l.faces.size() != layout_.faces.size() || l.ranges.size() != layout_.ranges.size())
    fail("internal: LightMaps::setLights changed the number of light-map faces");
  layout_ = std::move(l);
  uploadLayout();
}

void LightMaps::render(const GpuScene& gpu, ShaderLibrary& shaders, Profiler& profiler) {
  draw(gpu, shaders, profiler, std::vector<bool>(layout_.faces.size(), true));
}

namespace {
// Whether box b lies wholly outside one clip plane of viewProj (then the frustum cannot see it).
bool outsideFrustum(const glm::mat4& viewProj, const Bounds& b) {
  glm::vec4 c[8];
  for (int i = 0; i < 8; ++i)
    c[i] =
        viewProj * glm::vec4(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z, 1.0f);
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f}) {
      bool all = true;
      for (const glm::vec4& p : c) all = all && side * p[axis] > p.w;
      if (all) return true;
    }
  return false;
}

bool sameFace(const shared::LightFace& a, const shared::LightFace& b) {
  return a.viewProj == b.viewProj && a.rayUnproject == b.rayUnproject && a.eyeOrtho == b.eyeOrtho &&
         a.axisTexel == b.axisTexel;
}
}  // namespace

// The texels of a `res`² face that box b can cover (x, y, width, height; one texel of margin), or a
// zero width where a corner lies behind the eye (its projection is unbounded: the whole face).
glm::ivec4 projectedRect(const glm::mat4& viewProj, const Bounds& b, int res) {
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (int i = 0; i < 8; ++i) {
    const glm::vec4 c =
        viewProj * glm::vec4(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z, 1.0f);
    if (!(c.w > 1e-6f)) return glm::ivec4(0);
    const glm::vec2 t = (glm::vec2(c) / c.w * 0.5f + 0.5f) * float(res);
    lo = glm::min(lo, t);
    hi = glm::max(hi, t);
  }
  const glm::ivec2 a = glm::clamp(glm::ivec2(glm::floor(lo)) - 1, glm::ivec2(0), glm::ivec2(res)),
                   z = glm::clamp(glm::ivec2(glm::ceil(hi)) + 1, glm::ivec2(0), glm::ivec2(res));
  return glm::ivec4(a, glm::max(z - a, glm::ivec2(1)));
}

int LightMaps::renderChanged(const GpuScene& gpu, ShaderLibrary& shaders, Profiler& profiler,
                             const Bounds& moved) {
  std::vector<bool> faces(layout_.faces.size(), true);
  std::vector<glm::ivec4> rects(layout_.faces.size(), glm::ivec4(0));
  if (drawnLayout_.faces.size() == layout_.faces.size())
    for (size_t f = 0; f < faces.size(); ++f) {
      const bool same =
          sameFace(layout_.faces[f], drawnLayout_.faces[f]) && layout_.drawn[f] == drawnLayout_.drawn[f];
      faces[f] =
          !same || (layout_.drawn[f] && !moved.empty() && !outsideFrustum(layout_.faces[f].viewProj, moved));
      if (same && faces[f]) rects[f] = projectedRect(layout_.faces[f].viewProj, moved, resolution_);
    }
  return draw(gpu, shaders, profiler, faces, rects);
}

int LightMaps::draw(const GpuScene& gpu, ShaderLibrary& shaders, Profiler& profiler,
                    const std::vector<bool>& faces, const std::vector<glm::ivec4>& rects) {
  // (A face outside a spot's cone is only cleared: it counts when a drawn face does not.)
  int cleared = 0;
  redrawn_ = 0;
  scissored_ = 0;
  for (size_t f = 0; f < faces.size(); ++f) {
    cleared += faces[f] ? 1 : 0;
    redrawn_ += faces[f] && layout_.drawn[f] ? 1 : 0;
  }
  drawnLayout_ = layout_;
  if (cleared == 0) return 0;
  const int channels = reflective_ ? 4 : 1;
  ShaderDefines defs;
  if (reflective_) defs["REFLECTIVE"] = "1";
  unsigned prog =
      shaders.program({"illum/raster/surface.vert.glsl", "illum/raster/light_map.frag.glsl"}, defs);
  auto s = profiler.scope(reflective_ ? "rsm" : "shadow_maps");
  ++renders_;
  glUseProgram(prog);
  gpu.bind(shaders, prog);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, resolution_, resolution_);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  const float far = 1e30f, zero[4] = {0, 0, 0, 0}, farv[4] = {far, far, far, far};
  for (size_t li = 0; li < layout_.ranges.size(); ++li) {
    const glm::ivec4 r = layout_.ranges[li];
    shaders.setUniform(prog, "uLight", int(li));
    for (int f = r.x; f < r.x + r.y; ++f) {
      if (!faces[size_t(f)]) continue;  // as drawn before
      const shared::LightFace& face = layout_.faces[size_t(f)];
      for (int c = 0; c < channels; ++c)
        glNamedFramebufferTextureLayer(fbo_, GL_COLOR_ATTACHMENT0 + c, textures_[c], 0, f);
      if (f == r.x && glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        fail("light maps: the framebuffer is incomplete on this GL");
      // Clears and draws within the face's rectangle (scissored), or all of it.
      const glm::ivec4 rect = size_t(f) < rects.size() ? rects[size_t(f)] : glm::ivec4(0);
      if (rect.z > 0) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(rect.x, rect.y, rect.z, rect.w);
        ++scissored_;
      } else {
        glDisable(GL_SCISSOR_TEST);
      }
      glClearBufferfv(GL_COLOR, 0, farv);
      for (int c = 1; c < channels; ++c) glClearBufferfv(GL_COLOR, c, zero);
      if (!layout_.drawn[size_t(f)]) continue;
      glClear(GL_DEPTH_BUFFER_BIT);
      shaders.setUniform(prog, "uEye", glm::vec3(face.eyeOrtho));
      shaders.setUniform(prog, "uAxis", glm::vec3(face.axisTexel));
      shaders.setUniform(prog, "uOrthographic", face.eyeOrtho.w > 0.5f ? 1 : 0);
      shaders.setUniform(prog, "uViewProj", face.viewProj);
      gpu.draw();
    }
  }
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return cleared;
}

LightMaps::~LightMaps() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &depth_);
  glDeleteTextures(4, textures_);
  unsigned b[2] = {faceBuffer_, rangeBuffer_};
  glDeleteBuffers(2, b);
}

void LightMaps::bind() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_LIGHT_FACES, faceBuffer_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_LIGHT_RANGES, rangeBuffer_);
  const unsigned units[4] = {TEXUNIT_LIGHT_DISTANCE, TEXUNIT_LIGHT_POSITION, TEXUNIT_LIGHT_NORMAL,
                             TEXUNIT_LIGHT_RADIANCE};
  for (int c = 0; c < (reflective_ ? 4 : 1); ++c) glBindTextureUnit(units[c], textures_[c]);
}

std::vector<std::string> LightMaps::channelNames(bool reflective) {
  if (!reflective) return {"distance"};
  return {"distance", "position", "normal", "radiance"};
}

Image LightMaps::readFace(int face, const std::string& channel) const {
  const std::vector<std::string> names = channels();
  const auto it = std::find(names.begin(), names.end(), channel);
  if (it == names.end())
    fail("light maps: no channel '", channel, "' (", reflective_ ? "reflective shadow maps" : "shadow maps",
         " hold ", names.size() == 1 ? "distance" : "distance, position, normal, radiance", ")");
  if (face < 0 || face >= faceCount())
    fail("light maps: face ", face, " out of range (the lights have ", faceCount(), " faces: 0 … ",
         faceCount() - 1, ")");
  const int c = int(it - names.begin()), n = resolution_;
  std::vector<float> texels(size_t(n) * size_t(n) * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureSubImage(textures_[c], 0, 0, 0, face, n, n, 1, c == 0 ? GL_RED : GL_RGB, GL_FLOAT,
                       GLsizei(texels.size() * sizeof(float)), texels.data());
  Image img(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const size_t i = size_t(n - 1 - y) * size_t(n) + size_t(x);  // GL rows are bottom-up
      img.at(x, y) =
          c == 0 ? glm::vec3(texels[i]) : glm::vec3(texels[3 * i], texels[3 * i + 1], texels[3 * i + 2]);
    }
  return img;
}

nlohmann::json LightMaps::describe() const {
  int single = 0, cube = 0;
  for (auto& r : layout_.ranges) (r.y == 6 ? cube : single)++;
  int drawn = 0;
  for (bool d : layout_.drawn) drawn += d ? 1 : 0;
  return {{"faces", faceCount()},  {"faces_drawn", drawn},      {"cube", cube},
          {"single_face", single}, {"resolution", resolution_}, {"reflective", reflective_},
          {"bytes", bytes_},       {"faces_redrawn", redrawn_}, {"faces_scissored", scissored_}};
}

namespace {
class LightMapsResource : public Resource {
 public:
  explicit LightMapsResource(const LightMapNeed& n) : need_(n) {}
  // A frame of an animation draws again only the faces that can see what moved since the last
  // (or whose light or frustum changed): the static scene in the others is as drawn.
  bool update(SceneResources& res, const ResourceNeed&, Profiler& prof) override {
    const GpuScene& gpu = res.get<GpuScene>();
    const bool made = !maps_;
    if (made)
      maps_ = std::make_unique<LightMaps>(res.lights(), gpu, need_.resolution, need_.reflective);
    else
      maps_->setLights(res.lights(), gpu);
    const float before = time_;
    time_ = res.time();
    if (res.sampleLights()) return false;  // beginSample draws them for the sample's lights
    if (made || !drawn_) {
      maps_->render(gpu, res.shaders(), prof);
    } else {
      Bounds moved = res.scene().dynamicBounds(before);
      const Bounds now = res.scene().dynamicBounds(time_);
      if (!now.empty()) moved.extend(now.lo), moved.extend(now.hi);
      if (maps_->renderChanged(gpu, res.shaders(), prof, moved) == 0) return false;
    }
    drawn_ = true;
    return true;
  }
  bool relight(SceneResources& res, const ResourceNeed&, Profiler& prof) override {
    const GpuScene& gpu = res.get<GpuScene>();
    maps_->setLights(res.lights(), gpu);
    maps_->render(gpu, res.shaders(), prof);
    drawn_ = true;
    return true;
  }
  nlohmann::json stats() override { return maps_->describe(); }
  void* offer(const std::type_info& t) override { return offerOf(t, maps_.get()); }

 private:
  LightMapNeed need_;
  std::unique_ptr<LightMaps> maps_;
  float time_ = 0;      // the time the maps were last made current for
  bool drawn_ = false;  // drawn for the scene's own lights (not a sample's emitter points)
};
}  // namespace

void lightMapsInput(Frame& f, unsigned) { f.resources.get<LightMaps>().bind(); }

ResourceKind lightMapsKind() {
  return {"light_maps",
          "shadow maps (or, reflective, RSMs: position, normal, reflected flux) of every delta light",
          [](const ResourceNeed&) { return std::vector<ResourceNeed>{GpuSceneNeed{}}; },
          [](const ResourceNeed& n, const SceneNeeds&, const std::string& method, bool gl) {
            requireGl(n, method, gl);
          },
          [](const ResourceNeed& n) {
            return std::vector<std::string>{n.spec<LightMapNeed>().reflective ? "rsm" : "light_maps"};
          },
          [](const ResourceNeed& n, SceneResources&) -> std::unique_ptr<Resource> {
            return std::make_unique<LightMapsResource>(n.spec<LightMapNeed>());
          },
          "light_maps"};
}

const ResourceKind& LightMapNeed::row() {
  static const ResourceKind k = lightMapsKind();
  return k;
}

}  // namespace vgi
