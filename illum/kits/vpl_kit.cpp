#include "illum/kits/vpl_kit.h"

#include <glad/gl.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/parallel.h"
#include "core/params.h"
#include "core/shader_library.h"
#include "illum/framework/deferred.h"
#include "illum/framework/sample_loop.h"
#include "shaders/shared/bindings.glsl"
#include "traverse/embree_tracer.h"
#include "traverse/gl_ray_tracer.h"

namespace vgi {

namespace {
// Visibility rays per pixel that one gather dispatch traces: a DDA over a
// 512³ grid takes up to 1539 steps, so 24 rays stay under llvmpipe's 65535
// loop iterations per invocation (illum/gather/gather.glsl).
constexpr int kRaysPerDispatch = 24;
}  // namespace

void readVplParams(ParamSet& p, VplSettings& s) {
  s.chains = p.getInt("vpls", s.chains, "N: VPL chains per sample (0: no indirect light)", 0, 1 << 20);
  s.gather = readGatherParams(p, "VPL gather", true, false);
  s.clamp = p.getFloat("clamp", s.clamp,
                       "geometry term clamp: 1/d^2 becomes 1/max(d^2, (clamp * scene diagonal)^2); 0 = off",
                       0.0f, 1.0f);
}

void checkVplMemory(const VplSettings& s) {
  const double mib = double(s.chains) * s.bounces * sizeof(shared::Vpl) / double(1 << 20);
  if (mib > 256.0)
    fail("parameters 'vpls' (", s.chains, ") x 'bounces' (", s.bounces, ") need ", mib,
         " MiB of VPLs (at most 256 MiB)");
}

glm::uvec2 vplRotation(int k, uint32_t seed) {
  const uint32_t h = shared::pcgHash(uint32_t(k) ^ shared::pcgHash(seed));
  return glm::uvec2(h, shared::pcgHash(h));
}

void VplKit::prepare(Frame& f, const VplSettings& s, const std::string& tracer, float voxelDiagonal,
                     float sceneDiagonal) {
  s_ = s;
  sceneDiagonal_ = sceneDiagonal;
  dMin_ = s.clamp * sceneDiagonal;
  ShaderDefines defs;
  addTracerDefine(defs, tracer);
  // The neighbours' visibility tests start at least a voxel diagonal off their surfaces (nearfield.cpp).
  kit_.prepare(f, s.gather, defs, std::max(s.offset, 1.0f) * voxelDiagonal);
  gather_.create(f, {"illum/vpl/gather.comp.glsl"}, defs, {gbufferInput});
  if (s.gather.fixup) {
    ShaderDefines fixupDefs = defs;
    fixupDefs["GATHER_FIXUP"] = "1";
    gatherFixup_.create(f, {"illum/vpl/gather.comp.glsl"}, fixupDefs, {gbufferInput});
  }
  GatherKit::checkPass(gather_);
  checkBlockLayout(gather_.program(), "VplShadow", sizeof(shared::VplShadowParams), gather_.files());
  shared::VplGatherParams& p = gather_.params();
  p.chains = unsigned(s.chains);
  p.bounces = s.bounces;
  p.minDistance2 = minDistance2();
  p.visibility = s.visibility == VplVisibility::Voxels       ? shared::VPL_VISIBILITY_VOXELS
                 : s.visibility == VplVisibility::ShadowMaps ? shared::VPL_VISIBILITY_SHADOW_MAPS
                                                             : shared::VPL_VISIBILITY_NONE;
  p.offset = s.offset * voxelDiagonal;
  shadow_.value = shared::VplShadowParams{};
  const size_t slots = std::max<size_t>(1, size_t(s.chains) * size_t(s.bounces));
  if (slots != slots_) {
    vpls_ = makeBuffer(slots * sizeof(shared::Vpl));
    slots_ = slots;
  }
}

void VplKit::gather(Frame& f, const std::function<void(unsigned)>& bindExtra) {
  if (s_.visibility == VplVisibility::Exact) {
    gatherExact(f);
    return;
  }
  gather_.use(f);
  bindShadowParams();
  if (bindExtra) bindExtra(gather_.program());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VPLS, vpls_.get());
  kit_.dispatchGather(chainBatches(), chainsPerDispatch());
}

int VplKit::chainBatches() const {
  const int sets = s_.gather.interleave * s_.gather.interleave;
  return (s_.chains + sets - 1) / sets;
}

int VplKit::chainsPerDispatch() const { return std::max(1, kRaysPerDispatch / s_.bounces); }

void VplKit::resolve(Frame& f, const std::function<void(unsigned)>& bindExtra) {
  kit_.resolve(f, bindExtra, [&] {
    gatherFixup_.params() = gather_.params();
    gatherFixup_.use(f);
    bindShadowParams();
    if (bindExtra) bindExtra(gatherFixup_.program());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_VPLS, vpls_.get());
    kit_.dispatchFixup(chainBatches(), chainsPerDispatch());
  });
}

void VplKit::bindShadowParams() {
  shadow_.upload();
  shadow_.buffer().bind(UBO_VPL_SHADOW);
}

