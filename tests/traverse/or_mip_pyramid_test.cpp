// The OR-mip pyramid: on the CPU it is checked against its definition (a bit
// is set at level l iff some level-0 column of the 2^l × 2^l block below has
// it); the GPU build must equal the CPU build bit for bit. Grids are odd-sized
// and deep on purpose (edges with missing children, several slabs).
#include "traverse/or_mip_pyramid.h"

#include <random>

#include "core/gl_context.h"
#include "core/shader_library.h"
#include "test_util.h"
#include "traverse/gl_ray_tracer.h"

namespace vgi {

namespace {
BinaryGrid randomGrid(glm::uvec3 res, double density, uint32_t seed) {
  GridBox box;
  box.resolution = res;
  box.extent = glm::vec3(res);
  BinaryGrid g(box);
  std::mt19937 rng(seed);
  std::bernoulli_distribution bit(density);
  for (uint32_t z = 0; z < res.z; ++z)
    for (uint32_t y = 0; y < res.y; ++y)
      for (uint32_t x = 0; x < res.x; ++x)
        if (bit(rng)) g.set(x, y, z);
  return g;
}
}  // namespace

TEST(OrMipPyramid, EveryLevelIsTheOrOfItsBlock) {
  for (glm::uvec3 res :
       {glm::uvec3(1, 1, 128), glm::uvec3(5, 3, 128), glm::uvec3(37, 20, 256), glm::uvec3(16, 16, 512)}) {
    BinaryGrid g = randomGrid(res, 0.004, res.x * 7 + res.y);
    OrMipPyramid p(g);
    ASSERT_EQ(p.levelSize(p.levels() - 1), glm::uvec2(1));
    for (uint32_t l = 0; l < p.levels(); ++l) {
      glm::uvec2 s = p.levelSize(l);
      for (uint32_t y = 0; y < s.y; ++y)
        for (uint32_t x = 0; x < s.x; ++x)
          for (uint32_t z = 0; z < res.z; ++z) {
            bool any = false;
            for (uint32_t by = y << l; by < std::min(res.y, (y + 1) << l) && !any; ++by)
              for (uint32_t bx = x << l; bx < std::min(res.x, (x + 1) << l) && !any; ++bx)
                any = g.test(bx, by, z);
            ASSERT_EQ(p.test(l, x, y, z), any)
                << "level " << l << " column " << x << "," << y << " cell " << z;
          }
    }
  }
}

TEST(OrMipPyramid, GpuBuildEqualsCpuBuild) {
  auto gl = GlContext::create();
  ShaderLibrary shaders;
  for (glm::uvec3 res : {glm::uvec3(5, 3, 128), glm::uvec3(37, 20, 256), glm::uvec3(64, 64, 1024)}) {
    BinaryGrid g = randomGrid(res, 0.01, res.x + 3 * res.y);
    OrMipPyramid cpu(g);
    OrMipPyramid gpu(g.box(), buildOrMipGl(g, shaders));
    EXPECT_EQ(cpu.words(), gpu.words()) << res.x << "x" << res.y << "x" << res.z;
  }
  EXPECT_EQ(gl->errorCount(), 0);
  test::expectError([] { OrMipPyramid(GridBox(), std::vector<uint32_t>(3)); }, {"3 words given"});
}

}  // namespace vgi
