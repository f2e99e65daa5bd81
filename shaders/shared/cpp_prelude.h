// Makes the files in shaders/shared/ compile as C++ (with GLM) as well as GLSL 4.50.
// Rules for shared code (see STYLE.md): no swizzles, no out/inout (return
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
#define SHARED_FN inline
