#include "illum/framework/deferred.h"

#include <glad/gl.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <vector>

#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/shader_library.h"
#include "shaders/shared/gbuffer.glsl"

namespace vgi {

float halton(int index, int base) {
  float f = 1, r = 0;
  for (int i = index; i > 0; i /= base) {
    f /= float(base);
    r += f * float(i % base);
  }
  return r;
}

FrameCamera frameCamera(const Camera& cam, const Bounds& b, int W, int H, int frame) {
  // Reversed-Z with an infinite far plane (GBuffer::render sets depth [0, 1]
  // and GL_GREATER): depth = near / distance, whose float precision is
  // relative at every distance. The usual [−1, 1] mapping with this near
  // plane resolved only ~3 mm at 1 m: a back face beside a silhouette tied
  // with the front face and won a 1-pixel column (seen on the Cornell box).
  const float camFar =
      glm::length(glm::max(glm::abs(b.lo - cam.position), glm::abs(b.hi - cam.position))) * 1.01f + 1e-6f;
  // A cut-away camera's near plane is its clip distance: the raster clips what lies before it. One
  // closer than the plain near plane cuts nothing away: that plane stands (a denormal near plane
  // gave depth near/distance = 0 everywhere, the cleared value, and a black image).
  const float plainNear = std::max(camFar * 1e-5f, 1e-7f);
  const float nearP = std::max(cam.clipNear, plainNear),
              f = 1.0f / std::tan(0.5f * glm::radians(cam.fovYDeg));
  glm::mat4 proj(0.0f);
  proj[0][0] = f * float(H) / float(W);
  proj[1][1] = f;
  proj[2][3] = -1.0f;  // w_clip = distance along the view axis
  proj[3][2] = nearP;  // z_clip = near

  glm::mat4 view = glm::lookAt(cam.position, cam.target, cam.up);
  // (Frame 0 was Halton point 1, (½, ⅓), unless it was the only frame: then a run's first sample
  // depended on its length, and a 1-sample viewer screenshot was not `vgi render --spp 1`.)
  glm::vec2 j = frame == 0 ? glm::vec2(0.0f) : glm::vec2(halton(frame + 1, 2), halton(frame + 1, 3)) - 0.5f;
  glm::vec2 jNdc = 2.0f * j / glm::vec2(W, H);
  glm::mat4 jitter = glm::translate(glm::mat4(1.0f), glm::vec3(jNdc.x, -jNdc.y, 0.0f));
  FrameCamera c;
  c.viewProj = jitter * proj * view;
  c.invViewProj = glm::inverse(c.viewProj);
  c.position = cam.position;
  c.forward = glm::normalize(cam.target - cam.position);
  c.clipNear = cam.clipNear;
  return c;
}

PinholeView pinholeView(const Camera& cam, int W, int H) {
  PinholeView v;
  v.position = cam.position;
  v.fwd = glm::normalize(cam.target - cam.position);
  v.right = glm::normalize(glm::cross(v.fwd, cam.up));
  v.up = glm::cross(v.right, v.fwd);
  v.tanHalf = std::tan(glm::radians(cam.fovYDeg) * 0.5f);
  v.aspect = float(W) / float(H);
  v.clipNear = cam.clipNear;
  return v;
}

GBuffer::GBuffer(int W, int H, ShaderLibrary& shaders) : w_(W), h_(H), shaders_(shaders) {
  GLint maxTex = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTex);
  if (W > maxTex || H > maxTex)
    fail("--size ", W, "x", H, " exceeds this GL's largest texture (", maxTex, ")");
  prog_ = shaders.program({"illum/raster/surface.vert.glsl", "illum/raster/gbuffer.frag.glsl"});
  for (GlTexture& t : tex_) t = makeTexture2D(W, H, GL_RGBA32F);
  glCreateRenderbuffers(1, &depth_);
  glNamedRenderbufferStorage(depth_, GL_DEPTH_COMPONENT32F, W, H);
  glCreateFramebuffers(1, &fbo_);
  for (int i = 0; i < 4; ++i) glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0 + i, tex_[i].get(), 0);
  glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum bufs[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                          GL_COLOR_ATTACHMENT3};
  glNamedFramebufferDrawBuffers(fbo_, 4, bufs);
  if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    fail("the G-buffer framebuffer is incomplete on this GL");
}

GBuffer::~GBuffer() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &depth_);
}

void GBuffer::render(const GpuScene& gpu, const FrameCamera& camera) {
  const float zero[4] = {0, 0, 0, 0};
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, w_, h_);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  // Reversed-Z (see frameCamera); the other passes keep GL's defaults.
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glDepthFunc(GL_GREATER);
  for (int i = 0; i < 4; ++i) glClearBufferfv(GL_COLOR, i, zero);
  const float clearDepth = 0.0f;
  glClearBufferfv(GL_DEPTH, 0, &clearDepth);
  glUseProgram(prog_);
  gpu.bind(shaders_, prog_);
  shaders_.setUniform(prog_, "uViewProj", camera.viewProj);
  gpu.draw();
  glDepthFunc(GL_LESS);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void GBuffer::bind() const {
  const unsigned units[4] = {TEXUNIT_GBUFFER_POSITION, TEXUNIT_GBUFFER_NORMAL, TEXUNIT_GBUFFER_ALBEDO,
                             TEXUNIT_GBUFFER_GEOMETRIC_NORMAL};
  for (unsigned i = 0; i < 4; ++i) glBindTextureUnit(units[i], tex_[i].get());
}

}  // namespace vgi
