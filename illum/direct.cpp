// `direct`: deferred direct lighting on the GPU — the first GL module and the
// base the GI modules add to. G-buffer (position, normal, albedo), one distance
// shadow map per light (a cube for point and spot lights, an orthographic map
// fitted to the scene for directional lights), then a compute pass that
// evaluates every delta light with the shared kernels (shaders/shared/lights,
// brdf) — the same code the Embree reference (`reference --set
// integrator=direct`) runs, so their difference is the shadow-map error.
// `--spp N` accumulates N frames with sub-pixel jitter (Halton 2,3) so edges
// converge to the same box-filtered pixel as the reference.
//
// Parameters
// | key           | type  | default | meaning                                            |
// |---------------|-------|---------|----------------------------------------------------|
// | shadow_res    | int   | 1024    | shadow map size (cube face / directional map)      |
// | shadow_bias   | float | 1.0     | depth bias in shadow-map texels (slope-scaled)     |
// | normal_offset | float | 0.25    | lookup offset along the normal, in texels          |
#include "illum/direct.h"

#include <glad/gl.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "core/gl_context.h"
#include "core/gpu_scene.h"
#include "core/progress.h"
#include "core/shader_library.h"

namespace vgi {

namespace {

constexpr int kMaxDirectional = 4;

float halton(int index, int base) {
  float f = 1, r = 0;
  for (int i = index; i > 0; i /= base) {
    f /= float(base);
    r += f * float(i % base);
  }
  return r;
}


class DirectMethod : public Method {
 public:
  DirectMethod(ParamSet& p, const Scene& scene) {
    shadowRes_ = p.getInt("shadow_res", 1024, "shadow map size (cube face / directional map)", 16, 8192);
    shadowBias_ = p.getFloat("shadow_bias", 1.0f, "depth bias in shadow-map texels (slope-scaled)", 0.0f, 100.0f);
    normalOffset_ = p.getFloat("normal_offset", 0.25f, "lookup offset along the normal, in texels", 0.0f, 100.0f);
    int directional = 0;
    for (auto& l : scene.lights) directional += l.type == LightType::Directional;
    if (directional > kMaxDirectional)
      fail("method direct: the scene has ", directional, " directional lights; at most ", kMaxDirectional,
           " are supported");
  }
  RenderResult render(const RenderRequest& req, Profiler& profiler) override;

 private:
  int shadowRes_;
  float shadowBias_, normalOffset_;
};

RenderResult DirectMethod::render(const RenderRequest& req, Profiler& prof) {
  VGI_CHECK(req.gl && req.shaders);
  const Scene& scene = *req.scene;
  const int W = req.width, H = req.height;
  GLint maxTex = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTex);
  if (W > maxTex || H > maxTex)
    fail("--size ", W, "x", H, " exceeds this GL's largest texture (", maxTex, ")");
  if (shadowRes_ > maxTex) fail("parameter 'shadow_res': ", shadowRes_, " exceeds GL_MAX_TEXTURE_SIZE ", maxTex);

  std::unique_ptr<GpuScene> gpu;
  {
    auto s = prof.scope("upload");
    gpu = std::make_unique<GpuScene>(scene, req.time);
  }
  ShaderDefines defs{{"MAX_DIRECTIONAL", std::to_string(kMaxDirectional)}};
  unsigned gbufProg = req.shaders->program({"illum/direct/gbuffer.vert.glsl", "illum/direct/gbuffer.frag.glsl"});
  unsigned shadowProg = req.shaders->program({"illum/direct/shadow.vert.glsl", "illum/direct/shadow.frag.glsl"});
  unsigned shadeProg = req.shaders->program({"illum/direct/shade.comp.glsl"}, defs);

