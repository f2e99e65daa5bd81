#include "illum/run/render_outputs.h"

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/image.h"
#include "core/json_text.h"
#include "core/output_files.h"

namespace fs = std::filesystem;

namespace vgi {

void checkOutputPath(const std::string& path) {
  fs::path p(path);
  std::string ext = p.extension().string();
  if (ext != ".exr" && ext != ".png")
    fail("-o '", path, "': the output must end in .exr or .png (both are written, plus a .json sidecar)");
  checkOutputFile(path, "-o");
}

namespace {

// <stem>.exr, <stem>.png, then <stem>.<aov>.exr/.png per extra output.
std::vector<std::string> writeImages(const RenderResult& r, const std::string& stem, float exposure) {
  std::vector<std::string> files = {stem + ".exr", stem + ".png"};
  writeImage(r.image, files[0]);
  writeImage(r.image, files[1], exposure);
  for (auto& [name, image] : r.aovs) {
    for (const char* ext : {".exr", ".png"}) {
      files.push_back(stem + "." + name + ext);
      writeImage(image, files.back(), ext[1] == 'p' ? exposure : 1.0f);
    }
  }
  return files;
}

void writeStats(nlohmann::json s, const std::string& json, const std::vector<std::string>& files,
                float exposure) {
  s["outputs"] = files;
  s["exposure_png"] = exposure;
  writeJsonFile(s, json);
}

std::string stemOf(const std::string& path) {
  checkOutputPath(path);
  return fs::path(path).replace_extension("").string();
}

}  // namespace

std::string checkpointStem(const std::string& stem, int spp) {
  char number[24];
  std::snprintf(number, sizeof number, ".spp%05d", spp);
  return stem + number;
}

std::string frameStem(const std::string& stem, int frame) {
  char number[16];
  std::snprintf(number, sizeof number, "_%04d", frame);
  return stem + number;
}

std::vector<std::string> renderOutputNames(const std::string& path, const RenderOptions& o) {
  const std::string stem = stemOf(path);
  std::vector<std::string> channels = {""};
  channels.insert(channels.end(), o.aovs.begin(), o.aovs.end());
  auto images = [&](const std::string& s, std::vector<std::string>& out) {
    for (const std::string& a : channels)
      for (const char* ext : {".exr", ".png"}) out.push_back(s + (a.empty() ? "" : "." + a) + ext);
  };
  std::vector<std::string> names = {stem + ".json"};
  if (o.frames > 1) {
    for (int f = 0; f < o.frames; ++f) images(frameStem(stem, f), names);
    return names;
  }
  images(stem, names);
  for (int k : o.checkpoints) {
    images(checkpointStem(stem, k), names);
    names.push_back(checkpointStem(stem, k) + ".json");
  }
  return names;
}

namespace {
// A still's images and its stats JSON under `stem` (the JSON listed third, after the EXR and PNG).
std::vector<std::string> writeStill(const RenderOutput& out, const std::string& stem, float exposure) {
  std::vector<std::string> files = writeImages(out.result, stem, exposure);
  files.insert(files.begin() + 2, stem + ".json");
  writeStats(out.stats, stem + ".json", files, exposure);
  return files;
}
}  // namespace

std::vector<std::string> writeRenderOutputs(const RenderOutput& out, const std::string& path,
                                            float exposure) {
  return writeStill(out, stemOf(path), exposure);
}

std::vector<std::string> writeCheckpointOutputs(const RenderOutput& out, const std::string& path, int spp,
                                                float exposure) {
  return writeStill(out, checkpointStem(stemOf(path), spp), exposure);
}

std::vector<std::string> writeFrameImages(const RenderOutput& out, const std::string& path, int frame,
                                          float exposure) {
  return writeImages(out.result, frameStem(stemOf(path), frame), exposure);
}

std::string writeAnimationStats(const RenderOutput& out, const std::string& path,
                                const std::vector<std::string>& files, float exposure) {
  const std::string json = stemOf(path) + ".json";
  writeStats(out.stats, json, files, exposure);
  return json;
}

}  // namespace vgi