std::vector<shared::Vpl> VplKit::read() const {
  std::vector<shared::Vpl> v(slots_);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // a compute pass wrote them (generate, avg's shoot)
  glGetNamedBufferSubData(vpls_.get(), 0, GLsizeiptr(v.size() * sizeof(shared::Vpl)), v.data());
  return v;
}

void VplKit::write(const std::vector<shared::Vpl>& v) const {
  glNamedBufferSubData(vpls_.get(), 0, GLsizeiptr(std::min(v.size(), slots_) * sizeof(shared::Vpl)),
                       v.data());
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

// visibility=exact: the gather pass's sum (shared/vpl.glsl: vplSubset,
// vplGather) on the CPU for the same VPLs and receivers, each VPL tested with
// an Embree occlusion ray between the two surface points (the receiver moved
// 10⁻⁴ of the scene diagonal along its normal, the VPL exactLift — avg's VPLs
// sit inside their cells, off the surface: its maps' lift), written into the
// kit's buffer.
void VplKit::gatherExact(Frame& f) {
  const std::vector<shared::Vpl> v = read();
  const int W = f.width(), H = f.height();
  std::vector<glm::vec4> pos(size_t(W) * size_t(H)), nrm(pos.size());
  glGetTextureImage(f.gbuffer().texture(0), 0, GL_RGBA, GL_FLOAT, GLsizei(pos.size() * sizeof(glm::vec4)),
                    pos.data());
  glGetTextureImage(f.gbuffer().texture(1), 0, GL_RGBA, GL_FLOAT, GLsizei(nrm.size() * sizeof(glm::vec4)),
                    nrm.data());
  const int lw = kit_.width(), lh = kit_.height(), scale = kit_.scale(), k = s_.gather.interleave;
  const int chains = s_.chains, bounces = s_.bounces;
  const float eps = 1e-4f * sceneDiagonal_, dMin2 = minDistance2();
  const float lift = s_.exactLift > 0.0f ? s_.exactLift : eps;
  const EmbreeTracer& bvh = f.resources.get<EmbreeTracer>();
  std::vector<glm::vec4> out(size_t(lw) * size_t(lh), glm::vec4(0.0f));
  parallelFor(size_t(lh), 1, f.request.threads, [&](size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y)
      for (int x = 0; x < lw; ++x) {
        const glm::ivec2 q(x, int(y));
        const glm::ivec2 rp = glm::min(q * scale + scale / 2, glm::ivec2(W - 1, H - 1));
        const glm::vec4 P = pos[size_t(rp.y) * size_t(W) + size_t(rp.x)];
        if (P.w == 0.0f) continue;
        const glm::vec3 p(P), n = glm::normalize(glm::vec3(nrm[size_t(rp.y) * size_t(W) + size_t(rp.x)]));
        const glm::vec3 a = p + n * eps;
        glm::vec3 sum(0.0f);
        for (int i = int(shared::vplSubset(q, k)); i < chains; i += k * k)
          for (int b = 0; b < bounces; ++b) {
            const shared::Vpl& l = v[size_t(b) * size_t(chains) + size_t(i)];
            if (l.position.w == 0.0f) break;
            const glm::vec3 c = shared::vplGather(l, p, n, dMin2);
            if (c == glm::vec3(0.0f)) continue;
            const glm::vec3 e = glm::vec3(l.position) + glm::vec3(l.normal) * lift;
            if (!bvh.occluded(a, e - a, 0.0f, 1.0f)) sum += c;
          }
        out[y * size_t(lw) + size_t(x)] = glm::vec4(sum * float(k * k), 1.0f);
      }
  });
  glTextureSubImage2D(kit_.gatherTexture(), 0, 0, 0, lw, lh, GL_RGBA, GL_FLOAT, out.data());
}

void VplKit::stats(Frame& f) const {
  f.addStateBytes(double(slots_ * sizeof(shared::Vpl)));
  const std::vector<shared::Vpl> v = read();
  nlohmann::json placed = nlohmann::json::array(), flux = nlohmann::json::array();
  for (int b = 0; b < s_.bounces; ++b) {
    uint64_t count = 0;
    double sum = 0;
    for (int i = 0; i < s_.chains; ++i) {
      const shared::Vpl& x = v[size_t(b) * size_t(s_.chains) + size_t(i)];
      if (x.position.w == 0.0f) continue;
      ++count;
      sum += (double(x.flux.x) + x.flux.y + x.flux.z) / 3.0;
    }
    placed.push_back(count);
    flux.push_back(sum);
  }
  f.extra["vpls_placed"] = placed;
  f.extra["vpl_flux"] = flux;
  f.extra["clamp_distance"] = dMin_;
  f.extra["clamped"] = s_.clamp > 0.0f;
  f.extra["gather_size"] = {kit_.width(), kit_.height()};
}

Counterpart vplChainsCounterpart(const nlohmann::json& p) {
  return Counterpart{
      "reference",
      {"integrator=path", "maxdepth=" + std::to_string(p.at("bounces").get<int>() + 1), "env=false",
       "glossy=direct"},
      {"direct", "indirect"},
      "neither side integrates the environment light (the VPLs come from the lights' maps); the "
      "environment is the background only; VPLs and receivers reflect diffusely (glossy=direct)",
      fullPathReference()};
}

}  // namespace vgi
