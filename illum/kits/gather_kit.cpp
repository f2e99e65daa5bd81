#include "illum/kits/gather_kit.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/params.h"
#include "core/shader_library.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "shaders/shared/bindings.glsl"

namespace vgi {

GatherSettings readGatherParams(ParamSet& p, const std::string& what, bool reflect, bool rays,
                                int interleaveDefault) {
  GatherSettings s;
  s.reflect = reflect;
  if (rays) s.rays = p.getInt("rays", 16, what + " rays per gather pixel per frame", 1, 4096);
  s.resolution =
      p.getFloat("resolution", 0.5f, what + " resolution: 1, 0.5 or 0.25 of the image", 0.0f, 1.0f);
  if (s.resolution != 1.0f && s.resolution != 0.5f && s.resolution != 0.25f)
    fail("parameter 'resolution': ", s.resolution, " is not one of 1, 0.5, 0.25");
  s.interleave =
      p.getInt("interleave", interleaveDefault,
               "k: the pixels of k x k blocks take k^2 different sets (of directions or VPLs)", 1, 8);
  s.blur = p.getBool("blur", true, "geometry-aware blur over the interleave window");
  return s;
}

void GatherKit::prepare(Frame& f, const GatherSettings& s) {
  s_ = s;
  ShaderLibrary& shaders = f.shaders();
  scale_ = int(std::lround(1.0f / s.resolution));
  lw_ = (f.width() + scale_ - 1) / scale_;
  lh_ = (f.height() + scale_ - 1) / scale_;
  low_[0] = f.scratchTexture("gather", lw_, lh_, GL_RGBA32F);
  low_[1] = f.scratchTexture("gather_blurred", lw_, lh_, GL_RGBA32F);
  blur_ = s.blur && s.interleave > 1;
  blurProg_ = shaders.program({"illum/gather/blur.comp.glsl"});
  upProg_ = shaders.program({"illum/gather/upsample.comp.glsl"});
  const float pixelAngle = 2.0f * std::tan(glm::radians(f.scene.camera.fovYDeg) * 0.5f) / float(f.height());
  for (unsigned prog : {blurProg_, upProg_}) {
    shaders.setUniform(prog, "uPixelAngle", pixelAngle);
    shaders.setUniform(prog, "uScale", scale_);
  }
  shaders.setUniform(blurProg_, "uInterleave", s.interleave);
  shaders.setUniform(upProg_, "uComposite", s.reflect ? 0 : 1);
  shaders.setUniform(upProg_, "uWriteIndirect", f.wants("indirect") ? 1 : 0);
  shaders.setUniform(upProg_, "uWriteDirect", f.wants("direct") ? 1 : 0);
}

void GatherKit::setFrameUniforms(ShaderLibrary& shaders, unsigned prog) const {
  shaders.setUniform(prog, "uScale", scale_);
  shaders.setUniform(prog, "uRays", s_.rays);
  shaders.setUniform(prog, "uInterleave", s_.interleave);
}

void GatherKit::setSampleUniforms(ShaderLibrary& shaders, unsigned prog, int k) const {
  shaders.setUniform(prog, "uFrame", k);
  // Sample 0 unrotated; later samples rotate by Halton (5, 7) points.
  shaders.setUniform(prog, "uRotation", k == 0 ? glm::vec2(0.0f) : glm::vec2(halton(k, 5), halton(k, 7)));
}

void GatherKit::dispatchGather(ShaderLibrary& shaders, unsigned prog, int items, int perDispatch) const {
  glBindImageTexture(IMAGE_OUTPUT, low_[0], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  perDispatch = std::max(1, perDispatch);
  for (int first = 0; first == 0 || first < items; first += perDispatch) {
    shaders.setUniform(prog, "uBatchFirst", first);
    shaders.setUniform(prog, "uBatchEnd", std::min(items, first + perDispatch));
    shaders.setUniform(prog, "uAccumulate", first > 0 ? 1 : 0);
    glDispatchCompute(unsigned(lw_ + 7) / 8, unsigned(lh_ + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

namespace {
// The blur (when on) of `low` into `scratch`; returns what the upsampling reads.
unsigned blurInto(Frame& f, unsigned prog, unsigned low, unsigned scratch, int lw, int lh, const char* pass) {
  auto s = f.profiler.scope(pass);
  glUseProgram(prog);
  f.shaders().setUniform(prog, "uCameraPosition", f.camera.position);
  f.gbuffer().bind();
  glBindTextureUnit(TEXUNIT_PASS_INPUT, low);
  glBindImageTexture(IMAGE_OUTPUT, scratch, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(unsigned(lw + 7) / 8, unsigned(lh + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  return scratch;
}
}  // namespace

void GatherKit::resolve(Frame& f) const {
  ShaderLibrary& shaders = f.shaders();
  const unsigned input = blur_ ? blurInto(f, blurProg_, low_[0], low_[1], lw_, lh_, "blur") : low_[0];
  auto s = f.profiler.scope(scale_ > 1 ? "upsample_composite" : "composite");
  glUseProgram(upProg_);
  shaders.setUniform(upProg_, "uCameraPosition", f.camera.position);
  f.gbuffer().bind();
  glBindTextureUnit(TEXUNIT_PASS_INPUT, input);
  bindSampleAndSplitImages(f);
  glDispatchCompute(unsigned(f.width() + 7) / 8, unsigned(f.height() + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void GatherKit::resolveValue(Frame& f, unsigned low, unsigned full, const std::string& name) const {
  ShaderLibrary& shaders = f.shaders();
  const unsigned input =
      blur_ ? blurInto(f, blurProg_, low, low_[1], lw_, lh_, ("blur_" + name).c_str()) : low;
  auto s = f.profiler.scope("upsample_" + name);
  glUseProgram(upProg_);
  shaders.setUniform(upProg_, "uCameraPosition", f.camera.position);
  shaders.setUniform(upProg_, "uComposite", 1);
  shaders.setUniform(upProg_, "uWriteIndirect", 0);
  shaders.setUniform(upProg_, "uWriteDirect", 0);
  f.gbuffer().bind();
  glBindTextureUnit(TEXUNIT_PASS_INPUT, input);
  glBindImageTexture(IMAGE_SAMPLE, full, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  glDispatchCompute(unsigned(f.width() + 7) / 8, unsigned(f.height() + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  shaders.setUniform(upProg_, "uComposite", s_.reflect ? 0 : 1);
  shaders.setUniform(upProg_, "uWriteIndirect", f.wants("indirect") ? 1 : 0);
  shaders.setUniform(upProg_, "uWriteDirect", f.wants("direct") ? 1 : 0);
}

}  // namespace vgi
