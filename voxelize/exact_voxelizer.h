#pragma once
#include "voxelize/voxel_grid.h"

namespace vgi {

// Closed-box triangle–box overlap by the separating axis theorem
// (Akenine-Möller, "Fast 3D Triangle-Box Overlap Testing", JGT 2001): 3 box
// normals, the triangle normal and 9 edge cross products. Touching counts.
bool triangleBoxOverlap(glm::dvec3 center, glm::dvec3 half, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c);

// Every cell whose closed box overlaps a triangle of the scene at `time`.
// shrink > 0 (in cells) tests boxes shrunk by that much on every side: cells the
// surface only grazes drop out ("interior" exact set, for point-based recall).
BinaryGrid voxelizeExact(const Scene& scene, const GridBox& box, float time = 0, int threads = 0,
                         double shrink = 0.0);

}  // namespace vgi
