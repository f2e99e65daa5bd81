#include "core/shader_library.h"

#include <glad/gl.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "core/error.h"
#include "core/hash.h"

namespace fs = std::filesystem;

namespace vgi {

std::string defaultShaderDir() {
  std::error_code ec;
  if (const char* env = std::getenv("VGI_SHADER_DIR")) {
    // A folder that is not vgi's shaders would fail at the first program with a missing include.
    if (!fs::is_directory(fs::path(env) / "shared", ec))
      fail("VGI_SHADER_DIR '", env,
           "': not a folder of vgi's shaders (it has no shared/; unset, vgi finds its own: vgi --version)");
    return env;
  }
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path beside = exe.parent_path().parent_path() / VGI_SHADER_DIR_RELATIVE;
    if (fs::is_directory(beside / "shared", ec)) return beside.string();
  }
  for (const char* dir : {VGI_SHADER_DIR_DEFAULT, VGI_SHADER_DIR_INSTALLED})
    if (fs::is_directory(fs::path(dir) / "shared", ec)) return dir;
  return VGI_SHADER_DIR_DEFAULT;
}

ShaderLibrary::ShaderLibrary(std::string root) : root_(std::move(root)) {
  if (!fs::is_directory(root_))
    fail("shader folder '", root_, "' does not exist (set VGI_SHADER_DIR to the project's shaders/ folder)");
  if (const char* dir = std::getenv("VGI_SHADER_DUMP")) {
    std::error_code ec;
    if (*dir && !fs::create_directories(dir, ec) && !fs::is_directory(dir))
      fail("VGI_SHADER_DUMP '", dir, "': cannot create that folder (", ec.message(), ")");
    dumpDir_ = dir;
  }
}

void ShaderLibrary::dump(const std::string& file, const std::string& key, const Source& src) const {
  if (dumpDir_.empty()) return;
  std::string name = file.substr(0, file.find(".glsl"));
  const size_t dot = name.find_last_of('.');
  const std::string stage = dot == std::string::npos ? "glsl" : name.substr(dot + 1);
  name = name.substr(0, dot);
  for (char& c : name)
    if (c == '/' || c == '\\') c = '_';
  // The program key's digest: one file per permutation, the stages of one program alike.
  const std::string path = dumpDir_ + "/" + name + "." + hexDigest(fnv1a(key)) + "." + stage;
  std::ofstream out(path);
  // The last line names the source strings: a message's line N is in file N / 100000, line N % 100000.
  out << src.text << "// source strings:";
  for (size_t i = 0; i < src.files.size(); ++i) out << " " << i << "=" << src.files[i];
  out << "\n";
  if (!out) fail("VGI_SHADER_DUMP: cannot write '", path, "'");
}

ShaderLibrary::~ShaderLibrary() {
  for (auto& [k, p] : cache_) glDeleteProgram(p);
}

namespace {
// Mesa ignores the source-string number of `#line` in its messages, so the file
// index also goes into the line number: line = index · kLinesPerFile + line.
constexpr long kLinesPerFile = 100000;
std::string lineDirective(int index, int line) {
  return std::to_string(index * kLinesPerFile + line) + " " + std::to_string(index);
}

struct Expander {
  std::string root;
  std::vector<std::string> files;
  std::set<std::string> included;
  std::ostringstream out;

  // A bare name or a "../" path: beside the including file; any other path: from the root.
  std::string resolve(const std::string& name, const std::string& from) {
    const bool relative = name.find('/') == std::string::npos || name.rfind("../", 0) == 0;
    const fs::path p = relative ? fs::path(from).parent_path() / name : fs::path(root) / name;
    return fs::exists(p) ? fs::weakly_canonical(p).string() : "";
  }

