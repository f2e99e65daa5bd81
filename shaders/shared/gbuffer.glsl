// Texture units of the G-buffer (illum/framework/deferred.h) as the deferred passes read
// it: world position (w = 1 where a surface was seen), shading normal towards
// the viewer (w = material), albedo, and the triangle's geometric normal (the
// receiver plane of the shadow test); unit 3 is a pass's own input texture.
#ifdef __cplusplus
#pragma once
#endif

#include "bindings.glsl"

#ifndef __cplusplus
layout(binding = TEXUNIT_GBUFFER_POSITION) uniform sampler2D gPosition;
layout(binding = TEXUNIT_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(binding = TEXUNIT_GBUFFER_ALBEDO) uniform sampler2D gAlbedo;
layout(binding = TEXUNIT_GBUFFER_GEOMETRIC_NORMAL) uniform sampler2D gGeometricNormal;
#endif
