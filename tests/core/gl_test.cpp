// Headless GL: both backends give a 4.5 core context, KHR_debug counts errors,
// the shader loader maps compile errors to files and lines, and the shared
// kernels compute on the GPU what they compute on the CPU.
#include <glad/gl.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/gl_context.h"
#include "core/gl_handles.h"
#include "core/gpu_memory.h"
#include "core/json_text.h"
#include "core/profiler.h"
#include "core/shader_library.h"
#include "shaders/shared/brdf.glsl"
#include "shaders/shared/lights.glsl"
#include "shaders/shared/sampling.glsl"
#include "test_util.h"

namespace vgi {

TEST(GlContext, EglAndOsmesaGiveGl45Core) {
  for (GlBackend b : {GlBackend::Egl, GlBackend::Osmesa}) {
    auto ctx = GlContext::create(b);
    EXPECT_FALSE(ctx->renderer().empty());
    GLint major = 0, minor = 0, mask = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    EXPECT_GE(major * 10 + minor, 45) << ctx->backendName();
    EXPECT_TRUE(mask & GL_CONTEXT_CORE_PROFILE_BIT);
    EXPECT_EQ(ctx->errorCount(), 0);
  }
  test::expectError([] { parseGlBackend("vulkan"); }, {"--gl", "vulkan"});
}

// libOSMesa is loaded when the OSMesa backend is chosen, not linked: a process that renders through
// EGL never maps it (a GPU node needs no Mesa), and the binary's dependencies do not name it.
TEST(GlContext, OsmesaIsLoadedWhenChosenNotLinked) {
  auto mapped = [] {
    std::ifstream maps("/proc/self/maps");
    const std::string text((std::istreambuf_iterator<char>(maps)), {});
    return text.find("libOSMesa") != std::string::npos;
  };
  if (mapped()) GTEST_SKIP() << "an earlier test of this process chose OSMesa (ctest runs each alone)";
  { auto egl = GlContext::create(GlBackend::Egl); }
  EXPECT_FALSE(mapped()) << "libOSMesa mapped before the OSMesa backend was chosen";
  auto ctx = GlContext::create(GlBackend::Osmesa);
  EXPECT_TRUE(mapped());
  EXPECT_EQ(ctx->backendName(), "osmesa");
}

TEST(GlContext, DebugCallbackCountsErrorsAndNamesThePass) {
  auto ctx = GlContext::create();
  Profiler profiler(true);
  {
    auto s = profiler.scope("provoke");
    glBindBuffer(GL_ARRAY_BUFFER, 987654u);  // not a buffer name: GL_INVALID_OPERATION
  }
  EXPECT_GE(ctx->errorCount(), 1);
  EXPECT_GE(GlContext::processErrorCount(), 1);
  // Taken here, so the suite's listener (tests/gl_error_listener.cpp) does not fail this test.
  const std::vector<std::string> errors = GlContext::takeProcessErrors();
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].find("pass 'provoke'"), std::string::npos) << errors[0];
}

// The memory the stats report against what the process measurably uses (issue 32): growth since the
// baseline over the resources' bytes, on the GPU's own report where there is one.
TEST(GpuMemory, GrowthIsMeasuredAgainstTheReportedBytes) {
  nlohmann::json base = {{"rss_bytes", 100.0}, {"peak_rss_bytes", 120.0}};
  nlohmann::json now = {{"rss_bytes", 400.0}, {"peak_rss_bytes", 450.0}};
  nlohmann::json m = memoryAgainstResources(now, base, 150.0);
  EXPECT_EQ(m["growth_of"], "rss_bytes");
  EXPECT_EQ(m["growth_bytes"], 300.0);
  EXPECT_EQ(m["growth_over_reported"], 2.0);  // twice what the stats say
  EXPECT_EQ(m["baseline"], base);
  EXPECT_EQ(memoryAgainstResources(now, base, 0.0)["growth_over_reported"], kUndefined);
  // The method's own state counts beside the resources.
  const nlohmann::json withState = memoryAgainstResources(now, base, 100.0, 50.0);
  EXPECT_EQ(withState["reported_bytes"], 150.0);
  EXPECT_EQ(withState["method_bytes"], 50.0);
  EXPECT_EQ(withState["growth_over_reported"], 2.0);
  base["gpu_used_bytes"] = 1000.0;
  now["gpu_used_bytes"] = 1150.0;
  nlohmann::json g = memoryAgainstResources(now, base, 150.0);
  EXPECT_EQ(g["growth_of"], "gpu_used_bytes");
  EXPECT_EQ(g["growth_over_reported"], 1.0);
  // A real process: what it uses now is at least what it used at the start.
  std::unique_ptr<GlContext> gl = GlContext::create();
  nlohmann::json real = memoryAgainstResources(measuredMemory(true), measuredMemory(true), 1.0);
  EXPECT_GT(real["rss_bytes"].get<double>(), 0.0);
  EXPECT_TRUE(real.contains("growth_bytes"));
}

