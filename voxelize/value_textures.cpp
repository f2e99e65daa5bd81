#include "voxelize/value_textures.h"

#include <glad/gl.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/profiler.h"
#include "core/shader_library.h"
#include "shaders/shared/bindings.glsl"
#include "shaders/shared/value_grid.glsl"
#include "voxelize/value_grids.h"

namespace vgi {

const char* valueMipsName(ValueMips m) {
  return m == ValueMips::None ? "none" : m == ValueMips::Isotropic ? "isotropic" : "anisotropic";
}

GlTexture makeGridTexture3D(glm::uvec3 size, int levels, unsigned format, bool linear) {
  unsigned t = 0;
  glCreateTextures(GL_TEXTURE_3D, 1, &t);
  glTextureStorage3D(t, levels, format, GLsizei(size.x), GLsizei(size.y), GLsizei(size.z));
  const GLint mag = linear ? GL_LINEAR : GL_NEAREST;
  const GLint min = !linear ? GL_NEAREST : levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR;
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, min);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, mag);
  // Outside the grid is empty: the border (0) blends in at the box's faces.
  for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTextureParameteri(t, w, GL_CLAMP_TO_BORDER);
  const float zero[4] = {0, 0, 0, 0};
  glTextureParameterfv(t, GL_TEXTURE_BORDER_COLOR, zero);
  return GlTexture(t);
}

namespace {
constexpr GLenum kChannelFormat[4] = {GL_RGBA16F, GL_RGBA8, GL_RGBA16F,
                                      GL_RGBA16F};  // normal, albedo, glossy, radiance
const char* formatName(GLenum f) {
  return f == GL_RGBA16F ? "rgba16f" : f == GL_RGBA8 ? "rgba8" : f == GL_R8 ? "r8" : "r32ui";
}
size_t texelBytes(GLenum f) { return f == GL_RGBA16F ? 8 : f == GL_RGBA8 || f == GL_R32UI ? 4 : 1; }

glm::uvec3 halve(glm::uvec3 s, int times) {
  return glm::max(glm::uvec3(1u), glm::uvec3(s.x >> times, s.y >> times, s.z >> times));
}

void dispatch3D(glm::uvec3 size) { glDispatchCompute((size.x + 3) / 4, (size.y + 3) / 4, (size.z + 3) / 4); }

template <class Reduce>
std::vector<glm::vec4> mipLevel(const std::vector<glm::vec4>& in, glm::uvec3 s, Reduce reduce) {
  const glm::uvec3 o = halve(s, 1);
  std::vector<glm::vec4> out(size_t(o.x) * o.y * o.z);
  for (uint32_t z = 0; z < o.z; ++z)
    for (uint32_t y = 0; y < o.y; ++y)
      for (uint32_t x = 0; x < o.x; ++x) {
        glm::vec4 c[8];
        for (uint32_t i = 0; i < 8; ++i) {
          const glm::uvec3 p(2 * x + (i & 1), 2 * y + ((i >> 1) & 1), 2 * z + ((i >> 2) & 1));
          c[i] = (p.x < s.x && p.y < s.y && p.z < s.z) ? in[(size_t(p.z) * s.y + p.y) * s.x + p.x]
                                                       : glm::vec4(0.0f);
        }
        out[(size_t(z) * o.y + y) * o.x + x] = reduce(c);
      }
  return out;
}
}  // namespace

std::vector<glm::vec4> isoMipLevel(const std::vector<glm::vec4>& in, glm::uvec3 s) {
  return mipLevel(
      in, s, [](glm::vec4* c) { return shared::boxMean8(c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]); });
}

std::vector<glm::vec4> anisoMipLevel(const std::vector<glm::vec4>& in, glm::uvec3 s, uint32_t face) {
  return mipLevel(in, s, [face](glm::vec4* c) { return shared::anisoReduce(c, face); });
}

