// The tracer of a GL pass that traces rays through the scene (the `tracer`
// parameter, traverse/gl_ray_tracer.h): hierarchical, dda or march through
// the binary grid's OR-mip pyramid, or bvh through the scene's triangles on
// the GPU (resource kind gpu_bvh) — exact visibility with everything else of
// the method unchanged: a hit is reported in the grid cell that holds it, so
// the value grids, the back-projection and passHit work as with voxels (VGI's
// error split: the visibility stage without leaving the device).
#pragma once
#include <string>

#include "illum/resources/binary_grid.h"

namespace vgi {

class ShaderLibrary;

// The pyramid over `grid` (the cells hits are reported in) and, with tracer=bvh, the BVH.
void addTracerNeeds(SceneNeeds& needs, const BinaryGridNeed& grid, const std::string& tracer);
// Binds what addTracerNeeds declared for `program` (in use).
void bindTracer(const SceneResources& resources, ShaderLibrary& shaders, unsigned program);

}  // namespace vgi
