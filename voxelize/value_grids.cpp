#include "voxelize/value_grids.h"

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image.h"
#include "shaders/shared/value_grid.glsl"

namespace vgi {

const std::vector<std::string>& valueChannelNames() {
  static const std::vector<std::string> names = {"normal", "albedo", "glossy", "radiance"};
  return names;
}

std::vector<std::string> parseValueChannels(const std::string& list) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= list.size()) {
    size_t comma = list.find(',', start);
    std::string name = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    bool known = false;
    for (auto& n : valueChannelNames()) known |= n == name;
    if (!known)
      fail("--kind: unknown grid '", name, "' (binary, normal, albedo, glossy, radiance; comma-separated)");
    bool dup = false;
    for (auto& o : out) dup |= o == name;
    if (!dup) out.push_back(name);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::vector<glm::vec4> decodeMeans(const std::vector<uint32_t>& sums, const std::vector<uint32_t>& counts,
                                   const std::string& channel, float radianceMax) {
  std::vector<glm::vec4> means(counts.size(), glm::vec4(0.0f));
  const uint32_t ch = valueChannelIndex(channel);
  for (size_t i = 0; i < counts.size(); ++i) {
    if (counts[i] == 0) continue;
    const glm::uvec4 s(sums[4 * i], sums[4 * i + 1], sums[4 * i + 2], sums[4 * i + 3]);
    if (ch == shared::VALUE_CHANNEL_RADIANCE) {
      means[i] = shared::decodeRadianceMean(s, counts[i], radianceMax);
      continue;
    }
    means[i] = shared::decodeValueMean(s, counts[i], ch);
    if (ch == shared::VALUE_CHANNEL_GLOSSY) means[i].w = shared::decodeExponent(means[i].w);
  }
  return means;
}

uint32_t valueChannelIndex(const std::string& channel) {
  for (size_t k = 0; k < valueChannelNames().size(); ++k)
    if (valueChannelNames()[k] == channel) return uint32_t(k);
  fail("unknown value channel '", channel, "'");
}

const std::vector<glm::vec4>& ValueGrids::channel(const std::string& name) const {
  for (size_t i = 0; i < channels.size(); ++i)
    if (channels[i] == name) return means[i];
  std::string built;
  for (auto& ch : channels) built += (built.empty() ? "" : ", ") + ch;
  fail("grid '", name, "' was not built (built: ", built.empty() ? "none" : built, ")");
}

nlohmann::json ValueGrids::summary() const {
  nlohmann::json j = nlohmann::json::object();
  size_t cells = 0;
  for (uint32_t c : counts) cells += c > 0;
  for (size_t k = 0; k < channels.size(); ++k) {
    glm::dvec4 sum(0.0);
    for (size_t i = 0; i < counts.size(); ++i)
      if (counts[i]) sum += glm::dvec4(means[k][i]);
    glm::dvec4 m = cells ? sum / double(cells) : glm::dvec4(0.0);
    j[channels[k]] = {{"cells", cells}, {"mean", {m.x, m.y, m.z, m.w}}};
  }
  return j;
}

void writeValuePicture(const ValueGrids& g, const std::string& channel, const std::string& path) {
  const auto& v = g.channel(channel);
  const glm::uvec3 r = g.box.resolution;
  Image img(int(r.x), int(r.y));
  for (uint32_t y = 0; y < r.y; ++y)
    for (uint32_t x = 0; x < r.x; ++x)
      for (uint32_t z = 0; z < r.z; ++z) {
        size_t i = g.cellIndex(x, y, z);
        if (!g.counts[i]) continue;
        glm::vec3 c(v[i]);
        if (channel == "normal") c = c * 0.5f + 0.5f;
        img.at(int(x), int(r.y - 1 - y)) = c;
        break;
      }
  writeImage(img, path);
}

}  // namespace vgi
