#include <fstream>

#include "core/emitters.h"
#include "core/scene_loader.h"
#include "test_util.h"

namespace vgi {

TEST(Scene, BuiltinCornellMatchesThePublishedBox) {
  Scene s = loadScene("builtin:cornell");
  EXPECT_EQ(s.triangleCount(), 30u);  // 5 walls + 2 blocks of 5 quads, light quad omitted
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Spot);
  EXPECT_FLOAT_EQ(s.lights[0].coneHalfAngleDeg, 90.0f);
  EXPECT_FLOAT_EQ(s.lights[0].falloff, 1.0f);
  EXPECT_NEAR(s.camera.fovYDeg, 39.3077f, 1e-3f);
  Bounds b = s.bounds();
  EXPECT_NEAR(b.hi.x, 0.556f, 1e-6f);
  EXPECT_NEAR(b.hi.y, 0.5488f, 1e-6f);
  EXPECT_NEAR(b.hi.z, 0.5592f, 1e-6f);
  EXPECT_EQ(s.report.degenerateTrianglesDropped, 0);
  EXPECT_TRUE(s.report.warnings.empty());
  // The light hangs inside the box, below the ceiling.
  EXPECT_LT(s.lights[0].position.y, b.hi.y);
}

TEST(Scene, SharedCornellObjLoads) {
  std::string p = test::sharedScene("cornell-box/CornellBox-Original.obj");
  if (p.empty()) GTEST_SKIP() << "../shared/scenes not present";
  Scene s = loadScene(p);
  EXPECT_EQ(s.triangleCount(), 36u);
  bool emissive = false;
  for (auto& m : s.materials) emissive |= m.emission.x > 0;
  EXPECT_TRUE(emissive);  // Ke 17 12 4 of the light quad
}

TEST(Scene, SharedPlyAndTexturedObjLoad) {
  std::string bunny = test::sharedScene("stanford-bunny/bun_zipper.ply");
  std::string sib = test::sharedScene("sibenik/sibenik.obj");
  if (bunny.empty() || sib.empty()) GTEST_SKIP() << "../shared/scenes not present";
  Scene b = loadScene(bunny);
  EXPECT_EQ(b.triangleCount() + size_t(b.report.degenerateTrianglesDropped), 69451u);
  EXPECT_FALSE(b.lights.empty());  // a default light was added, with a warning
  Scene s = loadScene(sib);
  EXPECT_GT(s.triangleCount(), 70000u);
  int textured = 0;
  for (auto& m : s.materials) textured += m.albedoTexture >= 0;
  EXPECT_GT(textured, 0);
}

TEST(Scene, GltfLoadsWithNodeTransformAndBaseColour) {
  Scene s = loadScene(test::dataPath("triangle.gltf"));
  ASSERT_EQ(s.triangleCount(), 1u);
  EXPECT_NEAR(s.bounds().lo.z, 2.0f, 1e-6f);  // node translation applied
  EXPECT_NEAR(s.materials[size_t(s.meshes[0].material)].albedo.x, 0.8f, 1e-6f);
  // Its one material and no other: assimp's default stood beside it, unused (issue 64).
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "red");
}

// A bare OBJ (no MTL): its faces use the default material, which is kept.
TEST(Scene, AModelWithoutMaterialsKeepsTheDefault) {
  const std::string path = testing::TempDir() + "/bare.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const Scene s = loadScene(path);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[size_t(s.meshes[0].material)].name, "bare_default");
}

