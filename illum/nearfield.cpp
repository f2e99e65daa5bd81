// `nearfield`: real-time near-field single-bounce indirect light with voxel
// visibility and RSM back-projection — Thiedemann, Henrich, Grosch, Müller,
// "Voxel-based Global Illumination", I3D 2011, §5.1 (Fig. 7, 12, 15).
//
// Per render: the scene is voxelized into a binary grid (any voxelizer of
// voxelize/, the atlas voxelizer by default), its OR-mip pyramid built on the
// GPU, and reflective shadow maps rendered for every light. In an animation
// (`vgi render --frames N`) these are kept between frames; with dynamic meshes
// the atlas voxelizer keeps the static meshes' grid and re-inserts only the
// dynamic ones (VGI §3.2), then the pyramid and the RSMs are rebuilt. Per
// sample (`--spp` jittered passes, directions rotated): G-buffer → deferred direct light →
// indirect gathering at 1, ½ or ¼ resolution (shaders/illum/nearfield/
// indirect.comp: N cosine rays per pixel, interleaved k×k, first hit by the
// chosen GLSL tracer, back-projection into the RSMs, environment beyond r)
// → geometry-aware blur → joint bilateral upsampling and composite
// direct + albedo × indirect.
//
// Back-projection: VGI tests the voxel entry point against the RSM with
// ε ≥ a voxel diagonal (`backprojection=entry`). By default the texel the
// entry projects to names the surface the light sees there, the ray is
// intersected with that surface's plane, and that point is tested with the
// texel term of ε only (`plane`): the voxel entry lies up to a diagonal off
// the surface, which let the ε test take light from neighbouring surfaces and
// drop lit ones at grazing angles (indirect rel. MAE on the Cornell box at
// 256³, full resolution: 0.22 → 0.09; docs/BENCHMARKS.md). A hit voxel whose
// entry point a light sees past holds no surface there, and the ray goes on
// (`passthrough`).
//
// The exact counterpart is `reference --set integrator=nearfield` with the
// same `radius` and `env`: it differs by voxel visibility (and the start
// offset), RSM back-projection (texel resolution, ε, diffuse-only radiance,
// no emission at the hit point), shadow-mapped direct light, and the reduced
// resolution with its blur and upsampling.
//
// Parameters
// | key          | type   | default            | meaning                                              |
// |--------------|--------|--------------------|------------------------------------------------------|
// | rays         | int    | 16                 | rays per indirect pixel per frame                    |
// | radius       | float  | 0.5 · scene diag.  | ray length r, world units (docs/BENCHMARKS.md: radius) |
// | resolution   | float  | 0.5                | indirect resolution: 1, 0.5 or 0.25 of the image     |
// | interleave   | int    | 4                  | k: k×k pixel blocks with k² direction sets           |
// | blur         | bool   | true               | geometry-aware blur over the interleave window       |
// | tracer       | string | hierarchical       | hierarchical, dda or march (GLSL define)             |
// | env          | bool   | true               | rays leaving r read the environment (black if the scene has none) |
// | backprojection | string | plane            | hit → RSM: `plane` (see indirect.comp) or `entry` (VGI's voxel entry) |
// | passthrough  | bool   | true               | go on past hit voxels whose entry a light sees through |
// | offset       | float  | 0.5 (entry: 1)     | ray start offset along the normal, voxel diagonals (VGI: 1) |
// | voxels       | string | 128                | grid resolution N or WxHxD                           |
// | voxelizer    | string | atlas              | binary voxelizer (see `vgi voxelize --help`)         |
// | shadow_res, shadow_bias, normal_offset: light maps, as in `direct`                        |
#include "illum/nearfield.h"

#include <glad/gl.h>

#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "core/gpu_scene.h"
#include "core/progress.h"
#include "core/shader_library.h"
#include "illum/deferred.h"
#include "illum/direct.h"
#include "illum/light_maps.h"
#include "shaders/shared/gbuffer.glsl"
#include "traverse/gl_ray_tracer.h"
#include "traverse/or_mip_pyramid.h"
#include "voxelize/atlas.h"
#include "voxelize/atlas_voxelizer.h"
#include "voxelize/voxelizer.h"

