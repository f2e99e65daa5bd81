// vgi info --scene S [--json] [--gl B]: what a scene contains, and the OpenGL driver a render
// would use (backend, GL_RENDERER, GL_VERSION: the same line every stats JSON carries). The text is
// the JSON's contents, laid out for reading.
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "core/emitters.h"
#include "core/error.h"
#include "core/gl_context.h"
#include "core/json_text.h"
#include "core/scene_loader.h"

namespace vgi::app {

namespace {

nlohmann::json vec(glm::vec3 v) { return {v.x, v.y, v.z}; }

std::string str(const nlohmann::json& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g)", v[0].get<double>(), v[1].get<double>(),
                v[2].get<double>());
  return buf;
}

nlohmann::json materialsInfo(const Scene& s) {
  nlohmann::json list = nlohmann::json::array();
  for (auto& m : s.materials)
    list.push_back({{"name", m.name},
                    {"albedo", vec(m.albedo)},
                    {"ks", vec(m.ks)},
                    {"exponent", m.exponent},
                    {"emission", vec(m.emission)},
                    {"texture", m.albedoTexture >= 0 ? s.textures[size_t(m.albedoTexture)].path : ""}});
  return list;
}

// Each light with the fields its type has: a point light has no direction or
// cone, a directional light no position (and irradiance, not intensity).
nlohmann::json lightsInfo(const Scene& s) {
  nlohmann::json list = nlohmann::json::array();
  for (auto& l : s.lights) {
    nlohmann::json lj = {{"type", lightTypeName(l.type)}};
    if (l.type != LightType::Directional) lj["position"] = vec(l.position);
    if (l.type != LightType::Point) lj["direction"] = vec(l.direction);
    lj[l.type == LightType::Directional ? "irradiance" : "intensity"] = vec(l.intensity);
    if (l.type == LightType::Spot) {
      lj["cone_deg"] = l.coneHalfAngleDeg;
      lj["falloff"] = l.falloff;
    }
    list.push_back(lj);
  }
  return list;
}

// Area lights: the emissive meshes (core/emitters.h), per mesh at time 0.
nlohmann::json areaLightsInfo(const Scene& s) {
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
  nlohmann::json list = nlohmann::json::array();
  for (auto& [mesh, a] : areaLights)
    list.push_back({{"mesh", s.meshes[size_t(mesh)].name},
                    {"triangles", a.triangles},
                    {"area", a.area},
                    {"radiance", vec(a.radiance)},
                    {"power", vec(a.power)}});
  return list;
}

nlohmann::json sceneInfo(const Scene& s, const std::string& spec) {
  const Bounds b = s.bounds();
  nlohmann::json j;
  j["scene"] = spec;
  j["triangles"] = s.triangleCount();
  j["meshes"] = s.meshes.size();
  size_t dyn = 0;
  for (auto& m : s.meshes) dyn += m.dynamic;
  j["dynamic_meshes"] = dyn;
  j["materials"] = materialsInfo(s);
  j["lights"] = lightsInfo(s);
  j["area_lights"] = areaLightsInfo(s);
  j["two_sided_emission"] = s.twoSidedEmission;
  j["bounds"] = {{"min", vec(b.lo)}, {"max", vec(b.hi)}, {"diagonal", b.diagonal()}};
  j["camera"] = {{"position", vec(s.camera.position)},
                 {"target", vec(s.camera.target)},
                 {"up", vec(s.camera.up)},
                 {"fov_deg", s.camera.fovYDeg}};
  j["presets"] = s.presets;
  j["degenerate_triangles_dropped"] = s.report.degenerateTrianglesDropped;
  j["warnings"] = s.report.warnings;
  return j;
}