ValueTextures::ValueTextures(const GridBox& box, std::vector<std::string> channels, ValueMips mips)
    : box_(box), channels_(std::move(channels)), mips_(mips) {
  const glm::uvec3 r = box.resolution;
  if (mips != ValueMips::None) {
    const uint32_t m = std::max({r.x, r.y, r.z});
    while ((m >> levels_) > 0) ++levels_;  // down to 1 texel along the longest axis
  }
  GLint max3d = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
  if (int(std::max({r.x, r.y, r.z})) > max3d)
    fail("multi-valued grid ", r.x, "x", r.y, "x", r.z, ": exceeds GL_MAX_3D_TEXTURE_SIZE ", max3d);
  const double cells = double(r.x) * r.y * r.z, chain = levels_ > 1 ? 8.0 / 7.0 : 1.0;
  count_ = makeGridTexture3D(r, 1, GL_R32UI, false);
  occupancy_ = makeGridTexture3D(r, levels_, GL_R8, true);
  bytes_ = size_t(cells * (4 + chain));
  for (auto& ch : channels_) {
    const uint32_t k = valueChannelIndex(ch);
    channel_[k] = makeGridTexture3D(r, levels_, kChannelFormat[k], true);
    bytes_ += size_t(cells * chain * double(texelBytes(kChannelFormat[k])));
    if (mips == ValueMips::Anisotropic && k != shared::VALUE_CHANNEL_GLOSSY)
      for (int f = 0; f < 6; ++f) {
        aniso_[k][f] = makeGridTexture3D(halve(r, 1), std::max(1, levels_ - 1), GL_RGBA16F, true);
        bytes_ += size_t(cells / 8 * chain * 8);
      }
  }
}

ValueTextures::~ValueTextures() = default;

bool ValueTextures::has(const std::string& channel) const {
  return std::find(channels_.begin(), channels_.end(), channel) != channels_.end();
}

glm::uvec3 ValueTextures::levelSize(int level) const { return halve(box_.resolution, level); }

unsigned ValueTextures::textureOf(const std::string& channel) const {
  if (channel == "occupancy") return occupancy_.get();
  if (!has(channel)) fail("value channel '", channel, "' was not built");
  return channel_[valueChannelIndex(channel)].get();
}

