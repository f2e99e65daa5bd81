// Cone-volume fixtures of the cone-tracing tests (vct_test.cpp, sparse_octree_test.cpp):
// a unit grid box, and the dense volume resolved on the GPU from given counts,
// radiance sums and an occupancy grid.
#pragma once
#include <glad/gl.h>

#include <memory>
#include <string>
#include <vector>

#include "core/gl_context.h"
#include "core/profiler.h"
#include "core/shader_library.h"
#include "shaders/shared/value_grid.glsl"
#include "traverse/gl_ray_tracer.h"
#include "voxelize/value_textures.h"

namespace vgi {
namespace test {

inline GridBox unitBox(glm::uvec3 res) {
  GridBox b;
  b.origin = glm::vec3(0.0f);
  b.extent = glm::vec3(res) / float(res.x);
  b.resolution = res;
  return b;
}

// A volume resolved on the GPU from given counts, radiance sums and an
// occupancy grid (what ConeVolume::update hands ValueTextures::resolve).
struct VolumeFixture {
  std::unique_ptr<GlContext> gl = GlContext::create();
  ShaderLibrary shaders;
  Profiler prof{true};
  GridBox box;
  std::unique_ptr<ValueTextures> tex;
  GlTexture direction;  // with directions: D per cell (RGBA8_SNORM)
  VolumeFixture(const GridBox& b, ValueMips mips, const BinaryGrid& grid, const std::vector<uint32_t>& counts,
                const std::vector<uint32_t>& sums, float radianceMax,
                const std::vector<glm::vec4>* directions = nullptr)
      : box(b) {
    if (directions) {  // the level-0 direction texture, as vct's direction_resolve.comp writes it
      direction = makeGridTexture3D(box.resolution, 1, GL_RGBA8_SNORM, true);
      glTextureSubImage3D(direction.get(), 0, 0, 0, 0, GLsizei(box.resolution.x), GLsizei(box.resolution.y),
                          GLsizei(box.resolution.z), GL_RGBA, GL_FLOAT, directions->data());
    }
    GlPyramid pyramid(box);
    pyramid.build(grid, shaders);
    GlBuffer c = makeBuffer(counts.size() * 4), s = makeBuffer(sums.size() * 4);
    glNamedBufferSubData(c.get(), 0, GLsizeiptr(counts.size() * 4), counts.data());
    glNamedBufferSubData(s.get(), 0, GLsizeiptr(sums.size() * 4), sums.data());
    tex = std::make_unique<ValueTextures>(box, std::vector<std::string>{"radiance"}, mips);
    ValueSumBuffers v;
    v.counts = c.get();
    v.sums[shared::VALUE_CHANNEL_RADIANCE] = s.get();
    v.radianceMax = radianceMax;
    tex->resolve(v, shaders, prof, pyramid.words(), direction.get());
    glFinish();
  }
};

}  // namespace test
}  // namespace vgi