TEST(Scene, JsonSceneWithDynamicMeshAndPresets) {
  std::string path = testing::TempDir() + "/dyn.json";
  std::ofstream(path) << R"({
    "meshes": [ {"path": "builtin:cornell"},
                {"path": ")"
                      << test::dataPath("triangle.gltf") << R"(", "material": "gold", "dynamic": true,
                 "keyframes": [ {"time": 0, "translate": [0, 0, 0]},
                                {"time": 1, "translate": [1, 0, 0], "rotate": [90, 0, 1, 0]} ] } ],
    "materials": { "gold": {"albedo": [0.5, 0.4, 0.1], "ks": [0.3, 0.3, 0.3], "exponent": 50},
                   "red": {"albedo": 0.2} },
    "environment": {"color": [0.1, 0.2, 0.3]},
    "presets": { "fast": {"rays": 4, "env": "off"} } })";
  Scene s = loadScene(path);
  EXPECT_EQ(s.lights.size(), 1u);  // the built-in's spot light is kept
  const Mesh& tri = s.meshes.back();
  EXPECT_TRUE(tri.dynamic);
  EXPECT_EQ(s.materials[size_t(tri.material)].name, "gold");
  EXPECT_FLOAT_EQ(s.materials[size_t(tri.material)].exponent, 50.0f);
  glm::vec3 p0 = glm::vec3(tri.objectToWorld(0.0f) * glm::vec4(tri.positions[0], 1));
  glm::vec3 p1 = glm::vec3(tri.objectToWorld(1.0f) * glm::vec4(tri.positions[0], 1));
  glm::vec3 pHalf = glm::vec3(tri.objectToWorld(0.5f) * glm::vec4(tri.positions[0], 1));
  EXPECT_NEAR(p0.z, 2.0f, 1e-5f);
  EXPECT_NEAR(p1.x, 1.0f + 2.0f, 1e-5f);  // rotated 90° about y: (0,0,2) → (2,0,0), then +1 x
  EXPECT_GT(pHalf.x, 0.5f);
  EXPECT_EQ(s.presets["fast"]["rays"], "4");
  EXPECT_EQ(s.presets["fast"]["env"], "off");
  // "red" overrides the built-in's red wall.
  for (auto& m : s.materials)
    if (m.name == "red") {
      EXPECT_FLOAT_EQ(m.albedo.y, 0.2f);
    }
  EXPECT_NEAR(s.environmentRadiance({0, 1, 0}).z, 0.3f, 1e-6f);
}

