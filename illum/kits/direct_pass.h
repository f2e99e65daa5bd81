// The deferred direct-lighting pass the GL methods share: emission + the delta lights through the
// light maps (illum/resources/light_maps.h), the environment behind, written into an RGBA32F image
// (a sample image of the loop). `direct` is this pass alone; the GI methods add their indirect light
// to it.
#pragma once
#include "illum/framework/deferred.h"

namespace vgi {

class GpuScene;
class LightMaps;
class ShaderLibrary;

class DirectPass {
 public:
  DirectPass(ShaderLibrary& shaders, const GpuScene& gpu, float shadowBias, float normalOffset);
  void shade(const GBuffer& gbuffer, const LightMaps& maps, const FrameCamera& camera, unsigned targetImage);

 private:
  ShaderLibrary& shaders_;
  const GpuScene& gpu_;
  unsigned prog_ = 0;
};

}  // namespace vgi
