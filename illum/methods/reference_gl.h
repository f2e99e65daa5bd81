// `reference_gl`: exact integrals on the GL device through the scene's BVH (see reference_gl.cpp).
#pragma once
#include "illum/framework/method.h"

namespace vgi {

// The registry row: name, description, factory (an exact method: no counterpart).
MethodInfo referenceGlMethod();

}  // namespace vgi