TEST(Scene, FlattenGivesFiniteNormals) {
  Scene s = loadScene("builtin:cornell");
  FlatScene f = flatten(s);
  ASSERT_EQ(f.triangleCount(), 30u);
  for (auto& n : f.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

TEST(Scene, ProjectSceneFilesLoadWhenTheirDataIsPresent) {
  for (const char* name : {"cornell-original.json", "sibenik.json", "bunny.json", "dragon.json",
                           "cornell-bunny.json", "sibenik-bunny.json", "sibenik-bunny-still.json"}) {
    std::string p = std::string(VGI_TEST_DATA) + "/../../scenes/" + name;
    std::ifstream in(p);
    ASSERT_TRUE(in.good()) << p;
    std::string text((std::istreambuf_iterator<char>(in)), {});
    if (text.find("../shared/scenes") != std::string::npos && test::sharedScene("").empty()) continue;
    Scene s = loadScene(p);
    EXPECT_GT(s.triangleCount(), 0u) << name;
    EXPECT_TRUE(!s.lights.empty() || !Emitters::ofScene(s, 0.0f).empty()) << name;  // lit by something
  }
}

namespace {
// A scene JSON over the built-in Cornell box with `key` (e.g. "camera") set to `value`; returns its path.
std::string cornellWith(const std::string& name, const std::string& key, const std::string& value) {
  const std::string path = testing::TempDir() + "/" + name + ".json";
  std::ofstream(path) << R"({"meshes": [{"path": "builtin:cornell"}], ")" << key << R"(": )" << value << "}";
  return path;
}
std::string cornellWithCamera(const std::string& name, const std::string& camera) {
  return cornellWith(name, "camera", camera);
}
std::string cornellWithLights(const std::string& name, const std::string& lights) {
  return cornellWith(name, "lights", lights);
}
}  // namespace

// A camera path: linear between keys, clamped at the ends; a key inherits what it leaves out from the
// camera (up, field of view) and every key keeps the camera's cut-away distance.
TEST(Scene, CameraPathInterpolatesBetweenKeysAndClampsAtTheEnds) {
  const Scene s = loadScene(cornellWithCamera("camera_path", R"({"position": [0, 0, 1], "target": [0, 0, 0],
      "fov_deg": 40, "near": 0.25, "keyframes": [
        {"time": 1, "position": [0, 0, 2], "target": [0, 0, 0]},
        {"time": 3, "position": [2, 0, 2], "target": [1, 0, 0], "up": [0, 0, -1], "fov_deg": 60}]})"));
  ASSERT_EQ(s.cameraPath.size(), 2u);
  EXPECT_FLOAT_EQ(s.camera.clipNear, 0.25f);
  const Camera before = s.cameraAt(0), at1 = s.cameraAt(1), mid = s.cameraAt(2), after = s.cameraAt(7);
  EXPECT_EQ(before.position, glm::vec3(0, 0, 2));  // before the first key: the first key
  EXPECT_EQ(at1.up, glm::vec3(0, 1, 0));           // the camera's up, inherited
  EXPECT_FLOAT_EQ(at1.fovYDeg, 40.0f);
  EXPECT_FLOAT_EQ(at1.clipNear, 0.25f);
  EXPECT_EQ(mid.position, glm::vec3(1, 0, 2));
  EXPECT_EQ(mid.target, glm::vec3(0.5f, 0, 0));
  EXPECT_FLOAT_EQ(mid.fovYDeg, 50.0f);
  EXPECT_NEAR(glm::length(mid.up - glm::vec3(0, 0.5f, -0.5f)), 0.0f, 1e-6f);  // mixed, not renormalised
  EXPECT_EQ(after.position, glm::vec3(2, 0, 2));
  EXPECT_EQ(after.up, glm::vec3(0, 0, -1));
  // Without a path the camera is the same at every time.
  const Scene plain = loadScene("builtin:cornell");
  EXPECT_EQ(plain.cameraAt(5).position, plain.camera.position);
}

// Between two valid keys the position can pass through the target: the nearer key stands in.
TEST(Scene, CameraPathThroughItsTargetKeepsAValidCamera) {
  const Scene s =
      loadScene(cornellWithCamera("camera_through", R"({"position": [0, 0, 1], "target": [0, 0, 0],
      "keyframes": [{"time": 0, "position": [0, 0, 1], "target": [0, 0, 0]},
                    {"time": 1, "position": [0, 0, -1], "target": [0, 0, 0]}]})"));
  const glm::vec3 halfway = s.cameraAt(0.5f).position;  // on the target: a key's camera
  EXPECT_TRUE(halfway == glm::vec3(0, 0, 1) || halfway == glm::vec3(0, 0, -1)) << halfway.z;
  EXPECT_EQ(s.cameraAt(0.75f).position, glm::vec3(0, 0, -0.5f));  // past it: interpolated again
}

// A light path: position and direction linear between keys (the direction renormalised), clamped at
// the ends; a key inherits what it leaves out from the light; a light without keys stays.
TEST(Scene, LightPathsInterpolateBetweenKeysAndClampAtTheEnds) {
  Scene s = loadScene(cornellWithLights("light_path", R"([
      {"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "intensity": 1, "keyframes": [
        {"time": 0, "position": [0, 1, 0]},
        {"time": 2, "position": [1, 1, 0], "direction": [1, 0, 0]}]},
      {"type": "point", "position": [0.5, 0.5, 0.5], "intensity": 1}])"));
  ASSERT_TRUE(s.hasLightPaths());
  s.placeLightsAt(-1);
  EXPECT_EQ(s.lights[0].position, glm::vec3(0, 1, 0));
  EXPECT_EQ(s.lights[0].direction, glm::vec3(0, -1, 0));  // the key's: the light's own
  s.placeLightsAt(1);
  EXPECT_EQ(s.lights[0].position, glm::vec3(0.5f, 1, 0));
  EXPECT_NEAR(glm::length(s.lights[0].direction - glm::normalize(glm::vec3(0.5f, -0.5f, 0))), 0.0f, 1e-6f);
  s.placeLightsAt(9);
  EXPECT_EQ(s.lights[0].position, glm::vec3(1, 1, 0));
  EXPECT_EQ(s.lights[0].direction, glm::vec3(1, 0, 0));
  EXPECT_EQ(s.lights[1].position, glm::vec3(0.5f, 0.5f, 0.5f));
  EXPECT_FALSE(loadScene("builtin:cornell").hasLightPaths());
}

TEST(Scene, BadLightPathsAreNamed) {
  using test::expectError;
  expectError(
      [] {
        loadScene(cornellWithLights("bad_light_time", R"([{"type": "point", "position": [0, 1, 0],
          "intensity": 1, "keyframes": [{"time": 1}, {"time": 0.5, "position": [0, 0, 0]}]}])"));
      },
      {"bad_light_time.json", "lights[0].keyframes[1].time", "increase"});
  expectError(
      [] {
        loadScene(cornellWithLights("bad_light_key", R"([{"type": "directional", "direction": [0, -1, 0],
          "irradiance": 1, "keyframes": [{"time": 0, "position": [0, 1, 0]}]}])"));
      },
      {"bad_light_key.json", "lights[0].keyframes[0]", "position"});
  expectError(
      [] {
        loadScene(cornellWithLights("bad_light_empty", R"([{"type": "point", "position": [0, 1, 0],
          "intensity": 1, "keyframes": []}])"));
      },
      {"bad_light_empty.json", "lights[0].keyframes", "non-empty"});
  expectError(
      [] {
        loadScene(cornellWithLights("bad_light_dir", R"([{"type": "spot", "position": [0, 1, 0],
          "direction": [0, -1, 0], "intensity": 1, "keyframes": [{"time": 0, "direction": [0, 0, 0]}]}])"));
      },
      {"bad_light_dir.json", "lights[0].keyframes[0].direction"});
}

