// The scene: triangle meshes (static or rigidly animated), materials, lights,
// environment and camera. The GL modules and the Embree reference read the
// same structures, so both render the same scene with the same definitions.
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <string>
#include <vector>

namespace vgi {

// Linear RGB float texture (sRGB 8-bit files are linearised on load).
struct Texture {
  std::string path;
  int width = 0, height = 0;
  std::vector<glm::vec3> texels;  // row 0 = top of the image file
  size_t nonFiniteTexels = 0;     // NaN or Inf in the file (read as 0)
  bool srgb = false;              // the file's 8/16-bit values were sRGB-decoded into texels
  // Bilinear; u always wraps, v wraps (albedo textures) or clamps (lat-long maps,
  // whose top and bottom rows are the poles, not neighbours).
  glm::vec3 lookup(glm::vec2 uv, bool wrapV = true) const;
};

// Lambert (albedo, optional texture) + normalised Phong lobe (ks, exponent) + emission.
struct Material {
  std::string name;
  glm::vec3 albedo{0.8f};
  int albedoTexture = -1;  // index into Scene::textures
  glm::vec3 ks{0.0f};
  float exponent = 1.0f;
  glm::vec3 emission{0.0f};
};

// Where `time` lies between two keys at times a < b, in [0, 1] (0 where b <= a). Computed in double:
// in float, (time − a) / (b − a) overflows to inf/inf for keys near ±3.4e38, which the loader accepts,
// and a NaN fraction placed a light nowhere (a black image with exit 0).
float keyFraction(float time, float a, float b);

struct Keyframe {
  float time = 0;
  glm::vec3 translation{0.0f};
  glm::quat rotation{1, 0, 0, 0};
  glm::vec3 scale{1.0f};
};

struct Mesh {
  std::string name;
  std::string source;  // file it came from, or "builtin:..."
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // per vertex; empty = use face normals
  std::vector<glm::vec2> uvs;      // per vertex; may be empty
  std::vector<glm::uvec3> triangles;
  int material = 0;
  glm::mat4 transform{1.0f};  // object to world (static part)
  bool dynamic = false;
  std::vector<Keyframe> keyframes;  // dynamic only; applied after `transform`
  glm::mat4 objectToWorld(float time) const;
};

enum class LightType { Point, Spot, Directional };
const char* lightTypeName(LightType type);  // "point", "spot", "directional" (the scene files' names)

// Delta lights. Point/spot: intensity in W/sr (per RGB channel); directional:
// irradiance on a surface facing the light. Spot: I(θ) = I0 cos(θ)^falloff for
// θ ≤ cone half-angle, θ measured from `direction`.
// A light's path: its position (point, spot) and direction (spot, directional) at `time`.
struct LightKey {
  float time = 0;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0, -1, 0};
};

struct Light {
  LightType type = LightType::Point;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0, -1, 0};  // spot axis / direction the directional light travels
  glm::vec3 intensity{1.0f};
  float coneHalfAngleDeg = 90.0f;
  float falloff = 1.0f;
  std::vector<LightKey> keyframes;  // empty: fixed; else times increasing (Scene::placeLightsAt)
};

// Radiance arriving from directions that leave the scene: constant colour, or
// a lat-long map (scaled) when mapTexture >= 0.
struct Environment {
  glm::vec3 color{0.0f};
  int mapTexture = -1;
  float scale = 1.0f;
  bool isBlack() const { return mapTexture < 0 && color == glm::vec3(0.0f); }
};

struct Camera {
  glm::vec3 position{0, 0, 5}, target{0.0f}, up{0, 1, 0};
  float fovYDeg = 45.0f;
  // > 0: a cut-away view — what lies closer than this distance along the view axis is not seen
  // (the near plane of every method's primary visibility); light transport still sees it.
  float clipNear = 0.0f;
};

// A camera path: the camera at `time`, linearly interpolated between keys (clamped at the ends).
struct CameraKey {
  float time = 0;
  Camera camera;
};

struct Bounds {
  glm::vec3 lo{1e30f}, hi{-1e30f};
  void extend(glm::vec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return lo.x > hi.x; }
  float diagonal() const { return empty() ? 0.0f : glm::length(hi - lo); }
};

// Counted, non-fatal problems found while loading (shown by `vgi info` and in stats).
struct LoadReport {
  long degenerateTrianglesDropped = 0;
  std::vector<std::string> warnings;
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Light> lights;
  Environment environment;
  Camera camera;
  std::vector<CameraKey> cameraPath;  // empty: `camera` at every time; else times increasing
  // Emissive surfaces emit on their front side only (core/emitters.h), or on both.
  bool twoSidedEmission = false;
  std::map<std::string, std::map<std::string, std::string>> presets;
  LoadReport report;

  size_t triangleCount() const;
  Bounds bounds(float time = 0) const;
  // The dynamic meshes' bounds at `time` (empty without dynamic meshes).
  Bounds dynamicBounds(float time) const;
  bool hasDynamicMeshes() const;
  // The dynamic (or the static) meshes alone, as geometry for a binary voxelizer: the materials
  // without their textures, no textures, no environment map; lights, camera and name as here.
  Scene meshGeometry(bool dynamic) const;
  // The camera at `time`: `camera`, or the path's interpolation (position, target, up, field of view).
  Camera cameraAt(float time) const;
  // Whether a light has keyframes; placeLightsAt moves each such light to its path at `time`: the
  // position and the direction linearly interpolated between keys (the direction renormalized; where
  // it would vanish, the nearer key's), clamped at the ends.
  bool hasLightPaths() const;
  void placeLightsAt(float time);
  glm::vec3 environmentRadiance(glm::vec3 dir) const;
};

// A flat, world-space triangle soup at one instant: what renderers consume.
struct FlatScene {
  std::vector<glm::vec3> positions;  // 3 per triangle
  std::vector<glm::vec3> normals;    // 3 per triangle (shading normals)
  std::vector<glm::vec2> uvs;        // 3 per triangle
  std::vector<int> material;         // 1 per triangle
  std::vector<int> meshOfTriangle;   // 1 per triangle
  size_t triangleCount() const { return material.size(); }
};
FlatScene flatten(const Scene& scene, float time = 0);
// Appends mesh `mesh` at `time` (flatten() is this over every mesh, in order).
void flattenMesh(const Scene& scene, int mesh, float time, FlatScene& out);

}  // namespace vgi
