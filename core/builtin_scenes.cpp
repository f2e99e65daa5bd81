// Built-in scenes.
//
// builtin:cornell — the Cornell box as measured and published by the Cornell
// Program of Computer Graphics (graphics.cornell.edu/online/box/data.html):
// the vertex coordinates of that page (millimetres, here scaled to metres), its
// camera (position (278, 273, −800), looking along +z, 35 mm focal length on a
// 25 mm film: vertical fov 2·atan(12.5/35) = 39.31°), and the usual RGB
// reflectances of its measured spectra (white 0.725 0.71 0.68, red 0.63 0.065
// 0.05, green 0.14 0.45 0.091). The 130×105 mm ceiling light is modelled as a
// spot light 1 mm below the ceiling, facing down, with cosine falloff over the
// whole hemisphere: a small Lambertian emitter of radiance L and area A seen from
// afar has intensity I(θ) = L·A·cos θ, so I0 = (17, 12, 4) · 0.01365 m² with the
// radiance commonly used for this light. The light's quad itself is omitted (it
// would be coplanar with the ceiling).
#include "core/builtin_scenes.h"

#include "core/error.h"

namespace vgi {

std::vector<std::string> builtinSceneNames() { return {"cornell"}; }

namespace {
void addQuads(Scene& scene, const std::string& name, int material, const std::vector<glm::vec3>& cornersMm) {
  Mesh m;
  m.name = name;
  m.source = "builtin:cornell";
  m.material = material;
  for (size_t q = 0; q + 3 < cornersMm.size(); q += 4) {
    uint32_t b = uint32_t(m.positions.size());
    for (int k = 0; k < 4; ++k) m.positions.push_back(cornersMm[q + k] * 0.001f);
    m.triangles.push_back({b, b + 1, b + 2});
    m.triangles.push_back({b, b + 2, b + 3});
  }
  scene.meshes.push_back(std::move(m));
}
}  // namespace

void appendBuiltin(const std::string& name, Scene& scene, std::vector<Light>& lights, Camera& camera) {
  if (name != "cornell") {
    std::string known;
    for (auto& n : builtinSceneNames()) known += " builtin:" + n;
    fail("unknown built-in scene 'builtin:", name, "'; known:", known);
  }
  int base = int(scene.materials.size());
  auto mat = [&](const char* n, glm::vec3 a) {
    Material m;
    m.name = n;
    m.albedo = a;
    scene.materials.push_back(m);
  };
  mat("white", {0.725f, 0.71f, 0.68f});
  mat("red", {0.63f, 0.065f, 0.05f});
  mat("green", {0.14f, 0.45f, 0.091f});
  const int white = base, red = base + 1, green = base + 2;

  addQuads(scene, "floor", white, {{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}});
  addQuads(scene, "ceiling", white,
           {{556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}});
  addQuads(scene, "back_wall", white,
           {{549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}});
  addQuads(scene, "right_wall", green, {{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}});
  addQuads(scene, "left_wall", red,
           {{552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}});
  addQuads(scene, "short_block", white,
           {{130, 165, 65},  {82, 165, 225},  {240, 165, 272}, {290, 165, 114}, {290, 0, 114},
            {290, 165, 114}, {240, 165, 272}, {240, 0, 272},   {130, 0, 65},    {130, 165, 65},
            {290, 165, 114}, {290, 0, 114},   {82, 0, 225},    {82, 165, 225},  {130, 165, 65},
            {130, 0, 65},    {240, 0, 272},   {240, 165, 272}, {82, 165, 225},  {82, 0, 225}});
  addQuads(scene, "tall_block", white,
           {{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}, {423, 0, 247},
            {423, 330, 247}, {472, 330, 406}, {472, 0, 406},   {472, 0, 406},   {472, 330, 406},
            {314, 330, 456}, {314, 0, 456},   {314, 0, 456},   {314, 330, 456}, {265, 330, 296},
            {265, 0, 296},   {265, 0, 296},   {265, 330, 296}, {423, 330, 247}, {423, 0, 247}});

  Light spot;
  spot.type = LightType::Spot;
  spot.position = glm::vec3(278.0f, 547.8f, 279.5f) * 0.001f;
  spot.direction = {0, -1, 0};
  spot.intensity = glm::vec3(17, 12, 4) * (0.130f * 0.105f);
  spot.coneHalfAngleDeg = 90.0f;
  spot.falloff = 1.0f;
  lights = {spot};

  camera.position = glm::vec3(278, 273, -800) * 0.001f;
  camera.target = glm::vec3(278, 273, 0) * 0.001f;
  camera.up = {0, 1, 0};
  camera.fovYDeg = 39.3077f;
}

}  // namespace vgi