// The large storage buffers (the dense cone volume's sums, 2 GiB at 512³; the
// sparse octree's leaf sums, 166 MB at 1024³ on Sibenik) are checked against
// the GL memory budget, not against GL_MAX_SHADER_STORAGE_BLOCK_SIZE, which
// llvmpipe advertises as 128 MiB but does not enforce: a shader reads and
// writes the last word of a 160 MiB buffer, and length() sees all of it.
TEST(GlContext, StorageBuffersPastTheAdvertisedBlockSizeWork) {
  auto gl = GlContext::create();
  ShaderLibrary shaders;
  GLint64 advertised = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &advertised);
  const size_t bytes = std::max<size_t>(160u << 20, size_t(advertised) + (32u << 20));
  GlBuffer big = makeBuffer(bytes), out = makeBuffer(8);
  const unsigned prog = shaders.program({"../tests/data/shaders/ssbo_end_probe.comp.glsl"});
  glUseProgram(prog);
  shaders.setUniform(prog, "uLast", unsigned(bytes / 4 - 1));
  shaders.setUniform(prog, "uValue", 0x5eed1234u);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, big.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.get());
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  uint32_t got[2] = {0, 0}, last = 0;
  glGetNamedBufferSubData(out.get(), 0, 8, got);
  glGetNamedBufferSubData(big.get(), GLintptr(bytes - 4), 4, &last);
  EXPECT_EQ(got[0], 0x5eed1234u) << "advertised " << advertised;
  EXPECT_EQ(last, 0x5eed1234u);
  EXPECT_EQ(got[1], uint32_t(bytes / 4));
  EXPECT_EQ(gl->errorCount(), 0);
}

TEST(ShaderLibrary, CompileErrorsNameTheIncludedFileAndLine) {
  auto ctx = GlContext::create();
  namespace fs = std::filesystem;
  fs::path dir = fs::path(testing::TempDir()) / "shaders_line_test";
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "main.comp.glsl")
      << "layout(local_size_x = 1) in;\n#include \"sub/helper.glsl\"\nvoid main() { helper(); }\n";
  std::ofstream(dir / "sub/helper.glsl") << "// helper\n\nvoid helper() { undefined_symbol = 1; }\n";
  ShaderLibrary lib(dir.string());
  test::expectError([&] { lib.program({"main.comp.glsl"}); }, {"sub/helper.glsl:3", "undefined_symbol"});
  std::ofstream(dir / "sub/helper.glsl") << "void helper() {}\n";
  std::ofstream(dir / "missing.comp.glsl") << "#include \"nope.glsl\"\n";
  test::expectError([&] { lib.program({"missing.comp.glsl"}); }, {"missing.comp.glsl:1", "nope.glsl"});
  EXPECT_NE(lib.program({"main.comp.glsl"}, {{"FOO", "1"}}), 0u);
  EXPECT_EQ(lib.program({"main.comp.glsl"}, {{"FOO", "1"}}), lib.program({"main.comp.glsl"}, {{"FOO", "1"}}));
  EXPECT_EQ(ctx->errorCount(), 0);
}

// Includes: a path with a folder is rooted at the shader root, a bare name is the including file's
// neighbour (never a root file of the same name), "../" reaches the neighbours' folders.
TEST(ShaderLibrary, IncludePathsAreRootedAndBareNamesAreNeighbours) {
  namespace fs = std::filesystem;
  fs::path dir = fs::path(testing::TempDir()) / "shaders_rooted_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "a/b");
  fs::create_directories(dir / "c");
  std::ofstream(dir / "a/b/main.comp.glsl")
      << "#include \"c/x.glsl\"\n#include \"y.glsl\"\n#include \"../z.glsl\"\n";
  std::ofstream(dir / "c/x.glsl") << "int rootedX;\n";
  std::ofstream(dir / "a/b/y.glsl") << "int neighbourY;\n";
  std::ofstream(dir / "y.glsl") << "int rootY;\n";
  std::ofstream(dir / "a/z.glsl") << "int parentZ;\n";
  ShaderLibrary lib(dir.string());
  const std::string text = lib.preprocess("a/b/main.comp.glsl", {}).text;
  for (const char* kept : {"int rootedX;", "int neighbourY;", "int parentZ;"})
    EXPECT_NE(text.find(kept), std::string::npos) << kept << " missing from:\n" << text;
  EXPECT_EQ(text.find("rootY"), std::string::npos) << text;
  // A folder path is not looked up beside the including file.
  std::ofstream(dir / "a/b/bad.comp.glsl") << "#include \"b/y.glsl\"\n";
  test::expectError([&] { lib.preprocess("a/b/bad.comp.glsl", {}); }, {"bad.comp.glsl:1", "b/y.glsl"});
}