namespace vgi {

namespace {

struct NearFieldParams {
  int rays = 16, interleave = 4;
  float radius = 0, resolution = 0.5f, offset = 0.5f;
  bool blur = true, env = true, passThrough = true;
  std::string tracer = "hierarchical", voxelizer = "atlas", backProjection = "plane";
  glm::uvec3 voxels{128};
  ShadowParams shadow;
};

class NearFieldMethod : public Method {
 public:
  NearFieldMethod(ParamSet& p, const Scene& scene) {
    NearFieldParams& q = p_;
    q.rays = p.getInt("rays", 16, "rays per indirect pixel per frame", 1, 4096);
    // The default makes near-field GI plainly visible: 0.5 × the diagonal
    // gathers 82 % of the exact one-bounce light on the Cornell box (0.1 ×:
    // 8 %) and all of it on Sibenik (docs/BENCHMARKS.md, the radius table).
    q.radius = p.getFloat("radius", kDefaultNearFieldRadius * scene.bounds().diagonal(),
                          "ray length r in world units (default 0.5 x scene diagonal)", 1e-30f, 1e30f);
    q.resolution = p.getFloat("resolution", 0.5f, "indirect resolution: 1, 0.5 or 0.25 of the image", 0.0f, 1.0f);
    if (q.resolution != 1.0f && q.resolution != 0.5f && q.resolution != 0.25f)
      fail("parameter 'resolution': ", q.resolution, " is not one of 1, 0.5, 0.25");
    q.interleave = p.getInt("interleave", 4, "k: k x k pixel blocks share k^2 direction sets", 1, 8);
    q.blur = p.getBool("blur", true, "geometry-aware blur over the interleave window");
    q.tracer = p.getString("tracer", "hierarchical", "voxel tracer (GLSL define)", {"hierarchical", "dda", "march"});
    q.env = p.getBool("env", true,
                      "rays that leave the radius read the environment (directional occlusion); a scene without "
                      "an environment has a black one, so there env=true adds nothing");
    q.backProjection = p.getString("backprojection", "plane",
                                   "hit -> RSM: plane (the ray meets the plane of the surface the RSM sees there) "
                                   "or entry (VGI: the voxel entry point, epsilon >= a voxel diagonal)",
                                   {"plane", "entry"});
    // VGI's entry test takes light from any surface within ε ≥ a voxel diagonal, the receiver's own
    // voxels included, so with `entry` the rays start VGI's full diagonal off.
    const bool entry = q.backProjection == "entry";
    q.offset = p.getFloat("offset", entry ? 1.0f : 0.5f,
                          "ray start offset along the normal, in voxel diagonals (default 0.5; 1 with "
                          "backprojection=entry, as VGI; with passthrough, voxels within a diagonal of the "
                          "receiver's plane that give no light are passed)",
                          0.0f, 100.0f);
    q.passThrough = p.getBool("passthrough", true,
                              "rays go on past a hit voxel whose entry point a light sees through (empty there), "
                              "or that lies within a voxel diagonal of the receiver's plane and gives no light "
                              "(it may be the receiver's own)");

    q.voxels = parseResolution(p.getString("voxels", "128", "grid resolution N or WxHxD (D a multiple of 128)"),
                               "parameter 'voxels'");
    std::vector<std::string> voxelizers;
    for (auto& v : voxelizerRegistry()) voxelizers.push_back(v.name);
    q.voxelizer = p.getString("voxelizer", "atlas", "binary voxelizer (see vgi voxelize --help)", voxelizers);
    checkGridMemory(q.voxels, 4);  // static + frame grid (atlas), the pyramid (≈ 4/3 of a grid)
    readShadowParams(p, q.shadow);
  }
  std::vector<std::string> outputs() const override { return {"direct", "indirect"}; }
  RenderResult render(const RenderRequest& req, Profiler& profiler) override;