TEST(Scene, BadCameraPathsAndCutAwaysAreNamed) {
  using test::expectError;
  expectError(
      [] {
        loadScene(
            cornellWithCamera("bad_near", R"({"position": [0, 0, 1], "target": [0, 0, 0], "near": -1})"));
      },
      {"bad_near.json", "camera.near", "-1"});
  expectError(
      [] {
        loadScene(
            cornellWithCamera("bad_key_time", R"({"position": [0, 0, 1], "target": [0, 0, 0], "keyframes": [
        {"time": 1, "position": [0, 0, 2]}, {"time": 1, "position": [0, 0, 3]}]})"));
      },
      {"bad_key_time.json", "camera.keyframes[1].time", "increase"});
  expectError(
      [] {
        loadScene(
            cornellWithCamera("bad_key_pose", R"({"position": [0, 0, 1], "target": [0, 0, 0], "keyframes": [
        {"time": 0}, {"time": 1, "position": [0, 0, 0]}]})"));
      },
      {"bad_key_pose.json", "camera.keyframes[1]", "position equals its target"});
  expectError(
      [] {
        loadScene(
            cornellWithCamera("bad_key_key", R"({"position": [0, 0, 1], "target": [0, 0, 0], "keyframes": [
        {"time": 0, "near": 2}]})"));
      },
      {"bad_key_key.json", "camera.keyframes[0]", "near"});
  expectError(
      [] {
        loadScene(cornellWithCamera("bad_keys",
                                    R"({"position": [0, 0, 1], "target": [0, 0, 0], "keyframes": []})"));
      },
      {"bad_keys.json", "camera.keyframes", "non-empty"});
}

// Issue 63, class 3: keys at the ends of float's range. (t − a) / (b − a) in float is inf / inf there,
// and the NaN placed the light nowhere (a black image, exit 0); the fraction is computed in double.
TEST(Scene, KeysAtTheEndsOfFloatsRangeInterpolateFinitely) {
  EXPECT_FLOAT_EQ(keyFraction(1e38f, -3e38f, 3e38f), 2.0f / 3.0f);
  EXPECT_EQ(keyFraction(3.4e38f, -3.4e38f, 3.4e38f), 1.0f);
  EXPECT_EQ(keyFraction(-3.4e38f, -3.4e38f, 3.4e38f), 0.0f);
  EXPECT_EQ(keyFraction(5.0f, 1.0f, 1.0f), 0.0f);  // one instant: the first key
  EXPECT_EQ(keyFraction(-1e30f, 0.0f, 1e-30f), 0.0f);
  Scene s = loadScene(cornellWithLights("light_extreme_keys", R"([
      {"type": "point", "position": [0, 1, 0], "intensity": 1, "keyframes": [
        {"time": -3e38, "position": [0, 1, 0]}, {"time": 3e38, "position": [0.6, 1, 0]}]}])"));
  s.placeLightsAt(1e38f);
  EXPECT_NEAR(s.lights[0].position.x, 0.4f, 1e-6f);
  const Scene c =
      loadScene(cornellWithCamera("camera_extreme_keys", R"({"position": [0, 0, 1], "target": [0, 0, 0],
      "keyframes": [{"time": -3e38, "position": [0, 0, 1]}, {"time": 3e38, "position": [0, 0, 4]}]})"));
  EXPECT_NEAR(c.cameraAt(1e38f).position.z, 3.0f, 1e-6f);
  Mesh m;
  m.dynamic = true;
  Keyframe a, b;
  a.time = -3e38f;
  b.time = 3e38f;
  b.translation = glm::vec3(6, 0, 0);
  m.keyframes = {a, b};
  EXPECT_NEAR(m.objectToWorld(1e38f)[3].x, 4.0f, 1e-5f);
}

}  // namespace vgi