// `#ifdef __cplusplus` … `#else` … `#endif`: the C++ side is blanked, the
// GLSL side kept (it once vanished with the C++ side), nested #ifs included,
// and the line numbers stay those of the file.
TEST(ShaderLibrary, TheGlslSideOfACplusplusElseIsKept) {
  namespace fs = std::filesystem;
  fs::path dir = fs::path(testing::TempDir()) / "shaders_else_test";
  fs::create_directories(dir);
  std::ofstream(dir / "a.comp.glsl")
      << "#ifdef __cplusplus\n#include <cpp_only>\n#if 1\nint cpp;\n#endif\n#else\n"
         "#if 1\nint glslNested;\n#endif\nint glslSide;\n#endif\nint after;\n";
  ShaderLibrary lib(dir.string());
  const std::string text = lib.preprocess("a.comp.glsl", {}).text;
  for (const char* kept : {"int glslNested;", "int glslSide;", "int after;"})
    EXPECT_NE(text.find(kept), std::string::npos) << kept << " missing from:\n" << text;
  for (const char* gone : {"cpp_only", "int cpp;"}) EXPECT_EQ(text.find(gone), std::string::npos) << gone;
  // Lines keep their numbers: "int after;" is line 12 of the file.
  const std::string body = text.substr(text.find("#line 1 0\n") + 10);
  int line = 1;
  for (size_t i = 0; i < body.find("int after;"); ++i) line += body[i] == '\n';
  EXPECT_EQ(line, 12);
  std::ofstream(dir / "b.comp.glsl") << "#ifdef __cplusplus\nint a;\n#elif FOO\nint b;\n#endif\n";
  test::expectError([&] { lib.preprocess("b.comp.glsl", {}); }, {"b.comp.glsl:3", "#elif"});
}

TEST(Profiler, GpuPassesGetTimestampTimings) {
  auto ctx = GlContext::create();
  Profiler prof(true);
  for (int i = 0; i < 40; ++i) {  // more passes than the initial query pool
    auto s = prof.scope(i % 2 ? "odd" : "even");
    glFinish();
  }
  prof.resolve(true);
  auto t = prof.timingsMs();
  ASSERT_TRUE(t.contains("odd") && t.contains("even"));
  EXPECT_GE(t["odd"].get<double>(), 0.0);
  EXPECT_EQ(prof.callCounts()["even"], 20);
  EXPECT_EQ(ctx->errorCount(), 0);
}