  // ---- shadow maps (static over the samples: computed once)
  int cubes = 0, planes = 0;
  for (auto& l : scene.lights) (l.type == LightType::Directional ? planes : cubes)++;
  unsigned cubeArray = 0, planeArray = 0, shadowFbo = 0, shadowDepth = 0;
  glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &cubeArray);
  glTextureStorage3D(cubeArray, 1, GL_R32F, shadowRes_, shadowRes_, 6 * std::max(cubes, 1));
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &planeArray);
  glTextureStorage3D(planeArray, 1, GL_R32F, shadowRes_, shadowRes_, std::max(planes, 1));
  for (unsigned t : {cubeArray, planeArray}) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  glCreateFramebuffers(1, &shadowFbo);
  glCreateRenderbuffers(1, &shadowDepth);
  glNamedRenderbufferStorage(shadowDepth, GL_DEPTH_COMPONENT32F, shadowRes_, shadowRes_);
  glNamedFramebufferRenderbuffer(shadowFbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, shadowDepth);

  const Bounds& b = gpu->bounds();
  const float diag = std::max(b.diagonal(), 1e-6f);
  const glm::vec3 center = 0.5f * (b.lo + b.hi);
  glm::mat4 planeVP[kMaxDirectional];
  glm::vec3 planeOrigin[kMaxDirectional];
  float planeTexel[kMaxDirectional] = {};
  {
    auto s = prof.scope("shadow_maps");
    glUseProgram(shadowProg);
    glBindFramebuffer(GL_FRAMEBUFFER, shadowFbo);
    glViewport(0, 0, shadowRes_, shadowRes_);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    const float far = 1e30f;
    // Cube faces in GL's order with their conventional up vectors.
    const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    int cube = 0, plane = 0;
    for (auto& l : scene.lights) {
      if (l.type != LightType::Directional) {
        float maxDist = glm::length(glm::max(glm::abs(b.lo - l.position), glm::abs(b.hi - l.position))) * 1.01f + 1e-6f;
        float nearP = std::max(maxDist * 1e-5f, 1e-7f);
        glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, nearP, maxDist);
        glUniform3fv(glGetUniformLocation(shadowProg, "uLightPosition"), 1, &l.position.x);
        glUniform1i(glGetUniformLocation(shadowProg, "uDirectional"), 0);
        for (int f = 0; f < 6; ++f) {
          glNamedFramebufferTextureLayer(shadowFbo, GL_COLOR_ATTACHMENT0, cubeArray, 0, 6 * cube + f);
          const float clear[4] = {far, far, far, far};
          glClearBufferfv(GL_COLOR, 0, clear);
          glClear(GL_DEPTH_BUFFER_BIT);
          glm::mat4 vp = proj * glm::lookAt(l.position, l.position + dirs[f], ups[f]);
          glUniformMatrix4fv(glGetUniformLocation(shadowProg, "uViewProj"), 1, GL_FALSE, glm::value_ptr(vp));
          gpu->draw();
        }
        ++cube;
      } else {
        glm::vec3 d = glm::normalize(l.direction);
        glm::vec3 up = std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        float r = 0.5f * diag * 1.01f;
        planeOrigin[plane] = center - d * r;
        glm::mat4 view = glm::lookAt(planeOrigin[plane], center, up);
        planeVP[plane] = glm::ortho(-r, r, -r, r, 0.0f, 2.0f * r) * view;
        planeTexel[plane] = 2.0f * r / float(shadowRes_);
        glUniform3fv(glGetUniformLocation(shadowProg, "uLightPosition"), 1, &planeOrigin[plane].x);
        glUniform3fv(glGetUniformLocation(shadowProg, "uLightDirection"), 1, &d.x);
        glUniform1i(glGetUniformLocation(shadowProg, "uDirectional"), 1);
        glNamedFramebufferTextureLayer(shadowFbo, GL_COLOR_ATTACHMENT0, planeArray, 0, plane);
        const float clear[4] = {far, far, far, far};
        glClearBufferfv(GL_COLOR, 0, clear);
        glClear(GL_DEPTH_BUFFER_BIT);
        glUniformMatrix4fv(glGetUniformLocation(shadowProg, "uViewProj"), 1, GL_FALSE, glm::value_ptr(planeVP[plane]));
        gpu->draw();
        ++plane;
      }
    }
  }

  // ---- G-buffer targets and the accumulation image
  unsigned gTex[3], gDepth = 0, gFbo = 0, accum = 0;
  glCreateTextures(GL_TEXTURE_2D, 3, gTex);
  for (unsigned t : gTex) glTextureStorage2D(t, 1, GL_RGBA32F, W, H);
  glCreateRenderbuffers(1, &gDepth);
  glNamedRenderbufferStorage(gDepth, GL_DEPTH_COMPONENT32F, W, H);
  glCreateFramebuffers(1, &gFbo);
  for (int i = 0; i < 3; ++i) glNamedFramebufferTexture(gFbo, GL_COLOR_ATTACHMENT0 + i, gTex[i], 0);
  glNamedFramebufferRenderbuffer(gFbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, gDepth);
  const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  glNamedFramebufferDrawBuffers(gFbo, 3, bufs);
  if (glCheckNamedFramebufferStatus(gFbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    fail("method direct: the G-buffer framebuffer is incomplete on ", req.gl->renderer());
  glCreateTextures(GL_TEXTURE_2D, 1, &accum);
  glTextureStorage2D(accum, 1, GL_RGBA32F, W, H);
  const float zero[4] = {0, 0, 0, 0};
  glClearTexImage(accum, 0, GL_RGBA, GL_FLOAT, zero);

  const Camera& cam = scene.camera;
  float camFar = glm::length(glm::max(glm::abs(b.lo - cam.position), glm::abs(b.hi - cam.position))) * 1.01f + 1e-6f;
  glm::mat4 proj = glm::perspective(glm::radians(cam.fovYDeg), float(W) / float(H),
                                    std::max(camFar * 1e-5f, 1e-7f), camFar);
  glm::mat4 view = glm::lookAt(cam.position, cam.target, cam.up);

  gpu->bind(shadeProg);
  glProgramUniform3fv(shadeProg, glGetUniformLocation(shadeProg, "uCameraPosition"), 1, &cam.position.x);
  glProgramUniform1f(shadeProg, glGetUniformLocation(shadeProg, "uShadowRes"), float(shadowRes_));
  glProgramUniform1f(shadeProg, glGetUniformLocation(shadeProg, "uShadowBias"), shadowBias_);
  glProgramUniform1f(shadeProg, glGetUniformLocation(shadeProg, "uNormalOffset"), normalOffset_);
  if (planes > 0) {
    glProgramUniformMatrix4fv(shadeProg, glGetUniformLocation(shadeProg, "uPlaneViewProj"), planes, GL_FALSE,
                              glm::value_ptr(planeVP[0]));
    glProgramUniform1fv(shadeProg, glGetUniformLocation(shadeProg, "uPlaneTexelWorld"), planes, planeTexel);
    glProgramUniform3fv(shadeProg, glGetUniformLocation(shadeProg, "uPlaneOrigin"), planes, &planeOrigin[0].x);
  }
  gpu->bind(gbufProg);

  RenderResult result;
  ProgressBar bar("direct", req.spp);
  int done = 0;
  for (; done < req.spp && !interruptRequested(); ++done) {
    // Sample 0 at the pixel centre; then Halton (2,3) offsets in [−½, ½)².
    glm::vec2 j = req.spp == 1 ? glm::vec2(0.0f)
                               : glm::vec2(halton(done + 1, 2), halton(done + 1, 3)) - 0.5f;
    glm::vec2 jNdc = 2.0f * j / glm::vec2(W, H);
    glm::mat4 jitter = glm::translate(glm::mat4(1.0f), glm::vec3(jNdc.x, -jNdc.y, 0.0f));
    glm::mat4 vp = jitter * proj * view;
    {
      auto s = prof.scope("gbuffer");
      glBindFramebuffer(GL_FRAMEBUFFER, gFbo);
      glViewport(0, 0, W, H);
      glEnable(GL_DEPTH_TEST);
      glDisable(GL_CULL_FACE);
      for (int i = 0; i < 3; ++i) glClearBufferfv(GL_COLOR, i, zero);
      glClear(GL_DEPTH_BUFFER_BIT);
      glUseProgram(gbufProg);
      glUniformMatrix4fv(glGetUniformLocation(gbufProg, "uViewProj"), 1, GL_FALSE, glm::value_ptr(vp));
      gpu->draw();
    }
    {
      auto s = prof.scope("shade");
      glUseProgram(shadeProg);
      glm::mat4 inv = glm::inverse(vp);
      glUniformMatrix4fv(glGetUniformLocation(shadeProg, "uInvViewProj"), 1, GL_FALSE, glm::value_ptr(inv));
      for (int i = 0; i < 3; ++i) glBindTextureUnit(unsigned(i), gTex[i]);
      glBindTextureUnit(3, cubeArray);
      glBindTextureUnit(4, planeArray);
      glBindImageTexture(0, accum, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
      glDispatchCompute(unsigned(W + 7) / 8, unsigned(H + 7) / 8, 1);
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    prof.resolve(false);
    if (req.progress) bar.advance();
  }
  bar.finish();

  std::vector<glm::vec4> px(size_t(W) * H);
  {
    auto s = prof.scope("readback");
    glGetTextureImage(accum, 0, GL_RGBA, GL_FLOAT, GLsizei(px.size() * sizeof(glm::vec4)), px.data());
  }
  prof.resolve(true);
  result.image = Image(W, H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const glm::vec4& v = px[size_t(H - 1 - y) * W + x];  // GL rows start at the bottom
      result.image.at(x, y) = v.w > 0 ? glm::vec3(v) / v.w : glm::vec3(0.0f);
    }
  result.sppCompleted = done;
  result.interrupted = done < req.spp;
  result.extra["shadow_maps"] = {{"cube", cubes}, {"directional", planes}, {"resolution", shadowRes_}};

  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &gFbo);
  glDeleteFramebuffers(1, &shadowFbo);
  unsigned rbs[] = {gDepth, shadowDepth};
  glDeleteRenderbuffers(2, rbs);
  glDeleteTextures(3, gTex);
  unsigned texs[] = {accum, cubeArray, planeArray};
  glDeleteTextures(3, texs);
  return result;
}

}  // namespace

std::unique_ptr<Method> createDirectMethod(ParamSet& params, const Scene& scene) {
  return std::make_unique<DirectMethod>(params, scene);
}

}  // namespace vgi
