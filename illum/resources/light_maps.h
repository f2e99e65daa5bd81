// Light maps for every delta light of a scene (shaders/shared/light_maps.glsl):
// distance maps for shadow tests and, when reflective, reflective shadow maps
// (position, normal, reflected direct radiance; VGI §5.1) — one 2D array
// texture per channel, a face table as an SSBO. Resource kind "light_maps"
// (named "rsm" in the stats when reflective): the maps of the lights
// SceneResources places, drawn again when they change.
#pragma once
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "illum/framework/resources.h"
#include "shaders/shared/light_maps.glsl"

namespace vgi {

class GpuScene;
class Profiler;
class ShaderLibrary;

// The faces of each light, in scene order (first face, count) and their
// matrices; pure geometry, so it is testable without GL.
struct LightFaceLayout {
  std::vector<shared::LightFace> faces;
  std::vector<glm::ivec4> ranges;  // per light: x first face, y count
  // Per face: false where no direction of the face's frustum lies in a spot
  // light's cone (e.g. the up face of a downward 90° spot): it is cleared
  // (unoccluded, no reflected light — the light sends nothing there), not drawn.
  std::vector<bool> drawn;
};
// Spot lights with a cone half-angle up to this get one perspective face.
constexpr float kSingleFaceSpotDeg = 60.0f;
LightFaceLayout layoutLightFaces(const std::vector<Light>& lights, const Bounds& bounds, int resolution);

class LightMaps {
 public:
  // Allocates the maps of `lights` over the scene `gpu` holds; render() draws them.
  LightMaps(const std::vector<Light>& lights, const GpuScene& gpu, int resolution, bool reflective);
  ~LightMaps();
  LightMaps(const LightMaps&) = delete;
  LightMaps& operator=(const LightMaps&) = delete;

  // Renders the maps (timed as "shadow_maps" or "rsm") for the scene as `gpu`
  // holds it now (the frames of an animation).
  void render(const GpuScene& gpu, ShaderLibrary& shaders, Profiler& profiler);
  // The same for the faces that can have changed since they were drawn: a face whose layout (light,
  // frustum) differs, or whose frustum meets `moved` (what moved since: the dynamic meshes' bounds
  // before and after; the rest of the scene stands) — a face whose layout stayed only within the
  // rectangle `moved` projects to (scissored: the texels outside it see the same static scene).
  // Returns how many faces it cleared (and, inside a spot's cone, drew) again: 0 = the maps are as
  // they were.
  int renderChanged(const GpuScene& gpu, ShaderLibrary& shaders, Profiler& profiler, const Bounds& moved);
  // New positions and directions for lights of the same types as before (a
  // sample's emitter point, SceneResources::beginSample): the face layout is
  // made again; render() draws it.
  void setLights(const std::vector<Light>& lights, const GpuScene& gpu);

  // Binds the face table and the map textures (TEXUNIT_LIGHT_*).
  void bind() const;
  int faceCount() const { return int(layout_.faces.size()); }
  // How many times render() drew the maps: what a pass derived from them (vpl's flux tree) keys on.
  uint64_t renders() const { return renders_; }
  bool reflective() const { return reflective_; }
  nlohmann::json describe() const;  // for the stats
  int resolution() const { return resolution_; }

  // The channels, in texture order: "distance", and with reflective maps
  // "position", "normal", "radiance" (the viewer's light-map views).
  std::vector<std::string> channels() const { return channelNames(reflective_); }
  static std::vector<std::string> channelNames(bool reflective);
  // Face `face` of channel `channel` (channels()) as last rendered, read back
  // (rows top-down; distance in all three components; texels no surface
  // covers: distance 1e30, the others 0). Throws naming a face or channel
  // the maps do not have.
  Image readFace(int face, const std::string& channel) const;

 private:
  void uploadLayout();
  // Draws the faces marked, each within its rectangle of `rects` (x, y, width, height in texels; none
  // or a zero width: the whole face).
  int draw(const GpuScene& gpu, ShaderLibrary& shaders, Profiler& profiler, const std::vector<bool>& faces,
           const std::vector<glm::ivec4>& rects = {});
  LightFaceLayout layout_;
  LightFaceLayout drawnLayout_;  // the layout each face was last drawn with
  int redrawn_ = 0;              // drawn faces the last render drew again (the stats' faces_redrawn)
  int scissored_ = 0;            // … of them within a rectangle only (faces_scissored)
  int resolution_;
  bool reflective_;
  double bytes_ = 0;  // the textures and the depth buffer, as allocated
  uint64_t renders_ = 0;
  unsigned faceBuffer_ = 0, rangeBuffer_ = 0, fbo_ = 0, depth_ = 0;
  unsigned textures_[4] = {0, 0, 0, 0};  // distance, position, normal, radiance
};

struct LightMapNeed {
  static constexpr const char* kKind = "light_maps";
  static const ResourceKind& row();  // its row of the kinds table (lightMapsKind())
  int resolution = 1024;
  bool reflective = false;  // reflective shadow maps (position, normal, flux) for VGI §5.1
  nlohmann::json key() const { return {{"resolution", resolution}, {"reflective", reflective}}; }
};

ResourceKind lightMapsKind();

class Frame;
// A compute pass's input (illum/framework/compute_pass.h): the light maps at their units.
void lightMapsInput(Frame& f, unsigned program);

}  // namespace vgi
