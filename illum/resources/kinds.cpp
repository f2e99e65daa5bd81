// The resource kinds, as an explicit table (like the method registry): a new
// shared structure is one file pair in this folder and one row here.
#include "illum/framework/resources.h"
#include "illum/resources/binary_grid.h"
#include "illum/resources/bvh.h"
#include "illum/resources/cone_volume.h"
#include "illum/resources/gpu_bvh.h"
#include "illum/resources/gpu_emitters.h"
#include "illum/resources/gpu_scene.h"
#include "illum/resources/light_maps.h"
#include "illum/resources/occluders.h"
#include "illum/resources/or_mip_pyramid.h"
#include "illum/resources/sparse_octree.h"
#include "illum/resources/value_grids.h"

namespace vgi {

const std::vector<ResourceKind>& resourceKinds() {
  static const std::vector<ResourceKind> kinds = {
      gpuSceneKind(),  lightMapsKind(),  binaryGridKind(), orMipPyramidKind(), valueGridsKind(),   bvhKind(),
      occludersKind(), coneVolumeKind(), gpuBvhKind(),     gpuEmittersKind(),  sparseOctreeKind(),
  };
  return kinds;
}

}  // namespace vgi
