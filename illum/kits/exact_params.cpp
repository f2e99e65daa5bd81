#include "illum/kits/exact_params.h"

#include <string>
#include <vector>

#include "core/error.h"
#include "core/params.h"
#include "core/scene.h"
#include "illum/kits/shared_params.h"
#include "voxelize/voxel_grid.h"

namespace vgi {

namespace {
// visibility, voxels, offset: the voxel-visibility stage of nearfield and path (CPU only).
template <class Check>
void readVisibility(ParamSet& params, ExactParams& e, const char* method, bool voxelsSupported, Check check) {
  const bool nearField = e.integrator == ExactIntegrator::NearField;
  const char* visDoc =
      voxelsSupported
          ? "nearfield/path: exact, or voxels (bounce rays' first hits through an exact voxelization)"
          : "nearfield/path: exact (visibility=voxels, the voxel-visibility stage, runs in `reference` on "
            "the CPU)";
  const char* voxDoc = "nearfield/path, visibility=voxels: grid resolution N or WxHxD";
  const char* offDoc =
      "nearfield/path, visibility=voxels: ray start offset along the normal, voxel diagonals";
  if (check(nearField || e.integrator == ExactIntegrator::Path, "visibility")) {
    std::string v;
    try {
      v = params.getString(
          "visibility", "exact", visDoc,
          voxelsSupported ? std::vector<std::string>{"exact", "voxels"} : std::vector<std::string>{"exact"});
    } catch (const Error& ex) {
      if (voxelsSupported) throw;
      fail(ex.what(), ": ", method,
           " traces exact triangles only; the voxel-visibility stage is `reference --set visibility=voxels` "
           "(CPU)");
    }
    e.voxelVisibility = v == "voxels";
  } else {
    params.declare("visibility", "string", "exact", visDoc);
  }
  if (check(e.voxelVisibility, "voxels")) {
    e.voxels = parseResolution(params.getString("voxels", "128", voxDoc), "parameter 'voxels'");
    checkGridMemory(e.voxels, 2);
  } else {
    params.declare("voxels", "string", "128", voxDoc);
  }
  if (check(e.voxelVisibility, "offset"))
    e.offset = params.getFloat("offset", 1.0f, offDoc, 0.0f, 100.0f);
  else
    params.declare("offset", "float", "1.0", offDoc);
}
}  // namespace

ExactParams readExactParams(ParamSet& params, const Scene& scene, const char* method, bool voxelsSupported) {
  ExactParams e;
  const std::string name =
      params.getString("integrator", "path", "what to compute", {"path", "nearfield", "ao", "direct"});
  e.integrator = name == "path"        ? ExactIntegrator::Path
                 : name == "direct"    ? ExactIntegrator::Direct
                 : name == "nearfield" ? ExactIntegrator::NearField
                                       : ExactIntegrator::Ao;
  e.integratorName = e.integrator == ExactIntegrator::Path        ? "path"
                     : e.integrator == ExactIntegrator::Direct    ? "direct"
                     : e.integrator == ExactIntegrator::NearField ? "nearfield"
                                                                  : "ao";
  const bool usesDepth = e.integrator == ExactIntegrator::Path;
  const bool usesRadius = e.integrator == ExactIntegrator::NearField || e.integrator == ExactIntegrator::Ao;
  const bool nearField = e.integrator == ExactIntegrator::NearField;  // env, visibility
  // Every parameter is documented; only the integrator's own are read (and so
  // appear in the stats); giving another integrator's parameter is an error.
  auto check = [&](bool uses, const char* key) {
    if (!uses && params.has(key)) fail("parameter '", key, "' does not apply to integrator=", name);
    return uses;
  };
  const char* depthDoc = "path: maximum number of bounces";
  const char* rrDoc = "path: bounces before Russian roulette";
  const char* radiusDoc =
      "nearfield/ao: ray length in world units (default 0.5 x scene diagonal for nearfield, as the "
      "nearfield "
      "module; 0.1 x for ao)";
  const char* envDoc =
      "the environment lights the scene: path/direct: bounce rays that leave the scene read it; nearfield: "
      "rays that leave the radius read it (black where the scene has none). false: the environment is "
      "the camera's background only, the counterpart of a method that does not integrate it";
  const char* envChannelDoc =
      "path: the channel of the environment seen from the first surface (direct, as emission met by "
      "that bounce; or indirect, as nearfield and the cone methods count it)";
  if (check(usesDepth, "maxdepth"))
    e.maxDepth = params.getInt("maxdepth", 8, depthDoc, 1, 10000);
  else
    params.declare("maxdepth", "int", "8", depthDoc);
  if (check(usesDepth, "rr_depth"))
    e.rrDepth = params.getInt("rr_depth", 3, rrDoc, 0, 10000);
  else
    params.declare("rr_depth", "int", "3", rrDoc);
  const float diag = scene.bounds().diagonal();
  const float radiusDefault = (nearField ? kDefaultNearFieldRadius : kDefaultAoRadius) * diag;
  if (check(usesRadius, "radius"))
    e.radius = params.getFloat("radius", radiusDefault, radiusDoc, 1e-30f, 1e30f);
  else
    params.declare("radius", "float", std::to_string(radiusDefault), radiusDoc);
  if (check(e.integrator != ExactIntegrator::Ao, "env"))
    e.env = params.getBool("env", true, envDoc);
  else
    params.declare("env", "bool", "true", envDoc);
  if (check(usesDepth, "env_channel"))
    e.envIndirect =
        params.getString("env_channel", "direct", envChannelDoc, {"direct", "indirect"}) == "indirect";
  else
    params.declare("env_channel", "string", "direct", envChannelDoc);
  const char* glossyDoc =
      "path/nearfield: the surfaces that reflect by their Phong lobe: all; first (the visible surface "
      "only, every bounce surface diffuse: the cone methods' model); direct (only the visible surface's "
      "direct light: the indirect light it reflects and every bounce surface diffuse: the model of the "
      "methods that bounce diffusely)";
  if (check(usesDepth || nearField, "glossy")) {
    const std::string g = params.getString("glossy", "all", glossyDoc, {"all", "first", "direct"});
    e.glossy = g == "all" ? GlossyModel::All : g == "first" ? GlossyModel::First : GlossyModel::Direct;
  } else {
    params.declare("glossy", "string", "all", glossyDoc);
  }
  readVisibility(params, e, method, voxelsSupported, check);
  const char* emDoc = "path/direct/nearfield: area lights sampled by mis (light + BRDF), light or brdf";
  if (check(e.integrator != ExactIntegrator::Ao, "emitter_sampling")) {
    const std::string s = params.getString("emitter_sampling", "mis", emDoc, {"mis", "light", "brdf"});
    e.emitterSampling = s == "mis"     ? EmitterSampling::Mis
                        : s == "light" ? EmitterSampling::Light
                                       : EmitterSampling::Brdf;
  } else {
    params.declare("emitter_sampling", "string", "mis", emDoc);
  }
  if (e.integrator == ExactIntegrator::Direct) e.maxDepth = 1;
  return e;
}

}  // namespace vgi
