// Octahedral maps of the sphere of directions (Cigolle, Donow, Evangelakos, Mara, McGuire, Meyer, "A
// Survey of Efficient Representations for Independent Unit Vectors", JCGT 3(2), 2014, §3.4) in square
// tiles with a one-texel border, as DDGI stores each probe's irradiance and distance (Majercik et al.
// 2019, §4: the border repeats the texels across the map's folded edges, so bilinear filtering at a
// tile's edge reads its neighbours on the sphere); and the spherical Fibonacci point set of a probe's
// rays (Keinert, Innmann, Sänger, Stamminger, "Spherical Fibonacci Mapping", TOG 34(6), 2015).
// Shared GLSL and C++ (tests/illum/ddgi_test.cpp checks the maps on the CPU).
#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
#include "constants.glsl"
SHARED_BEGIN

SHARED_FN float signNotZero(float v) { return v >= 0.0f ? 1.0f : -1.0f; }

// A unit direction's point in [−1, 1]²: the upper hemisphere (z ≥ 0) is the inner diamond.
SHARED_FN vec2 octEncode(vec3 d) {
  float l1 = abs(d.x) + abs(d.y) + abs(d.z);
  float x = d.x / l1, y = d.y / l1;
  if (d.z < 0.0f) {
    float fx = (1.0f - abs(y)) * signNotZero(x);
    float fy = (1.0f - abs(x)) * signNotZero(y);
    x = fx;
    y = fy;
  }
  return vec2(x, y);
}

// The unit direction of a point in [−1, 1]² (octEncode's inverse).
SHARED_FN vec3 octDecode(vec2 e) {
  float x = e.x, y = e.y;
  float z = 1.0f - abs(x) - abs(y);
  if (z < 0.0f) {
    float fx = (1.0f - abs(y)) * signNotZero(x);
    float fy = (1.0f - abs(x)) * signNotZero(y);
    x = fx;
    y = fy;
  }
  return normalize(vec3(x, y, z));
}

// The interior texel that texel t of a tile `size` texels wide (an interior of size − 2 and a
// one-texel border) repeats: itself inside; across an edge the map folds there, so a border texel
// repeats the interior texel mirrored along that edge; a corner the interior's opposite corner.
SHARED_FN ivec2 octTileInterior(ivec2 t, int size) {
  int last = size - 1;
  bool bx = t.x == 0 || t.x == last, by = t.y == 0 || t.y == last;
  if (bx && by) return ivec2(t.x == 0 ? last - 1 : 1, t.y == 0 ? last - 1 : 1);
  if (bx) return ivec2(t.x == 0 ? 1 : last - 1, last - t.y);
  if (by) return ivec2(last - t.x, t.y == 0 ? 1 : last - 1);
  return t;
}

// The direction texel t of such a tile stands for (its interior texel's centre).
SHARED_FN vec3 octTexelDirection(ivec2 t, int size) {
  ivec2 i = octTileInterior(t, size);
  float n = float(size - 2);
  return octDecode(vec2((float(i.x - 1) + 0.5f) / n * 2.0f - 1.0f, (float(i.y - 1) + 0.5f) / n * 2.0f - 1.0f));
}

// Point i of n spherical Fibonacci points (unit directions, evenly spread over the sphere).
SHARED_FN vec3 sphericalFibonacci(float i, float n) {
  const float goldenFraction = 0.618033988749895f;  // φ − 1
  float phi = 2.0f * PI * fract(i * goldenFraction);
  float cosTheta = 1.0f - (2.0f * i + 1.0f) / n;
  float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
  return vec3(cos(phi) * sinTheta, sin(phi) * sinTheta, cosTheta);
}

SHARED_END
