// The explicit table of rendering methods (no static self-registration: a
// static library would drop unreferenced registrars).
#include <cstdio>

#include "core/error.h"
#include "illum/avg.h"
#include "illum/direct.h"
#include "illum/method.h"
#include "illum/nearfield.h"
#include "illum/reference.h"
#include "illum/vct.h"
#include "illum/vct_ao.h"
#include "illum/voxel_ao.h"
#include "illum/voxel_view.h"
#include "illum/voxelpath.h"
#include "illum/vpl.h"

namespace vgi {

namespace {
// A float parameter as text that parses back to the same float.
std::string exactText(const nlohmann::json& v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v.get<double>());
  return buf;
}
}  // namespace

const std::vector<MethodInfo>& methodRegistry() {
  static const std::vector<MethodInfo> table = {
      {"direct", "GL deferred direct lighting with shadow maps (delta lights, emission)", true,
       [](ParamSet& p, const Scene& s) { return createDirectMethod(p, s); },
       [](const nlohmann::json&) {
         return Counterpart{"reference", {"integrator=direct"}, {}};
       }},
      {"nearfield", "GL near-field one-bounce GI: voxel visibility + RSM back-projection (VGI 5.1)", true,
       [](ParamSet& p, const Scene& s) { return createNearFieldMethod(p, s); },
       [](const nlohmann::json& p) {
         return Counterpart{"reference",
                            {"integrator=nearfield", "radius=" + exactText(p.at("radius")),
                             std::string("env=") + (p.at("env").get<bool>() ? "true" : "false")},
                            {"direct", "indirect"}};
       }},
      {"voxel_ao",
       "GL ambient occlusion through the binary voxel grid (hierarchical first-hit tracer, VGI 4)", true,
       [](ParamSet& p, const Scene& s) { return createVoxelAoMethod(p, s); },
       [](const nlohmann::json& p) {
         return Counterpart{"reference", {"integrator=ao", "radius=" + exactText(p.at("radius"))}, {}};
       }},
      {"voxelpath",
       "GL voxel path tracing: multi-bounce diffuse + glossy GI through the voxel grid (VGI 5.2)", true,
       [](ParamSet& p, const Scene& s) { return createVoxelPathMethod(p, s); },
       [](const nlohmann::json& p) {
         return Counterpart{"reference",
                            {"integrator=path", "maxdepth=" + std::to_string(p.at("maxdepth").get<int>()),
                             "rr_depth=" + std::to_string(p.at("rr_depth").get<int>())},
                            {"direct", "indirect"}};
       }},
      {"vpl",
       "GL instant radiosity: RSM + voxel-traced VPL chains, voxel two-point visibility, interleaved (VGI "
       "5.3)",
       true, [](ParamSet& p, const Scene& s) { return createVplMethod(p, s); },
       [](const nlohmann::json& p) {
         return Counterpart{"reference",
                            {"integrator=path", "maxdepth=" + std::to_string(p.at("bounces").get<int>() + 1)},
                            {"direct", "indirect"}};
       }},
      {"avg",
       "GL instant radiosity with Approximate Visibility Grids: light-traced VPLs, per-VPL shadow maps "
       "(Bashford-Rogers et al.)",
       true, [](ParamSet& p, const Scene& s) { return createAvgMethod(p, s); },
       [](const nlohmann::json& p) {
         return Counterpart{"reference",
                            {"integrator=path", "maxdepth=" + std::to_string(p.at("bounces").get<int>() + 1)},
                            {"direct", "indirect"}};
       }},
      {"vct",
       "GL voxel cone tracing: injected radiance, anisotropic pre-integration, diffuse + specular cones, AO, "
       "soft shadows (Crassin et al. 2011; Dinse 2015)",
       true, [](ParamSet& p, const Scene& s) { return createVctMethod(p, s); },
       [](const nlohmann::json&) {
         return Counterpart{"reference", {"integrator=path", "maxdepth=2"}, {"direct", "indirect"}};
       }},
      {"vct_ao",
       "GL ambient occlusion by voxel cone tracing: 3/5/8-cone constellations, local jitter, overlap "
       "(Basgier "
       "2015)",
       true, [](ParamSet& p, const Scene& s) { return createVctAoMethod(p, s); },
       [](const nlohmann::json& p) {
         return Counterpart{"reference", {"integrator=ao", "radius=" + exactText(p.at("radius"))}, {}};
       }},
      {"voxels",
       "GL debug view: the binary grid from the camera through the tracer (VGI 4), faces coloured by axis",
       true, [](ParamSet& p, const Scene& s) { return createVoxelViewMethod(p, s); }},
      {"reference", "CPU Embree reference: integrator=path|nearfield|ao|direct", false,
       [](ParamSet& p, const Scene& s) { return createReferenceMethod(p, s); }},
  };
  return table;
}

const MethodInfo& findMethod(const std::string& name, const std::string& option) {
  std::string known;
  for (auto& m : methodRegistry()) {
    if (m.name == name) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  fail(option, ": unknown method '", name, "' (known: ", known, ")");
}

// The framework's headline method: near-field GI is what a first render should show.
std::string defaultMethodName() { return "nearfield"; }

}  // namespace vgi
