// The explicit table of rendering methods (no static self-registration: a
// static library would drop unreferenced registrars).
#include <cstdio>

#include "core/error.h"
#include "illum/framework/method.h"
#include "illum/methods/avg.h"
#include "illum/methods/ddgi.h"
#include "illum/methods/direct.h"
#include "illum/methods/nearfield.h"
#include "illum/methods/reference.h"
#include "illum/methods/reference_gl.h"
#include "illum/methods/ssdo.h"
#include "illum/methods/vct.h"
#include "illum/methods/vct_ao.h"
#include "illum/methods/voxel_ao.h"
#include "illum/methods/voxelpath.h"
#include "illum/methods/voxels.h"
#include "illum/methods/vpl.h"

namespace vgi {

std::string counterpartText(const nlohmann::json& v) {
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v.get<double>());
  return buf;
}

std::vector<std::string> fullPathReference(const std::string& envChannel) {
  std::vector<std::string> set = {"integrator=path"};
  if (envChannel != "direct") set.push_back("env_channel=" + envChannel);
  return set;
}

const std::vector<MethodInfo>& methodRegistry() {
  static const std::vector<MethodInfo> table = {
      directMethod(),    nearFieldMethod(), voxelAoMethod(),     voxelPathMethod(), vplMethod(),
      avgMethod(),       vctMethod(),       vctAoMethod(),       ssdoMethod(),      ddgiMethod(),
      voxelViewMethod(), referenceMethod(), referenceGlMethod(),
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
