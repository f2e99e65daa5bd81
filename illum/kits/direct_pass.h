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
  // `sender`: shade also writes the senders of screen-space methods (shade.comp.glsl's DIRECT_SENDER).
  DirectPass(ShaderLibrary& shaders, const GpuScene& gpu, float shadowBias, float normalOffset,
             bool sender = false);
  // The direct light into targetImage; with `sender`, each surface's diffuse direct light (no
  // emission) into senderImage (RGBA32F of the same size).
  void shade(const GBuffer& gbuffer, const LightMaps& maps, const FrameCamera& camera, unsigned targetImage,
             unsigned senderImage = 0);

 private:
  ShaderLibrary& shaders_;
  const GpuScene& gpu_;
  unsigned prog_ = 0;
  bool sender_ = false;
};

}  // namespace vgi
