// The scene as the GL modules see it: std430 structs shared with C++, binding
// points, and (GLSL only) the buffer and texture declarations.
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "lights.glsl"

#include "bindings.glsl"

SHARED_BEGIN
// The vertex buffer: per corner (3 per triangle, the flattened scene's order)
// position, shading normal, uv, the triangle's unit geometric normal.
const uint SCENE_VERTEX_FLOATS = 11u;
const uint SCENE_VERTEX_UV = 6u;  // the uv's first float

struct PackedMaterial {
  vec4 albedoLayer;     // rgb albedo, w = texture layer or −1
  vec4 ksExponent;      // rgb ks, w = Phong exponent
  vec4 emission;        // rgb emission
};
SHARED_END

#ifndef __cplusplus
layout(std430, binding = BINDING_MATERIALS) readonly buffer MaterialBuffer { PackedMaterial materials[]; };
layout(std430, binding = BINDING_TRI_MATERIAL) readonly buffer TriMaterialBuffer { int triMaterial[]; };
layout(std430, binding = BINDING_LIGHTS) readonly buffer LightBuffer { PackedLight lights[]; };
// The number of lights (GpuScene::bind). Counts come from the host, never from `.length()` of a runtime
// array: zink on lavapipe answered 0 or another buffer's length there (vpl placed no VPL), and a
// length follows the bound range, which a driver may round (tests/core/gl_test.cpp, Shaders.*).
uniform int uLightCount;
layout(binding = TEXUNIT_ALBEDO_ARRAY) uniform sampler2DArray albedoTextures;
layout(binding = TEXUNIT_ENV_MAP) uniform sampler2D envMap;
uniform vec4 uEnvColorScale;  // rgb constant colour, w = map scale
uniform int uEnvHasMap;

vec3 gpuEnvironmentRadiance(vec3 dir) {
  if (uEnvHasMap == 0) return vec3(uEnvColorScale.x, uEnvColorScale.y, uEnvColorScale.z);
  vec2 uv = latLongUv(dir);
  return texture(envMap, vec2(uv.x, 1.0f - uv.y)).xyz * uEnvColorScale.w;
}

BrdfParams gpuMaterialBrdf(int index, vec3 texturedAlbedo) {
  BrdfParams b;
  b.albedo = texturedAlbedo;
  b.ks = vec3(materials[index].ksExponent.x, materials[index].ksExponent.y, materials[index].ksExponent.z);
  b.exponent = materials[index].ksExponent.w;
  return b;
}
#endif
