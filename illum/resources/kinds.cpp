// The resource kinds, as an explicit table (like the method registry): a new
// shared structure is one file pair in this folder and one row here. (The framework reads a need's
// row from the need itself, ResourceNeed::kindRow(): it knows no kind.)
#include "illum/resources/kinds.h"

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

const std::vector<const ResourceKind*>& resourceKinds() {
  static const std::vector<const ResourceKind*> kinds = {
      &GpuSceneNeed::row(),  &LightMapNeed::row(),    &BinaryGridNeed::row(),   &OrMipPyramidNeed::row(),
      &ValueGridNeed::row(), &BvhNeed::row(),         &OccluderNeed::row(),     &ConeVolumeNeed::row(),
      &GpuBvhNeed::row(),    &GpuEmittersNeed::row(), &SparseOctreeNeed::row(),
  };
  return kinds;
}

}  // namespace vgi
