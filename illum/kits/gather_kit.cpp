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

namespace {
ShaderDefines with(ShaderDefines defs, const char* name) {
  defs[name] = "1";
  return defs;
}
}  // namespace

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

void readGatherWallParams(ParamSet& p, GatherSettings& s, bool visibilityByDefault, bool fixupByDefault) {
  s.visibility =
      p.getBool("blur_visibility", visibilityByDefault,
                "blur and upsampling weigh only neighbours the voxels show (no light across thin walls)");
  s.fixup =
      p.getBool("fixup", fixupByDefault,
                "pixels with no gather pixel on their surface are gathered at full rate (thin features)");
}

void GatherKit::prepare(Frame& f, const GatherSettings& s, const ShaderDefines& tracerDefines,
                        float visibilityOffset) {
  s_ = s;
  ShaderLibrary& shaders = f.shaders();
  scale_ = int(std::lround(1.0f / s.resolution));
  lw_ = (f.width() + scale_ - 1) / scale_;
  lh_ = (f.height() + scale_ - 1) / scale_;
  low_[0] = f.scratchTexture("gather", lw_, lh_, GL_RGBA32F);
  low_[1] = f.scratchTexture("gather_blurred", lw_, lh_, GL_RGBA32F);
  blur_ = s.blur && s.interleave > 1;
  ShaderDefines defs;
  if (s.visibility) {
    defs = tracerDefines;
    defs["GATHER_VISIBILITY"] = "1";
  }
  blurProg_ = shaders.program({"illum/gather/blur.comp.glsl"}, defs);
  fullW_ = f.width();
  fullH_ = f.height();
  if (s.fixup) {
    listProg_ = shaders.program({"illum/gather/upsample.comp.glsl"}, with(defs, "GATHER_FIXUP_LIST"));
    checkBlockLayout(listProg_, "Gather", sizeof(shared::GatherParams), "illum/gather/upsample.comp.glsl");
    fixupTexture_ = f.scratchTexture("gather_fixup", fullW_, fullH_, GL_RGBA32F);
    const size_t bytes = 16 + 4 * size_t(fullW_) * size_t(fullH_);
    if (bytes != fixupListBytes_) {
      fixupList_ = makeBuffer(bytes);
      fixupListBytes_ = bytes;
    }
  }
  upProg_ = shaders.program({"illum/gather/upsample.comp.glsl"}, s.fixup ? with(defs, "GATHER_FIXUP") : defs);
  if (s.visibility) {
    edgesProg_ = shaders.program({"illum/gather/edges.comp.glsl"}, defs);
    edges_ = f.scratchTexture("gather_edges", lw_, lh_, GL_R32UI);
    checkBlockLayout(edgesProg_, "Gather", sizeof(shared::GatherParams), "illum/gather/edges.comp.glsl");
  }
  checkBlockLayout(blurProg_, "Gather", sizeof(shared::GatherParams), "illum/gather/blur.comp.glsl");
  checkBlockLayout(upProg_, "Gather", sizeof(shared::GatherParams), "illum/gather/upsample.comp.glsl");
  shared::GatherParams& p = block_.value;
  p = shared::GatherParams{};
  const float pixelAngle = 2.0f * std::tan(glm::radians(f.scene.camera.fovYDeg) * 0.5f) / float(f.height());
  p.camera = glm::vec4(f.camera.position, pixelAngle);
  p.scale = scale_;
  p.rays = s.rays;
  p.interleave = s.interleave;
  p.visibilityOffset = visibilityOffset;
}

void GatherKit::checkPass(const ComputePassBase& pass) {
  checkBlockLayout(pass.program(), "Gather", sizeof(shared::GatherParams), pass.files());
}

glm::vec2 seedShift(uint32_t seed) {
  const double n = double(seed - 1u);  // (seed 0 wraps to the 2³²−1-th point)
  const double a1 = 0.75487766624669276, a2 = 0.56984029099805327;  // 1/φ₂, 1/φ₂² (the plastic number)
  return glm::vec2(float(n * a1 - std::floor(n * a1)), float(n * a2 - std::floor(n * a2)));
}

void GatherKit::setSample(int k, uint32_t seed) {
  block_.value.frame = k;
  // Sample 0 unrotated; later samples rotate by Halton (5, 7) points; all of them shifted by the seed.
  const glm::vec2 base = k == 0 ? glm::vec2(0.0f) : glm::vec2(halton(k, 5), halton(k, 7));
  const glm::vec2 r = glm::fract(base + seedShift(seed));
  block_.value.rotation = glm::vec4(r, 0.0f, 0.0f);
}

void GatherKit::upload() {
  block_.upload();
  block_.buffer().bind(UBO_GATHER);
}