  void expand(const std::string& path, const std::string& includedFrom) {
    std::ifstream in(path);
    if (!in)
      fail("shader '", path, "' not found",
           includedFrom.empty() ? "" : " (included from " + includedFrom + ")");
    included.insert(path);
    int index = int(files.size());
    files.push_back(fs::relative(path, root).string());
    out << "#line " << lineDirective(index, 1) << "\n";
    static const std::regex includeRe(R"(^\s*#\s*include\s+\"([^\"]+)\"\s*$)");
    std::string line;
    // `#ifdef __cplusplus` … [`#else` …] `#endif`: the C++ branch becomes blank
    // lines (line numbers kept), the `#else` branch is GLSL and stays.
    // cppDepth > 0: inside the C++ branch, at that #if nesting depth;
    // glslDepth > 0: inside the GLSL (#else) branch, whose #endif is dropped.
    int lineNo = 0, cppDepth = 0, glslDepth = 0;
    while (std::getline(in, line)) {
      ++lineNo;
      std::string t = line.substr(
          line.find_first_not_of(" \t") == std::string::npos ? line.size() : line.find_first_not_of(" \t"));
      const bool opens = t.rfind("#if", 0) == 0, closes = t.rfind("#endif", 0) == 0;
      if (cppDepth > 0) {
        if (opens)
          ++cppDepth;
        else if (closes)
          --cppDepth;
        else if (cppDepth == 1 && t.rfind("#elif", 0) == 0)
          fail(files[index], ":", lineNo, ": #elif after #ifdef __cplusplus is not supported (use #else)");
        else if (cppDepth == 1 && t.rfind("#else", 0) == 0) {
          cppDepth = 0;
          glslDepth = 1;
        }
        out << "\n";
        continue;
      }
      if (glslDepth > 0) {
        if (opens)
          ++glslDepth;
        else if (closes && --glslDepth == 0) {
          out << "\n";
          continue;
        }
      }
      if (t.rfind("#ifdef __cplusplus", 0) == 0) {
        if (glslDepth > 0)
          fail(files[index], ":", lineNo, ": nested #ifdef __cplusplus inside its own #else");
        cppDepth = 1;
        out << "\n";
        continue;
      }
      std::smatch m;
      if (std::regex_match(line, m, includeRe)) {
        std::string target = resolve(m[1], path);
        if (target.empty()) fail(files[index], ":", lineNo, ": cannot find include \"", m[1].str(), "\"");
        if (!included.count(target)) expand(target, files[index] + ":" + std::to_string(lineNo));
        out << "#line " << lineDirective(index, lineNo + 1) << "\n";
        continue;
      }
      if (t.rfind("#version", 0) == 0) {
        out << "\n";  // the library writes the one #version line
        continue;
      }
      out << line << "\n";
    }
  }
};

GLenum stageOf(const std::string& file) {
  if (file.find(".vert") != std::string::npos) return GL_VERTEX_SHADER;
  if (file.find(".frag") != std::string::npos) return GL_FRAGMENT_SHADER;
  if (file.find(".geom") != std::string::npos) return GL_GEOMETRY_SHADER;
  if (file.find(".comp") != std::string::npos) return GL_COMPUTE_SHADER;
  fail("shader '", file, "': cannot tell the stage from the name (.vert/.frag/.geom/.comp)");
}
}  // namespace

ShaderLibrary::Source ShaderLibrary::preprocess(const std::string& file, const ShaderDefines& defines) const {
  Expander e;
  e.root = fs::weakly_canonical(root_).string();
  e.out << "#version 450 core\n#define SHARED_BEGIN\n#define SHARED_END\n#define SHARED_FN\n"
           "#define SHARED_PRECISE precise\n#define SHARED_IN(T) T\n#define PYRAMID_PARAM\n#define "
           "PYRAMID_ARG\n#define BVH_PARAM\n#define BVH_ARG\n#define TRACE_FETCHES(n, nbytes)\n"
           "#define TRACE_CLIMB()\n#define TRACE_REFINE()\n";
  for (auto& [k, v] : defines) e.out << "#define " << k << " " << v << "\n";
  e.expand(fs::weakly_canonical(fs::path(root_) / file).string(), "");
  return {e.out.str(), e.files};
}

std::string ShaderLibrary::mapLog(const std::string& log, const std::vector<std::string>& files) {
  // Mesa: "0:12(5): error: …"; NVIDIA: "0(12) : error C…". The line carries the file index.
  static const std::regex mesaRe(R"(^(\d+):(\d+)\((\d+)\))");
  static const std::regex nvRe(R"(^(\d+)\((\d+)\))");
  std::istringstream in(log);
  std::ostringstream out;
  std::string line;
  auto where = [&](const std::string& encoded) {
    long v = std::stol(encoded);
    size_t i = size_t(v / kLinesPerFile);
    std::string name = i < files.size() ? files[i] : "source " + std::to_string(i);
    return name + ":" + std::to_string(v % kLinesPerFile);
  };
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, mesaRe))
      line = where(m[2]) + ":" + m[3].str() + m.suffix().str();
    else if (std::regex_search(line, m, nvRe))
      line = where(m[2]) + m.suffix().str();
    out << line << "\n";
  }
  return out.str();
}

