// The bad-input corpus (tests/data/bad/): every file must give a clear error
// naming the file and the bad value, or a counted warning — never a crash.
#include "core/scene_loader.h"
#include "test_util.h"

namespace vgi {
using test::dataPath;
using test::expectError;

TEST(BadInput, MalformedAndInvalidSceneJson) {
  expectError([] { loadScene(dataPath("bad/malformed.json")); }, {"malformed.json", "malformed JSON"});
  expectError([] { loadScene(dataPath("bad/unknown_key.json")); }, {"unknown_key.json", "lihgts"});
  expectError([] { loadScene(dataPath("bad/wrong_type.json")); },
              {"wrong_type.json", "lights[0].intensity", "bright"});
  expectError([] { loadScene(dataPath("bad/bad_fov.json")); }, {"bad_fov.json", "camera.fov_deg", "270"});
  expectError([] { loadScene(dataPath("bad/bad_cone.json")); }, {"bad_cone.json", "cone_deg", "120"});
  expectError([] { loadScene(dataPath("bad/missing_mesh.json")); }, {"does_not_exist.obj", "does not exist"});
  expectError([] { loadScene(dataPath("bad/no_meshes.json")); }, {"no_meshes.json", "meshes"});
  expectError([] { loadScene(dataPath("bad/zero_direction.json")); }, {"zero_direction.json", "direction"});
  expectError([] { loadScene(dataPath("bad/unknown_builtin.json")); }, {"builtin:sponza", "builtin:cornell"});
  expectError([] { loadScene("builtin:nothing"); }, {"builtin:nothing"});
  expectError([] { loadScene(dataPath("bad/no_such_file.json")); }, {"no_such_file.json", "does not exist"});
}

TEST(BadInput, NonFiniteVerticesAreErrors) {
  expectError([] { loadScene(dataPath("bad/nan_vertex.obj")); },
              {"nan_vertex.obj", "vertex 2", "non-finite"});
  expectError([] { loadScene(dataPath("bad/inf_vertex.obj")); }, {"inf_vertex.obj", "non-finite"});
}

TEST(BadInput, OutOfRangeIndicesAreErrors) {
  expectError([] { loadScene(dataPath("bad/bad_index.obj")); }, {"bad_index.obj"});
  expectError([] { loadScene(dataPath("bad/bad_index.ply")); }, {"bad_index.ply"});
}

TEST(BadInput, DegenerateTrianglesAreDroppedAndCounted) {
  Scene s = loadScene(dataPath("bad/degenerate.obj"));
  EXPECT_EQ(s.triangleCount(), 1u);
  EXPECT_EQ(s.report.degenerateTrianglesDropped, 2);
}

TEST(BadInput, EmptyScenesAreErrors) {
  expectError([] { loadScene(dataPath("bad/empty.obj")); }, {"empty.obj"});
}

TEST(BadInput, MissingTextureWarnsAndKeepsConstantAlbedo) {
  Scene s = loadScene(dataPath("bad/missing_texture.obj"));
  ASSERT_EQ(s.triangleCount(), 1u);
  const Material& m = s.materials[size_t(s.meshes[0].material)];
  EXPECT_EQ(m.albedoTexture, -1);
  EXPECT_NEAR(m.albedo.x, 0.5f, 1e-6f);
  bool warned = false;
  for (auto& w : s.report.warnings) warned |= w.find("no_such_texture.png") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(BadInput, BrokenPlyAndGltfAreErrors) {
  expectError([] { loadScene(dataPath("bad/truncated.ply")); }, {"truncated.ply"});
  expectError([] { loadScene(dataPath("bad/malformed.gltf")); }, {"malformed.gltf"});
  expectError([] { loadScene(dataPath("bad/bad_buffer.gltf")); }, {"bad_buffer.gltf"});
  expectError([] { loadScene(dataPath("bad/garbage.glb")); }, {"garbage.glb"});
  expectError([] { loadScene(dataPath("bad/unsupported.stl")); }, {"unsupported.stl", ".stl"});
  expectError([] { loadScene(dataPath("bad")); }, {"is a directory"});
}

TEST(BadInput, MeshValidationNamesTheProblem) {
  Mesh m;
  m.name = "tri";
  m.source = "unit";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.normals = {{0, 0, 1}};
  m.triangles = {{0, 1, 2}};
  LoadReport r;
  expectError([&] { validateMesh(m, r); }, {"1 normals for 3 vertices"});
  m.normals.clear();
  m.triangles = {{0, 1, 3}};
  expectError([&] { validateMesh(m, r); }, {"vertex index 3", "3 vertices"});
}

}  // namespace vgi

namespace vgi {
TEST(BadInput, MaterialsThatCreateEnergyAreClampedWithAWarning) {
  Scene s = loadScene(test::dataPath("bad/too_bright.obj"));
  const Material& m = s.materials[size_t(s.meshes[0].material)];
  EXPECT_NEAR(m.albedo.x + m.ks.x, 1.0f, 1e-6f);
  EXPECT_NEAR(m.ks.z, 0.5f, 1e-6f);  // 0.2 + 0.5 fits: unchanged
  EXPECT_NEAR(m.exponent, 30.0f, 1e-6f);
  bool warned = false;
  for (auto& w : s.report.warnings) warned |= w.find("shiny") != std::string::npos;
  EXPECT_TRUE(warned);
  // A PLY has no materials: it gets the framework's default, not assimp's white+specular one.
  Scene p = loadScene(test::dataPath("no_material.ply"));
  const Material& d = p.materials[size_t(p.meshes[0].material)];
  EXPECT_EQ(d.albedo, glm::vec3(0.8f));
  EXPECT_EQ(d.ks, glm::vec3(0.0f));
}
}  // namespace vgi
