// vgi info --scene S [--json]: what a scene contains.
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "core/emitters.h"
#include "core/json_text.h"
#include "core/scene_loader.h"

namespace vgi::app {

namespace {
nlohmann::json vec(glm::vec3 v) { return {v.x, v.y, v.z}; }
std::string str(glm::vec3 v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g)", v.x, v.y, v.z);
  return buf;
}
}  // namespace

void addInfoCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "info", "Print what a scene contains (triangles, meshes, materials, lights, bounds)");
  auto scene = std::make_shared<std::string>("builtin:cornell");
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--scene", *scene, "builtin:cornell, a scene .json, or an .obj/.gltf/.glb/.ply file")
      ->capture_default_str();
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=] {
    Scene s = loadScene(*scene);
    Bounds b = s.bounds();
    nlohmann::json j;
    j["scene"] = *scene;
    j["triangles"] = s.triangleCount();
    j["meshes"] = s.meshes.size();
    size_t dyn = 0;
    for (auto& m : s.meshes) dyn += m.dynamic;
    j["dynamic_meshes"] = dyn;
    j["materials"] = nlohmann::json::array();
    for (auto& m : s.materials)
      j["materials"].push_back(
          {{"name", m.name},
           {"albedo", vec(m.albedo)},
           {"ks", vec(m.ks)},
           {"exponent", m.exponent},
           {"emission", vec(m.emission)},
           {"texture", m.albedoTexture >= 0 ? s.textures[size_t(m.albedoTexture)].path : ""}});
    j["lights"] = nlohmann::json::array();
    // Each light with the fields its type has: a point light has no direction
    // or cone, a directional light no position (and irradiance, not intensity).
    for (auto& l : s.lights) {
      nlohmann::json lj = {{"type", lightTypeName(l.type)}};
      if (l.type != LightType::Directional) lj["position"] = vec(l.position);
      if (l.type != LightType::Point) lj["direction"] = vec(l.direction);
      lj[l.type == LightType::Directional ? "irradiance" : "intensity"] = vec(l.intensity);
      if (l.type == LightType::Spot) {
        lj["cone_deg"] = l.coneHalfAngleDeg;
        lj["falloff"] = l.falloff;
      }
      j["lights"].push_back(lj);
    }
    // Area lights: the emissive meshes (core/emitters.h), per mesh at time 0.
    struct AreaLight {
      int triangles = 0;
      float area = 0;
      glm::vec3 radiance{0.0f}, power{0.0f};
    };
    const Emitters emitters = Emitters::ofScene(s, 0.0f);
    std::map<int, AreaLight> areaLights;
    for (size_t e = 0; e < emitters.size(); ++e) {
      const EmitterTriangle& t = emitters.triangles()[e];
      AreaLight& a = areaLights[t.mesh];
      a.triangles++;
      a.area += t.area;
      a.radiance = t.radiance;
      a.power += emitters.power(e);
    }
    j["area_lights"] = nlohmann::json::array();
    for (auto& [mesh, a] : areaLights)
      j["area_lights"].push_back({{"mesh", s.meshes[size_t(mesh)].name},
                                  {"triangles", a.triangles},
                                  {"area", a.area},
                                  {"radiance", vec(a.radiance)},
                                  {"power", vec(a.power)}});
    j["two_sided_emission"] = s.twoSidedEmission;
    j["bounds"] = {{"min", vec(b.lo)}, {"max", vec(b.hi)}, {"diagonal", b.diagonal()}};
    j["camera"] = {{"position", vec(s.camera.position)},
                   {"target", vec(s.camera.target)},
                   {"up", vec(s.camera.up)},
                   {"fov_deg", s.camera.fovYDeg}};
    j["presets"] = s.presets;
    j["degenerate_triangles_dropped"] = s.report.degenerateTrianglesDropped;
    j["warnings"] = s.report.warnings;
    if (*json) {
      std::printf("%s\n", jsonText(j, 2).c_str());
      return;
    }
    std::printf("scene      %s\n", scene->c_str());
    std::printf("triangles  %zu (%ld degenerate dropped)\n", s.triangleCount(),
                s.report.degenerateTrianglesDropped);
    std::printf("meshes     %zu (%zu dynamic)\n", s.meshes.size(), dyn);
    std::printf("materials  %zu\n", s.materials.size());
    for (auto& m : s.materials)
      std::printf("  %-20s albedo %s ks %s exponent %g emission %s %s\n", m.name.c_str(),
                  str(m.albedo).c_str(), str(m.ks).c_str(), m.exponent, str(m.emission).c_str(),
                  m.albedoTexture >= 0 ? s.textures[size_t(m.albedoTexture)].path.c_str() : "");
    std::printf("lights     %zu\n", s.lights.size());
    for (auto& l : s.lights) {
      std::printf("  %-11s", lightTypeName(l.type));
      if (l.type != LightType::Directional) std::printf(" position %s", str(l.position).c_str());
      if (l.type != LightType::Point) std::printf(" direction %s", str(l.direction).c_str());
      std::printf(" %s %s", l.type == LightType::Directional ? "irradiance" : "intensity",
                  str(l.intensity).c_str());
      if (l.type == LightType::Spot) std::printf(" cone %g deg falloff %g", l.coneHalfAngleDeg, l.falloff);
      std::printf("\n");
    }
    std::printf("area lights %zu (%s emission)\n", areaLights.size(),
                s.twoSidedEmission ? "two-sided" : "one-sided");
    for (auto& [mesh, a] : areaLights)
      std::printf("  %-20s %d triangles area %g radiance %s power %s W\n",
                  s.meshes[size_t(mesh)].name.c_str(), a.triangles, a.area, str(a.radiance).c_str(),
                  str(a.power).c_str());
    std::printf("bounds     %s .. %s (diagonal %g)\n", str(b.lo).c_str(), str(b.hi).c_str(), b.diagonal());
    std::printf("camera     position %s target %s up %s fov %g deg\n", str(s.camera.position).c_str(),
                str(s.camera.target).c_str(), str(s.camera.up).c_str(), s.camera.fovYDeg);
    for (auto& w : s.report.warnings) std::printf("warning    %s\n", w.c_str());
  });
}

}  // namespace vgi::app
