#include "illum/kits/shared_params.h"

#include "core/params.h"

namespace vgi {

void readShadowParams(ParamSet& p, ShadowParams& s) {
  s.resolution = p.getInt("shadow_res", 1024, "shadow map size (per face)", 16, 8192);
  s.bias = p.getFloat("shadow_bias", 1.0f,
                      "depth bias in shadow-map texels (receiver plane at the texel centre; slope-scaled "
                      "within 0.6 deg of grazing)",
                      0.0f, 100.0f);
  s.normalOffset =
      p.getFloat("normal_offset", 0.0f, "lookup offset along the normal, in texels", 0.0f, 100.0f);
}

}  // namespace vgi
