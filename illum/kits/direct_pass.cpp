#include "illum/kits/direct_pass.h"

#include <glad/gl.h>

#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/shader_library.h"
#include "illum/resources/light_maps.h"
#include "shaders/shared/bindings.glsl"

namespace vgi {

DirectPass::DirectPass(ShaderLibrary& shaders, const GpuScene& gpu, float shadowBias, float normalOffset,
                       bool sender)
    : shaders_(shaders), gpu_(gpu), sender_(sender) {
  ShaderDefines defs;
  if (sender) defs["DIRECT_SENDER"] = "1";
  prog_ = shaders.program({"illum/direct/shade.comp.glsl"}, defs);
  shaders.setUniform(prog_, "uShadowBias", shadowBias);
  shaders.setUniform(prog_, "uNormalOffset", normalOffset);
}

void DirectPass::shade(const GBuffer& g, const LightMaps& maps, const FrameCamera& cam, unsigned target,
                       unsigned sender) {
  if (sender_ && !sender) fail("DirectPass: built with a sender target, shaded without one");
  glUseProgram(prog_);
  gpu_.bind(shaders_, prog_);  // other passes may have used the same binding points
  shaders_.setUniform(prog_, "uCameraPosition", cam.position);
  shaders_.setUniform(prog_, "uInvViewProj", cam.invViewProj);
  g.bind();
  maps.bind();
  glBindImageTexture(IMAGE_SAMPLE, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  if (sender_) glBindImageTexture(IMAGE_OUTPUT2, sender, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(unsigned(g.width() + 7) / 8, unsigned(g.height() + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace vgi
