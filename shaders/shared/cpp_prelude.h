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

// What a traversal pays for, counted by the C++ build only (vgi bench traverse): the same kernels, so
// the same rays give the counts the GLSL build has, without a counter in any GPU program (the GLSL
// prelude defines TRACE_FETCHES, TRACE_CLIMB and TRACE_REFINE as nothing). Counting is on for a
// thread while traceCounts points somewhere (RayTracer::countBatch); otherwise one predictable branch.
namespace vgi {
namespace shared {
struct TraceCounts {
  uint32_t fetches = 0;  // memory loads: a 32-bit pyramid word, a BVH vec4
  uint32_t bytes = 0;    // what those loads read
  uint32_t climbs = 0;   // hierarchical: levels gone up (an empty column's exit left its parent)
  uint32_t refines = 0;  // hierarchical: levels gone down (a non-empty coarse column)
};
inline thread_local TraceCounts* traceCounts = nullptr;
}  // namespace shared
}  // namespace vgi
#define TRACE_FETCHES(n, nbytes)                     \
  do {                                               \
    if (::vgi::shared::traceCounts) {                \
      ::vgi::shared::traceCounts->fetches += (n);    \
      ::vgi::shared::traceCounts->bytes += (nbytes); \
    }                                                \
  } while (false)
#define TRACE_CLIMB()                                                     \
  do {                                                                    \
    if (::vgi::shared::traceCounts) ++::vgi::shared::traceCounts->climbs; \
  } while (false)
#define TRACE_REFINE()                                                     \
  do {                                                                     \
    if (::vgi::shared::traceCounts) ++::vgi::shared::traceCounts->refines; \
  } while (false)