void printSceneInfo(const nlohmann::json& j) {
  auto text = [](const nlohmann::json& v) { return v.get<std::string>(); };
  std::printf("scene      %s\n", text(j["scene"]).c_str());
  std::printf("triangles  %zu (%ld degenerate dropped)\n", j["triangles"].get<size_t>(),
              j["degenerate_triangles_dropped"].get<long>());
  std::printf("meshes     %zu (%zu dynamic)\n", j["meshes"].get<size_t>(), j["dynamic_meshes"].get<size_t>());
  std::printf("materials  %zu\n", j["materials"].size());
  for (auto& m : j["materials"])
    std::printf("  %-20s albedo %s ks %s exponent %g emission %s %s\n", text(m["name"]).c_str(),
                str(m["albedo"]).c_str(), str(m["ks"]).c_str(), m["exponent"].get<double>(),
                str(m["emission"]).c_str(), text(m["texture"]).c_str());
  std::printf("lights     %zu\n", j["lights"].size());
  for (auto& l : j["lights"]) {
    std::printf("  %-11s", text(l["type"]).c_str());
    if (l.contains("position")) std::printf(" position %s", str(l["position"]).c_str());
    if (l.contains("direction")) std::printf(" direction %s", str(l["direction"]).c_str());
    const char* power = l.contains("irradiance") ? "irradiance" : "intensity";
    std::printf(" %s %s", power, str(l[power]).c_str());
    if (l.contains("cone_deg"))
      std::printf(" cone %g deg falloff %g", l["cone_deg"].get<double>(), l["falloff"].get<double>());
    std::printf("\n");
  }
  std::printf("area lights %zu (%s emission)\n", j["area_lights"].size(),
              j["two_sided_emission"].get<bool>() ? "two-sided" : "one-sided");
  for (auto& a : j["area_lights"])
    std::printf("  %-20s %d triangles area %g radiance %s power %s W\n", text(a["mesh"]).c_str(),
                a["triangles"].get<int>(), a["area"].get<double>(), str(a["radiance"]).c_str(),
                str(a["power"]).c_str());
  const nlohmann::json& b = j["bounds"];
  std::printf("bounds     %s .. %s (diagonal %g)\n", str(b["min"]).c_str(), str(b["max"]).c_str(),
              b["diagonal"].get<double>());
  const nlohmann::json& c = j["camera"];
  std::printf("camera     position %s target %s up %s fov %g deg\n", str(c["position"]).c_str(),
              str(c["target"]).c_str(), str(c["up"]).c_str(), c["fov_deg"].get<double>());
  for (auto& w : j["warnings"]) std::printf("warning    %s\n", text(w).c_str());
  const nlohmann::json& g = j["gl"];
  if (g.contains("error"))
    std::printf("gl         none: %s\n", text(g["error"]).c_str());
  else
    std::printf("gl         %s: %s, %s\n", text(g["backend"]).c_str(), text(g["renderer"]).c_str(),
                text(g["version"]).c_str());
}

// The driver `--gl` selects, or why there is none (info still describes the scene).
nlohmann::json glInfo(const std::string& backend) {
  const GlBackend b = parseGlBackend(backend);
  try {
    const std::unique_ptr<GlContext> gl = GlContext::create(b);
    return {{"backend", gl->backendName()}, {"renderer", gl->renderer()}, {"version", gl->version()}};
  } catch (const Error& e) {
    return {{"error", e.what()}};
  }
}

}  // namespace

void addInfoCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "info", "Print what a scene contains (triangles, meshes, materials, lights, bounds)");
  auto scene = std::make_shared<std::string>("builtin:cornell");
  auto json = std::make_shared<bool>(false);
  auto gl = std::make_shared<std::string>("auto");
  cmd->add_option("--scene", *scene, "builtin:cornell, a scene .json, or an .obj/.gltf/.glb/.ply file")
      ->capture_default_str();
  cmd->add_flag("--json", *json, "print JSON");
  cmd->add_option("--gl", *gl, "GL backend whose driver to name: auto|egl|osmesa|zink")
      ->capture_default_str();
  cmd->callback([=] {
    nlohmann::json j = sceneInfo(loadScene(*scene), *scene);
    j["gl"] = glInfo(*gl);
    if (*json)
      std::printf("%s\n", jsonText(j, 2).c_str());
    else
      printSceneInfo(j);
  });
}

}  // namespace vgi::app
