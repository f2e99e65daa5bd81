#include "voxelize/value_sums_cache.h"

#include <glad/gl.h>

#include <cstring>
#include <glm/glm.hpp>

#include "voxelize/value_grids.h"

namespace vgi {

namespace {

struct PackHeader {
  uint64_t cells;
  uint64_t occupied;
  uint32_t channelMask;
  uint32_t pad;
};

template <typename T>
void append(std::vector<uint8_t>& out, const T* data, size_t n) {
  const size_t at = out.size();
  out.resize(at + n * sizeof(T));
  std::memcpy(out.data() + at, data, n * sizeof(T));
}

}  // namespace

uint32_t valueChannelMask(const std::vector<std::string>& channels) {
  uint32_t mask = 0;
  for (const std::string& c : channels) mask |= 1u << unsigned(valueChannelIndex(c));
  return mask;
}

std::vector<uint8_t> packValueSums(const ValueSumBuffers& sums, size_t cells) {
  std::vector<uint32_t> counts(cells);
  glGetNamedBufferSubData(sums.counts, 0, GLsizeiptr(cells * 4), counts.data());
  std::vector<uint32_t> occupied;
  for (size_t i = 0; i < cells; ++i)
    if (counts[i]) occupied.push_back(uint32_t(i));
  PackHeader h{cells, occupied.size(), 0, 0};
  for (unsigned k = 0; k < 3; ++k)
    if (sums.sums[k]) h.channelMask |= 1u << k;
  std::vector<uint8_t> out;
  append(out, &h, 1);
  append(out, occupied.data(), occupied.size());
  std::vector<uint32_t> packedCounts(occupied.size());
  for (size_t j = 0; j < occupied.size(); ++j) packedCounts[j] = counts[occupied[j]];
  append(out, packedCounts.data(), packedCounts.size());
  std::vector<glm::uvec4> dense, packed(occupied.size());
  for (unsigned k = 0; k < 3; ++k) {
    if (!sums.sums[k]) continue;
    dense.resize(cells);
    glGetNamedBufferSubData(sums.sums[k], 0, GLsizeiptr(cells * 16), dense.data());
    for (size_t j = 0; j < occupied.size(); ++j) packed[j] = dense[occupied[j]];
    append(out, packed.data(), packed.size());
  }
  return out;
}

std::unique_ptr<CachedValueSums> CachedValueSums::unpack(const uint8_t* payload, size_t bytes, size_t cells,
                                                         uint32_t channelMask) {
  PackHeader h;
  if (bytes < sizeof h) return nullptr;
  std::memcpy(&h, payload, sizeof h);
  const size_t channels = size_t(__builtin_popcount(channelMask));
  if (h.cells != cells || h.channelMask != channelMask || h.occupied > cells ||
      bytes != sizeof h + h.occupied * (4 + 4 + 16 * channels))
    return nullptr;
  const size_t n = size_t(h.occupied);
  std::vector<uint32_t> index(n), packedCounts(n);
  const uint8_t* p = payload + sizeof h;
  std::memcpy(index.data(), p, n * 4);
  p += n * 4;
  std::memcpy(packedCounts.data(), p, n * 4);
  p += n * 4;
  for (uint32_t i : index)
    if (i >= cells) return nullptr;
  auto r = std::unique_ptr<CachedValueSums>(new CachedValueSums());
  r->cells_ = cells;
  std::vector<uint32_t> counts(cells, 0u);
  for (size_t j = 0; j < n; ++j) counts[index[j]] = packedCounts[j];
  r->counts_ = makeBuffer(cells * 4);
  glNamedBufferSubData(r->counts_.get(), 0, GLsizeiptr(cells * 4), counts.data());
  std::vector<glm::uvec4> dense, packed(n);
  for (unsigned k = 0; k < 3; ++k) {
    if (!(channelMask & (1u << k))) continue;
    std::memcpy(static_cast<void*>(packed.data()), p, n * 16);
    p += n * 16;
    dense.assign(cells, glm::uvec4(0u));
    for (size_t j = 0; j < n; ++j) dense[index[j]] = packed[j];
    r->sums_[k] = makeBuffer(cells * 16);
    glNamedBufferSubData(r->sums_[k].get(), 0, GLsizeiptr(cells * 16), dense.data());
  }
  return r;
}

ValueSumBuffers CachedValueSums::buffers() const {
  ValueSumBuffers b;
  b.counts = counts_.get();
  for (unsigned k = 0; k < 3; ++k) b.sums[k] = sums_[k].get();
  return b;
}

double CachedValueSums::gpuBytes() const {
  double bytes = double(cells_) * 4.0;
  for (const GlBuffer& s : sums_)
    if (s) bytes += double(cells_) * 16.0;
  return bytes;
}

}  // namespace vgi
