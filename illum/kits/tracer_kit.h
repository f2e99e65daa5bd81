// The tracer of a GL pass that traces rays through the scene (the `tracer`
// parameter, traverse/gl_ray_tracer.h): hierarchical, dda or march through
// the binary grid's OR-mip pyramid, or bvh through the scene's triangles on
// the GPU (resource kind gpu_bvh) — exact visibility with everything else of
// the method unchanged: a hit is reported in the grid cell that holds it, so
// the value grids, the back-projection and passHit work as with voxels (VGI's
// error split: the visibility stage without leaving the device).
#pragma once
#include <string>
#include <vector>

#include "illum/framework/compute_pass.h"
#include "illum/resources/binary_grid.h"
#include "shaders/illum/voxel_hit_params.glsl"

namespace vgi {

class ShaderLibrary;

// The pyramid over `grid` (the cells hits are reported in) and, with tracer=bvh, the BVH.
void addTracerNeeds(SceneNeeds& needs, const BinaryGridNeed& grid, const std::string& tracer);
// What illum/voxel_hits.glsl's path vertices read (voxelpath, vpl's bounces, ddgi's probe rays): the
// tracer over `grid` and the value grids of `values` (normal, albedo; glossy where the vertices' Phong
// lobes are lit) at full resolution.
void addVoxelHitNeeds(SceneNeeds& needs, BinaryGridNeed grid, const std::string& tracer,
                      std::vector<std::string> values);
// Binds what addTracerNeeds declared for `program` (in use).
void bindTracer(const SceneResources& resources, ShaderLibrary& shaders, unsigned program);

// The GLSL constant of a `hitpoint` choice (entry, centre, plane): shaders/illum/voxel_hit_params.glsl.
int hitPointConstant(const std::string& name);

// The parameters of illum/voxel_hits.glsl (the path-vertex rules voxelpath
// and vpl share) as their uniform block: set() checks the block's layout in
// `program` and uploads them, bind() binds them at UBO_VOXEL_HITS.
class VoxelHits {
 public:
  void set(unsigned program, const shared::VoxelHitParams& params);
  void bind() const;

 private:
  UniformBlock<shared::VoxelHitParams> block_;
};

}  // namespace vgi