unsigned ShaderLibrary::program(const std::vector<std::string>& files, const ShaderDefines& defines) {
  std::string key;
  for (auto& f : files) key += f + ";";
  for (auto& [k, v] : defines) key += k + "=" + v + ";";
  auto it = cache_.find(key);
  if (it != cache_.end()) return it->second;

  GLuint prog = glCreateProgram();
  ProgramInfo info;
  for (auto& f : files) info.files += (info.files.empty() ? "" : " + ") + f;
  std::vector<GLuint> shaders;
  auto cleanup = [&] {
    for (GLuint s : shaders) glDeleteShader(s);
    glDeleteProgram(prog);
  };
  for (auto& f : files) {
    GLenum stage;
    Source src;
    try {
      stage = stageOf(f);
      src = preprocess(f, defines);
    } catch (...) {
      cleanup();
      throw;
    }
    for (auto& u : declaredUniforms(src.text)) info.declared.insert(u);
    dump(f, key, src);
    GLuint s = glCreateShader(stage);
    shaders.push_back(s);
    const char* text = src.text.c_str();
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      GLint len = 0;
      glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
      std::string log(size_t(std::max(len, 1)), '\0');
      glGetShaderInfoLog(s, len, nullptr, log.data());
      cleanup();
      fail("compiling shader '", f, "' failed:\n", mapLog(log, src.files));
    }
    glAttachShader(prog, s);
  }
  glLinkProgram(prog);
  GLint ok = 0;
  glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(prog, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(std::max(len, 1)), '\0');
    glGetProgramInfoLog(prog, len, nullptr, log.data());
    cleanup();
    fail("linking program (", key, ") failed:\n", log);
  }
  for (GLuint s : shaders) {
    glDetachShader(prog, s);
    glDeleteShader(s);
  }
  try {
    checkBindings(prog, info.files);
  } catch (...) {
    glDeleteProgram(prog);
    throw;
  }
  cache_[key] = prog;
  info_[prog] = std::move(info);
  return prog;
}

namespace {
bool isImageType(GLint t) {
  switch (t) {
    case GL_IMAGE_2D:
    case GL_IMAGE_3D:
    case GL_IMAGE_2D_ARRAY:
    case GL_IMAGE_CUBE:
    case GL_INT_IMAGE_2D:
    case GL_INT_IMAGE_3D:
    case GL_UNSIGNED_INT_IMAGE_2D:
    case GL_UNSIGNED_INT_IMAGE_3D:
    case GL_UNSIGNED_INT_IMAGE_2D_ARRAY:
    case GL_INT_IMAGE_2D_ARRAY:
      return true;
    default:
      return false;
  }
}
bool isSamplerType(GLint t) {
  switch (t) {
    case GL_SAMPLER_1D:
    case GL_SAMPLER_2D:
    case GL_SAMPLER_3D:
    case GL_SAMPLER_CUBE:
    case GL_SAMPLER_2D_ARRAY:
    case GL_SAMPLER_2D_SHADOW:
    case GL_SAMPLER_2D_ARRAY_SHADOW:
    case GL_INT_SAMPLER_2D:
    case GL_INT_SAMPLER_3D:
    case GL_UNSIGNED_INT_SAMPLER_2D:
    case GL_UNSIGNED_INT_SAMPLER_3D:
    case GL_INT_SAMPLER_2D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY:
    case GL_SAMPLER_BUFFER:
      return true;
    default:
      return false;
  }
}
}  // namespace

void ShaderLibrary::checkBindings(unsigned prog, const std::string& files) {
  // kind → unit → the resource's name; GL's own introspection of what the program uses.
  std::map<std::string, std::map<int, std::string>> used;
  GLint maxSsbo = 0, maxTex = 0, maxImage = 0, maxUbo = 0;
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &maxSsbo);
  glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &maxTex);
  glGetIntegerv(GL_MAX_IMAGE_UNITS, &maxImage);
  glGetIntegerv(GL_MAX_UNIFORM_BUFFER_BINDINGS, &maxUbo);
  auto add = [&](const std::string& kind, int unit, int limit, const std::string& name) {
    if (unit < 0 || unit >= limit)
      fail("program (", files, "): ", kind, " '", name, "' is bound to unit ", unit,
           ", outside this GL's 0..", limit - 1);
    auto [it, fresh] = used[kind].emplace(unit, name);
    if (!fresh)
      fail("program (", files, ") binds ", kind, "s '", it->second, "' and '", name, "' to the same unit ",
           unit, " (shaders/shared/bindings.glsl lists the units)");
  };
  auto nameOf = [&](GLenum iface, GLuint i) {
    char name[256] = {0};
    glGetProgramResourceName(prog, iface, i, sizeof name, nullptr, name);
    return std::string(name);
  };
  using Interface = std::tuple<GLenum, const char*, GLint>;
  for (auto [iface, kind, limit] : {Interface{GL_SHADER_STORAGE_BLOCK, "storage buffer", maxSsbo},
                                    Interface{GL_UNIFORM_BLOCK, "uniform buffer", maxUbo}}) {
    GLint n = 0;
    glGetProgramInterfaceiv(prog, iface, GL_ACTIVE_RESOURCES, &n);
    for (GLint i = 0; i < n; ++i) {
      const GLenum prop = GL_BUFFER_BINDING;
      GLint binding = -1;
      glGetProgramResourceiv(prog, iface, GLuint(i), 1, &prop, 1, nullptr, &binding);
      add(kind, binding, limit, nameOf(iface, GLuint(i)));
    }
  }
  GLint n = 0;
  glGetProgramInterfaceiv(prog, GL_UNIFORM, GL_ACTIVE_RESOURCES, &n);
  for (GLint i = 0; i < n; ++i) {
    const GLenum props[2] = {GL_TYPE, GL_LOCATION};
    GLint v[2] = {0, -1};
    glGetProgramResourceiv(prog, GL_UNIFORM, GLuint(i), 2, props, 2, nullptr, v);
    const bool image = isImageType(v[0]), sampler = isSamplerType(v[0]);
    if ((!image && !sampler) || v[1] < 0) continue;
    GLint unit = -1;
    glGetUniformiv(prog, v[1], &unit);
    add(image ? "image" : "texture", unit, image ? maxImage : maxTex, nameOf(GL_UNIFORM, GLuint(i)));
  }
}