void GatherKit::dispatchBatches(int items, int perDispatch, int width, int height, unsigned indirect) {
  perDispatch = std::max(1, perDispatch);
  shared::GatherParams& p = block_.value;
  for (int first = 0; first == 0 || first < items; first += perDispatch) {
    p.batchFirst = first;
    p.batchEnd = std::min(items, first + perDispatch);
    p.accumulate = first > 0 ? 1 : 0;
    upload();
    if (indirect) {
      glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, indirect);
      glDispatchComputeIndirect(4);  // GatherFixup::fixupGroups
      glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    } else {
      glDispatchCompute(unsigned(width + 7) / 8, unsigned(height + 7) / 8, 1);
    }
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void GatherKit::dispatchGather(int items, int perDispatch) {
  glBindImageTexture(IMAGE_OUTPUT, low_[0], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  dispatchBatches(items, perDispatch, lw_, lh_);
}

unsigned GatherKit::blurInto(Frame& f, unsigned low, const char* pass,
                             const std::function<void(unsigned)>& bindTracer) {
  auto s = f.profiler.scope(pass);
  glUseProgram(blurProg_);
  if (s_.visibility && bindTracer) bindTracer(blurProg_);
  block_.value.camera = glm::vec4(f.camera.position, block_.value.camera.w);
  upload();
  f.gbuffer().bind();
  glBindTextureUnit(TEXUNIT_PASS_INPUT, low);
  glBindImageTexture(IMAGE_OUTPUT, low_[1], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(unsigned(lw_ + 7) / 8, unsigned(lh_ + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  return low_[1];
}

void GatherKit::upsample(Frame& f, unsigned input, const std::function<void(unsigned)>& bindTracer) {
  glUseProgram(upProg_);
  if (s_.visibility && bindTracer) bindTracer(upProg_);
  block_.value.camera = glm::vec4(f.camera.position, block_.value.camera.w);
  upload();
  f.gbuffer().bind();
  glBindTextureUnit(TEXUNIT_PASS_INPUT, input);
  glDispatchCompute(unsigned(f.width() + 7) / 8, unsigned(f.height() + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void GatherKit::edges(Frame& f, const std::function<void(unsigned)>& bindTracer) {
  if (!s_.visibility) return;
  auto s = f.profiler.scope("gather_edges");
  glUseProgram(edgesProg_);
  if (bindTracer) bindTracer(edgesProg_);
  block_.value.camera = glm::vec4(f.camera.position, block_.value.camera.w);
  upload();
  f.gbuffer().bind();
  glBindImageTexture(IMAGE_OUTPUT, edges_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
  glDispatchCompute(unsigned(lw_ + 7) / 8, unsigned(lh_ + 7) / 8, 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  glBindTextureUnit(TEXUNIT_PASS_INPUT2, edges_);
}

void GatherKit::dispatchFixup(int items, int perDispatch) {
  glBindImageTexture(IMAGE_OUTPUT, fixupTexture_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_GATHER_FIXUP, fixupList_.get());
  // ⌈count / 64⌉ groups, read from the list (gather_pass.glsl): invocation i takes entry i. The
  // listed pixels are scattered, so the invocations that one llvmpipe thread runs in lockstep trace
  // unrelated rays; its loop limit (65535 iterations per invocation, counted over the lockstep loop,
  // gather.glsl) then cuts rays short depending on their neighbours in the list: the kit runs
  // perDispatch / 4 items per dispatch here (4 rays × 4 traces × 1539 DDA steps at 512³ stay under it).
  dispatchBatches(items, std::max(1, perDispatch / 4), fullW_, fullH_, fixupList_.get());
}

void GatherKit::fixup(Frame& f, unsigned input, const std::function<void(unsigned)>& bindTracer,
                      const std::function<void()>& fixupGather) {
  if (!s_.fixup) return;
  auto s = f.profiler.scope("fixup");
  // No fix-up yet (w = 0 everywhere: the upsampling's own answer), and an empty list.
  glClearTexImage(fixupTexture_, 0, GL_RGBA, GL_FLOAT, nullptr);
  glBindTextureUnit(TEXUNIT_GATHER_FIXUP, fixupTexture_);
  if (!fixupGather) return;
  const uint32_t header[4] = {0, 0, 1, 1};  // no entries; groups 0 × 1 × 1
  glNamedBufferSubData(fixupList_.get(), 0, sizeof header, header);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  glUseProgram(listProg_);
  if (s_.visibility && bindTracer) bindTracer(listProg_);
  upload();
  f.gbuffer().bind();
  glBindTextureUnit(TEXUNIT_PASS_INPUT, input);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_GATHER_FIXUP, fixupList_.get());
  glDispatchCompute(unsigned(fullW_ + 7) / 8, unsigned(fullH_ + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  // The method's gather at the listed pixels (dispatchFixup), which the upsampling reads.
  fixupGather();
}

void GatherKit::stats(Frame& f) const {
  if (!s_.fixup) return;
  uint32_t count = 0;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(fixupList_.get(), 0, 4, &count);
  f.extra["fixup_pixels"] = count;
  f.addStateBytes(double(fixupListBytes_));  // the list (its textures are the frame's scratch)
}

void GatherKit::resolve(Frame& f, const std::function<void(unsigned)>& bindTracer,
                        const std::function<void()>& fixupGather) {
  edges(f, bindTracer);
  const unsigned input = blur_ ? blurInto(f, low_[0], "blur", bindTracer) : low_[0];
  fixup(f, input, bindTracer, fixupGather);
  auto s = f.profiler.scope(scale_ > 1 ? "upsample_composite" : "composite");
  shared::GatherParams& p = block_.value;
  p.composite = s_.reflect ? 0 : 1;
  p.writeIndirect = f.wants("indirect") ? 1 : 0;
  p.writeDirect = f.wants("direct") ? 1 : 0;
  bindSampleAndSplitImages(f);
  upsample(f, input, bindTracer);
}

void GatherKit::resolveValue(Frame& f, unsigned low, unsigned full, const std::string& name,
                             const std::function<void(unsigned)>& bindTracer) {
  edges(f, bindTracer);
  const unsigned input = blur_ ? blurInto(f, low, ("blur_" + name).c_str(), bindTracer) : low;
  fixup(f, input, bindTracer, {});
  auto s = f.profiler.scope("upsample_" + name);
  shared::GatherParams& p = block_.value;
  p.composite = 1;
  p.writeIndirect = 0;
  p.writeDirect = 0;
  glBindImageTexture(IMAGE_SAMPLE, full, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  upsample(f, input, bindTracer);
}

}  // namespace vgi
