// Makes the files in shaders/shared/ compile as C++ (with GLM) as well as GLSL 4.50.
// Rules for shared code: no swizzles, no out/inout (return
// structs), no struct constructors (assign fields), float literals with an f
// suffix (GLM has no vec3 * double), const uint instead of enums, and no shift by
// 32 or more. The GLSL side gets the same macros from ShaderLibrary's prelude.
#pragma once
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

#define SHARED_BEGIN \
  namespace vgi {    \
  namespace shared { \
  using namespace glm;
#define SHARED_END \
  }                \
  }
// Always inlined: the kernels are small and called in tight loops, and GLM's
// vec[i] is a switch that only folds away once the index is a constant.
#define SHARED_FN inline __attribute__((always_inline))
// A read-only struct parameter: by const reference in C++, by value in GLSL.
#define SHARED_IN(T) const T&
// GLSL `precise` (no fused multiply-add) where GPU and CPU must agree bit for
// bit; the C++ side gets the same by compiling with -ffp-contract=off.
#define SHARED_PRECISE
// Kernels that read the OR-mip pyramid take its words as a pointer in C++; in
// GLSL they read a buffer named pyramidWords declared by the including shader.
#define PYRAMID_PARAM , const uint* pyramidWords
#define PYRAMID_ARG , pyramidWords
// Likewise the BVH's nodes and triangles (shared/trace_bvh.glsl): buffers bvhNodes and bvhTris in GLSL.
#define BVH_PARAM , const vec4 *bvhNodes, const vec4 *bvhTris
#define BVH_ARG , bvhNodes, bvhTris