 private:
  // What a render keeps between the frames of an animation.
  struct SceneState {
    VoxelizeRequest vreq;
    std::unique_ptr<AtlasVoxelizer> atlas;  // the atlas voxelizer holds the static meshes' grid
    std::unique_ptr<GlPyramid> pyramid;
    std::unique_ptr<GpuScene> gpu;
    std::unique_ptr<LightMaps> rsm;
    uint64_t voxelsSet = 0;                 // of the grid as last built
    nlohmann::json voxelizerStats;          // idem
  };
  // The render targets of one image size, kept between frames (cleared per render).
  struct Targets {
    Targets(int w, int h, int lowW, int lowH, bool withAov, ShaderLibrary& shaders);
    ~Targets() { glDeleteTextures(2, low); }
    Targets(const Targets&) = delete;
    Targets& operator=(const Targets&) = delete;
    int width, height;
    GBuffer gbuffer;
    Accumulator accum;
    std::unique_ptr<Accumulator> indirectAov;  // when the direct or indirect AOV is asked for
    unsigned low[2] = {0, 0};                  // indirect at its resolution: gathered, blurred
  };
  NearFieldParams p_;
  std::unique_ptr<SceneState> state_;
  std::unique_ptr<Targets> targets_;
};

NearFieldMethod::Targets::Targets(int w, int h, int lowW, int lowH, bool withAov, ShaderLibrary& shaders)
    : width(w), height(h), gbuffer(w, h, shaders), accum(w, h) {
  if (withAov) indirectAov = std::make_unique<Accumulator>(w, h);
  glCreateTextures(GL_TEXTURE_2D, 2, low);
  for (unsigned t : low) {
    glTextureStorage2D(t, 1, GL_RGBA32F, lowW, lowH);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
}

void uniform1i(unsigned prog, const char* name, int v) { glUniform1i(glGetUniformLocation(prog, name), v); }
void uniform1f(unsigned prog, const char* name, float v) { glUniform1f(glGetUniformLocation(prog, name), v); }

RenderResult NearFieldMethod::render(const RenderRequest& req, Profiler& prof) {
  VGI_CHECK(req.gl && req.shaders);
  const Scene& scene = *req.scene;
  ShaderLibrary& shaders = *req.shaders;
  const int W = req.width, H = req.height;
  const int scale = int(std::lround(1.0f / p_.resolution));
  const int lw = (W + scale - 1) / scale, lh = (H + scale - 1) / scale;
  RenderResult result;
  nlohmann::json& extra = result.extra;

  // ---- scene resources: made on the first frame; for a scene with dynamic
  // meshes, updated per frame (static meshes stay voxelized, dynamic ones are
  // re-inserted, the pyramid is rebuilt on the GPU, RSMs re-rendered).
  const bool first = !state_;
  const bool dynamic = scene.hasDynamicMeshes();
  if (first) {
    state_ = std::make_unique<SceneState>();
    // One grid box for the whole animation: the union of the frames' bounds.
    Bounds b;
    for (float t : req.frameTimes.empty() ? std::vector<float>{req.time} : req.frameTimes) {
      Bounds f = scene.bounds(t);
      b.extend(f.lo);
      b.extend(f.hi);
      if (!dynamic) break;
    }
    state_->vreq.scene = &scene;
    state_->vreq.box = fitGridBox(b, p_.voxels);
    state_->vreq.threads = req.threads;
    state_->vreq.gl = req.gl;
    state_->vreq.shaders = req.shaders;
    state_->vreq.atlasCacheDir = defaultAtlasCacheDir();
    state_->vreq.time = req.time;
    if (p_.voxelizer == "atlas") state_->atlas = std::make_unique<AtlasVoxelizer>(state_->vreq, prof);
    state_->pyramid = std::make_unique<GlPyramid>(state_->vreq.box);
    {
      auto s = prof.scope("upload");
      state_->gpu = std::make_unique<GpuScene>(scene, req.time);
    }
    state_->rsm = std::make_unique<LightMaps>(scene, *state_->gpu, shaders, p_.shadow.resolution, true, prof);
  } else if (dynamic) {
    {
      auto s = prof.scope("upload");
      state_->gpu->setTime(scene, req.time);
    }
    state_->rsm->render(*state_->gpu, shaders, prof);
  }
  SceneState& st = *state_;
  if (first || dynamic) {
    st.vreq.time = req.time;
    if (st.atlas) {
      st.atlas->voxelizeFrame(req.time, prof);
      auto s = prof.scope("pyramid");
      st.pyramid->build(st.atlas->frameGrid(), shaders);
    } else {
      BinaryGrid grid = findVoxelizer(p_.voxelizer).run(st.vreq, prof, st.voxelizerStats);
      auto s = prof.scope("pyramid");
      st.pyramid->build(grid, shaders);
    }
  }
  const GlPyramid& glPyramid = *st.pyramid;
  const GpuScene& gpu = *st.gpu;
  const LightMaps& rsm = *st.rsm;
  const float voxelDiagonal = glm::length(st.vreq.box.voxelSize());

  // ---- render targets: kept while the size and the AOVs asked for stay the same.
  const bool wantIndirect = req.wants("indirect"), wantDirect = req.wants("direct");
  const bool withAov = wantIndirect || wantDirect;
  if (!targets_ || targets_->width != W || targets_->height != H || bool(targets_->indirectAov) != withAov) {
    targets_.reset();
    targets_ = std::make_unique<Targets>(W, H, lw, lh, withAov, shaders);
  } else {
    targets_->accum.clear();
    if (withAov) targets_->indirectAov->clear();
  }
  GBuffer& gbuffer = targets_->gbuffer;
  const Accumulator& accum = targets_->accum;
  const Accumulator* indirectAov = targets_->indirectAov.get();
  const unsigned* lowTex = targets_->low;
  DirectPass direct(shaders, gpu, p_.shadow.bias, p_.shadow.normalOffset);

  ShaderDefines defs;
  addTracerDefine(defs, p_.tracer);
  unsigned indirectProg = shaders.program({"illum/nearfield/indirect.comp.glsl"}, defs);
  unsigned blurProg = shaders.program({"illum/nearfield/blur.comp.glsl"});
  unsigned upProg = shaders.program({"illum/nearfield/upsample.comp.glsl"});
  const float pixelAngle = 2.0f * std::tan(glm::radians(scene.camera.fovYDeg) * 0.5f) / float(H);
  const bool blur = p_.blur && p_.interleave > 1;

  ProgressBar bar("nearfield", req.spp);
  int done = 0;
  for (; done < req.spp && !interruptRequested(); ++done) {
    FrameCamera cam = frameCamera(scene.camera, gpu.bounds(), W, H, done, req.spp);
    {
      auto s = prof.scope("gbuffer");
      gbuffer.render(gpu, cam);
    }
    {
      auto s = prof.scope("direct");
      direct.shade(gbuffer, rsm, cam, accum);
    }
    {
      auto s = prof.scope("indirect");
      glUseProgram(indirectProg);
      gpu.bind(indirectProg);
      rsm.bind();
      glPyramid.bind(indirectProg);
      gbuffer.bind();
      uniform1i(indirectProg, "uScale", scale);
      uniform1i(indirectProg, "uRays", p_.rays);
      uniform1i(indirectProg, "uInterleave", p_.interleave);
      uniform1f(indirectProg, "uRadius", p_.radius);
      uniform1f(indirectProg, "uOffset", p_.offset * voxelDiagonal);
      uniform1f(indirectProg, "uVoxelDiagonal", voxelDiagonal);
      uniform1i(indirectProg, "uEnv", p_.env ? 1 : 0);
      uniform1i(indirectProg, "uRsmRes", p_.shadow.resolution);
      uniform1i(indirectProg, "uRefine", p_.backProjection == "plane" ? 1 : 0);
      uniform1i(indirectProg, "uPassThrough", p_.passThrough ? 1 : 0);
      uniform1i(indirectProg, "uFrame", done);
      // Frame 0 unrotated; later frames rotate by Halton (5, 7) points.
      glm::vec2 rot = done == 0 ? glm::vec2(0.0f) : glm::vec2(halton(done, 5), halton(done, 7));
      glUniform2f(glGetUniformLocation(indirectProg, "uRotation"), rot.x, rot.y);
      glBindImageTexture(0, lowTex[0], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
      glDispatchCompute(unsigned(lw + 7) / 8, unsigned(lh + 7) / 8, 1);
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    int current = 0;
    auto geometryUniforms = [&](unsigned prog) {
      glUniform3fv(glGetUniformLocation(prog, "uCameraPosition"), 1, &cam.position.x);
      uniform1f(prog, "uPixelAngle", pixelAngle);
      uniform1i(prog, "uScale", scale);
    };
    if (blur) {
      auto s = prof.scope("blur");
      glUseProgram(blurProg);
      geometryUniforms(blurProg);
      uniform1i(blurProg, "uInterleave", p_.interleave);
      gbuffer.bind();
      glBindTextureUnit(TEXUNIT_PASS_INPUT, lowTex[0]);
      glBindImageTexture(0, lowTex[1], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
      glDispatchCompute(unsigned(lw + 7) / 8, unsigned(lh + 7) / 8, 1);
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
      current = 1;
    }
    {
      auto s = prof.scope(scale > 1 ? "upsample_composite" : "composite");
      glUseProgram(upProg);
      geometryUniforms(upProg);
      uniform1i(upProg, "uWriteAov", indirectAov ? 1 : 0);
      gbuffer.bind();
      glBindTextureUnit(TEXUNIT_PASS_INPUT, lowTex[current]);
      glBindImageTexture(0, accum.texture(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
      glBindImageTexture(1, indirectAov ? indirectAov->texture() : accum.texture(), 0, GL_FALSE, 0, GL_READ_WRITE,
                         GL_RGBA32F);
      glDispatchCompute(unsigned(W + 7) / 8, unsigned(H + 7) / 8, 1);
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    prof.resolve(false);
    if (req.progress) bar.advance();
  }
  bar.finish();
  {
    auto s = prof.scope("readback");
    result.image = accum.read();
    if (indirectAov) {
      Image indirect = indirectAov->read();
      if (wantDirect) {
        Image d(W, H);
        for (size_t i = 0; i < d.pixels.size(); ++i) d.pixels[i] = result.image.pixels[i] - indirect.pixels[i];
        result.aovs["direct"] = std::move(d);
      }
      if (wantIndirect) result.aovs["indirect"] = std::move(indirect);
    }
  }
  result.sppCompleted = done;
  result.interrupted = done < req.spp;
  result.built = {"binary_grid", "or_mip_pyramid", "rsm", "gbuffer"};
  result.samplePasses = {"gbuffer", "direct", "indirect", "blur", "upsample_composite", "composite"};
  extra["radius"] = p_.radius;
  extra["voxel_diagonal"] = voxelDiagonal;
  extra["offset_world"] = p_.offset * voxelDiagonal;
  extra["indirect_size"] = {lw, lh};
  extra["blur_window_px"] = blur ? p_.interleave : 0;
  extra["rays_per_frame"] = uint64_t(lw) * lh * p_.rays;
  if (first || dynamic) {
    // Read back after the image (no wait inside the frame), once per built grid.
    if (st.atlas) st.voxelizerStats = st.atlas->stats();
    st.voxelsSet = glPyramid.countLevel0();
  }
  extra["grid"] = {{"resolution", {p_.voxels.x, p_.voxels.y, p_.voxels.z}}, {"voxelizer", p_.voxelizer},
                   {"voxels_set", st.voxelsSet}, {"stats", st.voxelizerStats},
                   {"rebuilt_this_frame", first || dynamic}};
  extra["light_maps"] = rsm.describe();
  return result;
}

}  // namespace

std::unique_ptr<Method> createNearFieldMethod(ParamSet& params, const Scene& scene) {
  return std::make_unique<NearFieldMethod>(params, scene);
}

}  // namespace vgi