void ValueTextures::resolve(const ValueSumBuffers& sums, ShaderLibrary& shaders, Profiler& prof,
                            unsigned occupancyWords, unsigned radianceDirection,
                            const std::optional<CellRange>& cells) {
  {
    auto s = prof.scope("value_resolve");
    ShaderDefines defs;
    for (auto& ch : channels_) {
      std::string up = ch;
      std::transform(up.begin(), up.end(), up.begin(), ::toupper);
      defs["VALUE_" + up] = "1";
    }
    if (occupancyWords) defs["OCCUPANCY_FROM_GRID"] = "1";
    const unsigned prog = shaders.program({"voxelize/value_resolve.comp.glsl"}, defs);
    glUseProgram(prog);
    const glm::uvec3 r = box_.resolution;
    shaders.setUniform(prog, "uResolution", glm::uvec4(r, 0u));
    const CellRange range =
        cells ? CellRange{glm::min(cells->lo, r), glm::min(cells->hi, r)} : CellRange{{}, r};
    shaders.setUniform(prog, "uFirstCell", range.lo);
    shaders.setUniform(prog, "uEndCell", range.hi);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VALUE_COUNTS, sums.counts);
    if (occupancyWords) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_PYRAMID, occupancyWords);
    glBindImageTexture(IMAGE_VALUE_COUNT, count_.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
    glBindImageTexture(IMAGE_VALUE_OCCUPANCY, occupancy_.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R8);
    shaders.setUniform(prog, "uRadianceMax", sums.radianceMax);
    const unsigned images[4] = {IMAGE_VALUE_NORMAL, IMAGE_VALUE_ALBEDO, IMAGE_VALUE_GLOSSY,
                                IMAGE_VALUE_RADIANCE};
    for (auto& ch : channels_) {
      const uint32_t k = valueChannelIndex(ch);
      if (!sums.sums[k]) fail("internal: value channel '", ch, "' has no sums to resolve");
      glBindBufferBase(
          GL_SHADER_STORAGE_BUFFER,
          k == shared::VALUE_CHANNEL_RADIANCE ? BINDING_VALUE_RADIANCE : BINDING_VALUE_NORMAL + k,
          sums.sums[k]);
      glBindImageTexture(images[k], channel_[k].get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, kChannelFormat[k]);
    }
    if (range.count() > 0) dispatch3D(glm::max(range.hi, range.lo) - range.lo);
    resolvedCells_ = range.count();
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                    GL_TEXTURE_UPDATE_BARRIER_BIT);
  }
  if (mips_ == ValueMips::None) return;
  auto s = prof.scope("value_mips");
  // Level l's texels over level 0's changed cells (their parents), or all of it.
  auto levelRange = [&](int l) {
    const glm::uvec3 size = levelSize(l);
    if (!cells) return CellRange{{}, size};
    const uint32_t side = 1u << l;
    return CellRange{glm::min(cells->lo / side, size), glm::min((cells->hi + (side - 1u)) / side, size)};
  };
  auto run = [&](unsigned prog, unsigned input, int inputLevel, unsigned output, int outputLevel,
                 GLenum format, int gridLevel) {
    const CellRange r = levelRange(gridLevel);
    if (r.count() == 0) return;
    glBindTextureUnit(TEXUNIT_PASS_INPUT, input);
    shaders.setUniform(prog, "uInputLevel", inputLevel);
    shaders.setUniform(prog, "uFirstCell", r.lo);
    shaders.setUniform(prog, "uEndCell", r.hi);
    glBindImageTexture(IMAGE_OUTPUT, output, outputLevel, GL_TRUE, 0, GL_WRITE_ONLY, format);
    dispatch3D(r.hi - r.lo);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  };
  auto isoChain = [&](unsigned tex, GLenum format) {
    const unsigned prog = shaders.program({"voxelize/value_mip.comp.glsl"},
                                          {{"ISOTROPIC", "1"}, {"OUTPUT_FORMAT", formatName(format)}});
    glUseProgram(prog);
    shaders.setUniform(prog, "uFromValues", 0);
    for (int l = 1; l < levels_; ++l) run(prog, tex, l - 1, tex, l, format, l);
  };
  isoChain(occupancy_.get(), GL_R8);
  for (auto& ch : channels_)
    isoChain(channel_[valueChannelIndex(ch)].get(), kChannelFormat[valueChannelIndex(ch)]);
  if (mips_ != ValueMips::Anisotropic || levels_ < 2) return;
  const unsigned plain =
      shaders.program({"voxelize/value_mip.comp.glsl"}, {{"ANISOTROPIC", "1"}, {"OUTPUT_FORMAT", "rgba16f"}});
  for (auto& ch : channels_) {
    const uint32_t k = valueChannelIndex(ch);
    if (k == shared::VALUE_CHANNEL_GLOSSY) continue;
    const bool directional = radianceDirection && k == shared::VALUE_CHANNEL_RADIANCE;
    const unsigned prog =
        directional
            ? shaders.program({"voxelize/value_mip.comp.glsl"},
                              {{"ANISOTROPIC", "1"}, {"DIRECTIONAL", "1"}, {"OUTPUT_FORMAT", "rgba16f"}})
            : plain;
    glUseProgram(prog);
    glBindTextureUnit(TEXUNIT_PASS_INPUT2, occupancy_.get());
    if (directional) glBindTextureUnit(TEXUNIT_VALUE_DIRECTION, radianceDirection);
    for (unsigned f = 0; f < 6; ++f) {
      shaders.setUniform(prog, "uFace", f);
      const unsigned face = aniso_[k][f].get();
      shaders.setUniform(prog, "uFromValues", 1);
      run(prog, channel_[k].get(), 0, face, 0, GL_RGBA16F, 1);
      shaders.setUniform(prog, "uFromValues", 0);
      for (int l = 2; l < levels_; ++l) run(prog, face, l - 2, face, l - 1, GL_RGBA16F, l);
    }
  }
}