std::set<std::string> ShaderLibrary::declaredUniforms(const std::string& source) {
  // Comments out, then every `uniform …;` that is not a block (`uniform Name {`).
  static const std::regex comments(R"(//[^\n]*|/\*[\s\S]*?\*/)");
  static const std::regex decl(R"(\buniform\b([^;{]*);)");
  static const std::regex ident(R"(([A-Za-z_]\w*)\s*(\[[^\]]*\]\s*)?$)");
  const std::string text = std::regex_replace(source, comments, " ");
  std::set<std::string> names;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), decl); it != std::sregex_iterator(); ++it) {
    std::string body = (*it)[1].str();
    size_t start = 0;
    while (start <= body.size()) {
      size_t comma = body.find(',', start);
      std::string part = body.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      while (!part.empty() && std::isspace(static_cast<unsigned char>(part.back()))) part.pop_back();
      std::smatch m;
      if (std::regex_search(part, m, ident)) names.insert(m[1].str());
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  return names;
}

int ShaderLibrary::uniformLocation(unsigned program, const std::string& name) {
  auto it = info_.find(program);
  if (it == info_.end()) fail("internal: program ", program, " was not made by this shader library");
  ProgramInfo& p = it->second;
  auto loc = p.locations.find(name);
  if (loc != p.locations.end()) return loc->second;
  if (!p.declared.count(name))
    fail("program (", p.files, ") declares no uniform '", name,
         "': a misspelt name or a uniform removed from the shader");
  const int l = glGetUniformLocation(program, name.c_str());
  p.locations[name] = l;
  return l;
}

void ShaderLibrary::setUniform(unsigned p, const std::string& n, int v) {
  glProgramUniform1i(p, uniformLocation(p, n), v);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, unsigned v) {
  glProgramUniform1ui(p, uniformLocation(p, n), v);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, float v) {
  glProgramUniform1f(p, uniformLocation(p, n), v);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, glm::vec2 v) {
  glProgramUniform2f(p, uniformLocation(p, n), v.x, v.y);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, glm::vec3 v) {
  glProgramUniform3f(p, uniformLocation(p, n), v.x, v.y, v.z);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, glm::vec4 v) {
  glProgramUniform4f(p, uniformLocation(p, n), v.x, v.y, v.z, v.w);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, glm::ivec2 v) {
  glProgramUniform2i(p, uniformLocation(p, n), v.x, v.y);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, glm::uvec2 v) {
  glProgramUniform2ui(p, uniformLocation(p, n), v.x, v.y);
}
void ShaderLibrary::setUniformArray(unsigned p, const std::string& n, const uint32_t* v, int count) {
  glProgramUniform1uiv(p, uniformLocation(p, n), count, v);
}
void ShaderLibrary::setUniformArray(unsigned p, const std::string& n, const glm::vec4* v, int count) {
  glProgramUniform4fv(p, uniformLocation(p, n), count, &v[0].x);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, glm::ivec3 v) {
  glProgramUniform3i(p, uniformLocation(p, n), v.x, v.y, v.z);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, glm::uvec3 v) {
  glProgramUniform3ui(p, uniformLocation(p, n), v.x, v.y, v.z);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, glm::uvec4 v) {
  glProgramUniform4ui(p, uniformLocation(p, n), v.x, v.y, v.z, v.w);
}
void ShaderLibrary::setUniform(unsigned p, const std::string& n, const glm::mat4& v) {
  glProgramUniformMatrix4fv(p, uniformLocation(p, n), 1, GL_FALSE, &v[0][0]);
}

}  // namespace vgi