// One compute shader runs the shared kernels on inputs the CPU also evaluates.
TEST(SharedKernels, GpuMatchesCpu) {
  auto ctx = GlContext::create();
  namespace fs = std::filesystem;
  fs::path dir = fs::path(testing::TempDir()) / "shaders_kernel_test";
  fs::create_directories(dir);
  fs::path shared = fs::path(defaultShaderDir()) / "shared";
  std::ofstream(dir / "k.comp.glsl") << "#include \"" << (shared / "constants.glsl").string() << "\"\n"
                                     << "#include \"" << (shared / "sampling.glsl").string() << "\"\n"
                                     << "#include \"" << (shared / "brdf.glsl").string() << "\"\n"
                                     << "#include \"" << (shared / "lights.glsl").string() << "\"\n"
                                     << R"(layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Out { uint hashes[]; };
layout(std430, binding = 1) buffer OutF { vec4 values[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  hashes[i] = pcgHash(i * 7919u);
  vec2 u = vec2(uintToUnitFloat(pcgHash(2u * i)), uintToUnitFloat(pcgHash(2u * i + 1u)));
  vec3 n = normalize(vec3(u.x - 0.5f, u.y - 0.5f, float(i % 3u) - 1.0f + 0.01f));
  vec3 d = basisToWorld(makeBasis(n), cosineSampleHemisphere(u));
  BrdfParams m;
  m.albedo = vec3(0.5f);
  m.ks = vec3(0.25f);
  m.exponent = 12.0f;
  vec3 f = evalBrdf(m, n, n, d);
  PackedLight L;
  L.positionType = vec4(0.0f, 2.0f, 0.0f, float(LIGHT_SPOT));
  L.directionCosCone = vec4(0.0f, -1.0f, 0.0f, 0.5f);
  L.intensityFalloff = vec4(1.0f, 2.0f, 3.0f, 2.0f);
  LightSample s = sampleDeltaLight(L, d);
  values[3u * i] = vec4(d, f.x);
  values[3u * i + 1u] = vec4(s.wi, s.dist);
  values[3u * i + 2u] = vec4(s.radiance, 0.0f);
})";
  ShaderLibrary lib(dir.string());
  GLuint prog = lib.program({"k.comp.glsl"});
  const unsigned N = 4096;
  GLuint bufs[2];
  glCreateBuffers(2, bufs);
  glNamedBufferStorage(bufs[0], N * 4, nullptr, 0);
  glNamedBufferStorage(bufs[1], N * 3 * 16, nullptr, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bufs[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bufs[1]);
  glUseProgram(prog);
  glDispatchCompute(N / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> hashes(N);
  std::vector<glm::vec4> values(3 * N);
  glGetNamedBufferSubData(bufs[0], 0, N * 4, hashes.data());
  glGetNamedBufferSubData(bufs[1], 0, N * 3 * 16, values.data());
  glDeleteBuffers(2, bufs);
  using namespace vgi::shared;
  double maxErr = 0;
  for (unsigned i = 0; i < N; ++i) {
    ASSERT_EQ(hashes[i], pcgHash(i * 7919u)) << "integer kernel must match bit for bit, i=" << i;
    glm::vec2 u(uintToUnitFloat(pcgHash(2u * i)), uintToUnitFloat(pcgHash(2u * i + 1u)));
    glm::vec3 n = glm::normalize(glm::vec3(u.x - 0.5f, u.y - 0.5f, float(i % 3u) - 1.0f + 0.01f));
    glm::vec3 d = basisToWorld(makeBasis(n), cosineSampleHemisphere(u));
    BrdfParams m;
    m.albedo = glm::vec3(0.5f);
    m.ks = glm::vec3(0.25f);
    m.exponent = 12.0f;
    float f = evalBrdf(m, n, n, d).x;
    PackedLight L;
    L.positionType = glm::vec4(0, 2, 0, float(LIGHT_SPOT));
    L.directionCosCone = glm::vec4(0, -1, 0, 0.5f);
    L.intensityFalloff = glm::vec4(1, 2, 3, 2);
    LightSample s = sampleDeltaLight(L, d);
    glm::vec4 cpu[3] = {glm::vec4(d, f), glm::vec4(s.wi, s.dist), glm::vec4(s.radiance, 0)};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 4; ++c) {
        double ref = cpu[k][c], gpu = values[3 * i + k][c];
        maxErr = std::max(maxErr, std::abs(gpu - ref) / std::max(1.0, std::abs(ref)));
      }
  }
  // Float kernels: GLSL's transcendental functions may differ in the last bits.
  EXPECT_LT(maxErr, 1e-4);
  EXPECT_EQ(ctx->errorCount(), 0);
}

}  // namespace vgi

namespace vgi {

// No shader takes `.length()` of a runtime-sized buffer array: zink on lavapipe answered 0 or another
// buffer's length there (vpl then placed no VPL and rendered direct light only, exit 0), and a length
// follows the bound range, which a driver may round. Counts come from the host (uLightCount).
TEST(Shaders, NoRuntimeArrayLengthInAnyShader) {
  int files = 0;
  for (auto& e : std::filesystem::recursive_directory_iterator(defaultShaderDir())) {
    if (!e.is_regular_file() || e.path().extension() != ".glsl") continue;
    ++files;
    std::ifstream in(e.path());
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      const std::string code = line.substr(0, line.find("//"));
      EXPECT_EQ(code.find(".length()"), std::string::npos) << e.path().string() << ":" << n << ": " << line;
    }
  }
  EXPECT_GT(files, 50);
}

// Shaders include by rooted paths ("shared/brdf.glsl"): only a file that also compiles as C++ (it has an
// `#ifdef __cplusplus` side, and C++ includes it by its own relative paths) uses "../".
TEST(Shaders, IncludesAreRootedOutsideFilesThatCompileAsCplusplus) {
  int files = 0;
  for (auto& e : std::filesystem::recursive_directory_iterator(defaultShaderDir())) {
    if (!e.is_regular_file() || e.path().extension() != ".glsl") continue;
    ++files;
    std::ifstream in(e.path());
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    if (text.find("#ifdef __cplusplus") != std::string::npos) continue;
    EXPECT_EQ(text.find("#include \"../"), std::string::npos)
        << e.path().string() << ": include by a path from the shader root (e.g. \"shared/brdf.glsl\")";
  }
  EXPECT_GT(files, 50);
}

}  // namespace vgi