void ValueTextures::bind() const {
  glBindTextureUnit(TEXUNIT_VALUE_COUNT, count_.get());
  glBindTextureUnit(TEXUNIT_VALUE_OCCUPANCY, occupancy_.get());
  const unsigned units[4] = {TEXUNIT_VALUE_NORMAL, TEXUNIT_VALUE_ALBEDO, TEXUNIT_VALUE_GLOSSY,
                             TEXUNIT_VALUE_RADIANCE};
  for (auto& ch : channels_)
    glBindTextureUnit(units[valueChannelIndex(ch)], channel_[valueChannelIndex(ch)].get());
}

void ValueTextures::bindAniso(const std::string& channel) const {
  const uint32_t k = valueChannelIndex(channel);
  if (mips_ != ValueMips::Anisotropic || !has(channel) || k == shared::VALUE_CHANNEL_GLOSSY)
    fail("value channel '", channel, "' has no anisotropic mip chain (mips ", valueMipsName(mips_), ")");
  for (unsigned f = 0; f < 6; ++f) glBindTextureUnit(TEXUNIT_VALUE_ANISO + f, aniso_[k][f].get());
}

namespace {
std::vector<glm::vec4> readTexture(unsigned tex, int level, glm::uvec3 s, bool red) {
  const size_t n = size_t(s.x) * s.y * s.z;
  std::vector<glm::vec4> out(n, glm::vec4(0.0f));
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  if (red) {
    std::vector<float> r(n);
    glGetTextureImage(tex, level, GL_RED, GL_FLOAT, GLsizei(n * sizeof(float)), r.data());
    for (size_t i = 0; i < n; ++i) out[i].x = r[i];
  } else {
    glGetTextureImage(tex, level, GL_RGBA, GL_FLOAT, GLsizei(n * sizeof(glm::vec4)), out.data());
  }
  return out;
}
}  // namespace

std::vector<glm::vec4> ValueTextures::read(const std::string& channel, int level) const {
  if (level < 0 || level >= levels_) fail("value texture level ", level, " of ", levels_);
  return readTexture(textureOf(channel), level, levelSize(level), channel == "occupancy");
}

std::vector<glm::vec4> ValueTextures::readAniso(const std::string& channel, int face, int gridLevel) const {
  const uint32_t k = valueChannelIndex(channel);
  if (!aniso_[k][0] || face < 0 || face > 5 || gridLevel < 1 || gridLevel >= levels_)
    fail("no anisotropic level ", gridLevel, " face ", face, " of '", channel, "'");
  return readTexture(aniso_[k][face].get(), gridLevel - 1, levelSize(gridLevel), false);
}

std::vector<uint32_t> ValueTextures::readCounts() const {
  const glm::uvec3 s = box_.resolution;
  std::vector<uint32_t> out(size_t(s.x) * s.y * s.z);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  glGetTextureImage(count_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(out.size() * 4), out.data());
  return out;
}

nlohmann::json ValueTextures::describe() const {
  nlohmann::json formats = {{"count", "r32ui"}, {"occupancy", "r8"}};
  for (auto& ch : channels_) formats[ch] = formatName(kChannelFormat[valueChannelIndex(ch)]);
  return {{"channels", channels_}, {"formats", formats}, {"mips", valueMipsName(mips_)},
          {"levels", levels_},     {"bytes", bytes_},    {"resolved_cells", resolvedCells_}};
}

}  // namespace vgi
