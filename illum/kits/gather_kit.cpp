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
  checkBlockLayout(blurProg_, "Gather", sizeof(shared::GatherParams), "illum/gather/blur.comp.glsl");
  checkBlockLayout(upProg_, "Gather", sizeof(shared::GatherParams), "illum/gather/upsample.comp.glsl");
  shared::GatherParams& p = block_.value;
  p = shared::GatherParams{};
  const float pixelAngle = 2.0f * std::tan(glm::radians(f.scene.camera.fovYDeg) * 0.5f) / float(f.height());
  p.camera = glm::vec4(f.camera.position, pixelAngle);
  p.scale = scale_;
  p.rays = s.rays;
  p.interleave = s.interleave;
}

void GatherKit::checkPass(const ComputePassBase& pass) {
  checkBlockLayout(pass.program(), "Gather", sizeof(shared::GatherParams), pass.files());
}

void GatherKit::setSample(int k) {
  block_.value.frame = k;
  // Sample 0 unrotated; later samples rotate by Halton (5, 7) points.
  block_.value.rotation = k == 0 ? glm::vec4(0.0f) : glm::vec4(halton(k, 5), halton(k, 7), 0.0f, 0.0f);
}

void GatherKit::upload() {
  block_.upload();
  block_.buffer().bind(UBO_GATHER);
}

void GatherKit::dispatchGather(int items, int perDispatch) {
  glBindImageTexture(IMAGE_OUTPUT, low_[0], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  perDispatch = std::max(1, perDispatch);
  shared::GatherParams& p = block_.value;
  for (int first = 0; first == 0 || first < items; first += perDispatch) {
    p.batchFirst = first;
    p.batchEnd = std::min(items, first + perDispatch);
    p.accumulate = first > 0 ? 1 : 0;
    upload();
    glDispatchCompute(unsigned(lw_ + 7) / 8, unsigned(lh_ + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

unsigned GatherKit::blurInto(Frame& f, unsigned low, const char* pass) {
  auto s = f.profiler.scope(pass);
  glUseProgram(blurProg_);
  block_.value.camera = glm::vec4(f.camera.position, block_.value.camera.w);
  upload();
  f.gbuffer().bind();
  glBindTextureUnit(TEXUNIT_PASS_INPUT, low);
  glBindImageTexture(IMAGE_OUTPUT, low_[1], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(unsigned(lw_ + 7) / 8, unsigned(lh_ + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  return low_[1];
}

void GatherKit::upsample(Frame& f, unsigned input) {
  glUseProgram(upProg_);
  block_.value.camera = glm::vec4(f.camera.position, block_.value.camera.w);
  upload();
  f.gbuffer().bind();
  glBindTextureUnit(TEXUNIT_PASS_INPUT, input);
  glDispatchCompute(unsigned(f.width() + 7) / 8, unsigned(f.height() + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void GatherKit::resolve(Frame& f) {
  const unsigned input = blur_ ? blurInto(f, low_[0], "blur") : low_[0];
  auto s = f.profiler.scope(scale_ > 1 ? "upsample_composite" : "composite");
  shared::GatherParams& p = block_.value;
  p.composite = s_.reflect ? 0 : 1;
  p.writeIndirect = f.wants("indirect") ? 1 : 0;
  p.writeDirect = f.wants("direct") ? 1 : 0;
  bindSampleAndSplitImages(f);
  upsample(f, input);
}

void GatherKit::resolveValue(Frame& f, unsigned low, unsigned full, const std::string& name) {
  const unsigned input = blur_ ? blurInto(f, low, ("blur_" + name).c_str()) : low;
  auto s = f.profiler.scope("upsample_" + name);
  shared::GatherParams& p = block_.value;
  p.composite = 1;
  p.writeIndirect = 0;
  p.writeDirect = 0;
  glBindImageTexture(IMAGE_SAMPLE, full, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  upsample(f, input);
}

}  // namespace vgi
