#include <algorithm>
#include <cstdio>

#include "apps/viewer_impl.h"
#include "core/json_text.h"
#include "core/output_files.h"
#include "illum/framework/resources.h"
#include "illum/resources/light_maps.h"
#include "illum/run/render_outputs.h"

namespace vgi::app {

void Viewer::show(const std::string& channel) {
  attempt("show " + channel, [&] {
    if (isLightMapView(channel)) {
      const std::vector<std::string> views = lightMapViews();
      if (std::find(views.begin(), views.end(), channel) == views.end()) {
        std::string list;
        for (auto& v : views) list += (list.empty() ? "" : ", ") + v;
        fail("'", job_->info().name, "' renders ",
             views.empty() ? "no light maps" : "the light maps " + list);
      }
      channel_ = channel;  // the method's light maps as rendered for the last sample: no restart
      return;
    }
    std::vector<std::string> aovs;
    if (channel != "image") aovs.push_back(channel);
    job_->setMethod(job_->info().name, job_->options().set, aovs);
    session_.reset();  // it refers to the method and resources the job replaced
    channel_ = channel;
    dirty_ = true;
  });
}

std::vector<std::string> Viewer::lightMapViews() const {
  std::vector<std::string> views;
  const LightMapNeed* need = job_->resources().needs().find<LightMapNeed>();
  if (!need) return views;
  for (auto& c : LightMaps::channelNames(need->reflective))
    views.push_back((need->reflective ? "rsm." : "shadow_map.") + c);
  return views;
}

int Viewer::lightFaces() const {
  const LightMaps* maps = job_->resources().tryGet<LightMaps>();
  return maps ? maps->faceCount() : -1;
}

void Viewer::setLightFace(long face) {
  attempt("light face " + std::to_string(face), [&] {
    const int faces = lightFaces();
    if (face < 0 || (faces >= 0 && face >= faces))
      fail("face ", face, " out of range: the lights' maps have ", faces, " faces (0 … ", faces - 1, ")");
    lightFace_ = int(face);  // (checked again when the maps are there)
  });
}

// The shown light map, for the eye: radiance as stored; normals as n/2 + 1/2,
// positions over the scene's bounds, distances over the scene diagonal; texels
// no surface covers black. Reduced by a whole factor to fit the image area.
Image Viewer::lightMapImage() const {
  const LightMaps& maps = job_->resources().get<LightMaps>();
  const std::string ch = channel_.substr(channel_.find('.') + 1);
  const int face = lightFace_;
  const Image raw = maps.readFace(face, ch), dist = ch == "distance" ? raw : maps.readFace(face, "distance");
  const Bounds b = job_->scene().bounds(time_);
  const glm::vec3 lo = b.lo, extent = glm::max(b.hi - b.lo, glm::vec3(1e-30f));
  const float diag = sceneSize();
  const int k =
      std::max(1, (raw.width + std::min(req_.width, req_.height) - 1) / std::min(req_.width, req_.height));
  Image out(raw.width / k, raw.height / k);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      glm::vec3 sum(0.0f);
      for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
          const int sx = x * k + i, sy = y * k + j;
          const glm::vec3 v = raw.at(sx, sy);
          if (dist.at(sx, sy).x >= 1e29f) continue;  // nothing there
          if (ch == "distance")
            sum += glm::vec3(v.x / diag);
          else if (ch == "normal")
            sum += 0.5f * v + 0.5f;
          else if (ch == "position")
            sum += (v - lo) / extent;
          else
            sum += v;
        }
      out.at(x, y) = sum / float(k * k);
    }
  return out;
}

void Viewer::screenshot(const std::string& path) {
  attempt("screenshot " + path, [&] {
    if (!session_ || session_->samples() == 0) fail("nothing rendered yet");
    checkOutputPath(path);
    job_->checkGl();
    prof_->resolve(true);
    RenderOutput out;
    out.result = session_->sofar();
    job_->checkFiniteResult(out.result);
    out.stats = job_->describe();
    out.stats.update(renderStats(out.result, *prof_));
    out.stats["spp"] = session_->samples();
    out.stats["time"] = time_;
    if (showingLightMap()) out.result.aovs[channel_] = lightMapImage();  // what is shown, beside the image
    out.stats["viewer"] = {{"shown", channel_},
                           {"exposure", exposure_},
                           {"panel_parameters", panelKeys_},
                           {"gl_errors", gl_->errorCount()},
                           {"errors_reported", failures_},
                           {"resources_kept", job_->resources().adopted()},
                           // The image blends the frames before (the camera moved less than 1/alpha
                           // samples ago): `command` renders the samples alone.
                           {"filtered_over_time", session_->filtered()}};
    if (showingLightMap()) out.stats["viewer"]["light_face"] = lightFace_;
    // The job (and the `vgi render` command) that renders this image again.
    RenderOptions shot = job_->options();
    shot.method = job_->info().name;
    shot.methodGiven = true;
    shot.width = req_.width;
    shot.height = req_.height;
    shot.spp = session_->samples();
    shot.seed = req_.seed;
    shot.time = time_;
    shot.frames = 1;
    shot.progress = true;
    shot.camera = job_->scene().camera;
    shot.lightPositions.clear();
    for (int i : movedLights_) shot.lightPositions.emplace_back(i, job_->scene().lights[size_t(i)].position);
    out.stats["job"] = renderJobJson(shot);
    out.stats["command"] = renderCommandLine(shot);
    for (auto& f : writeRenderOutputs(out, path, exposure_)) std::fprintf(stderr, "wrote %s\n", f.c_str());
    ++shotCount_;
  });
}

}  // namespace vgi::app
