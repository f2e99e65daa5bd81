// GLSL programs from files under the shader root, with `#include "file"` (each file once): a path
// with a folder is rooted at the shader root ("shared/brdf.glsl", "illum/gather/gather.glsl"), a bare
// name is the including file's neighbour, and only a file that also compiles as C++ (it is then
// included from C++ too, where a rooted path would not resolve) reaches its neighbours' folders with
// "../";
// injected `#define`s, and `#line` directives so compile errors name the real
// file and line. `#ifdef __cplusplus … #endif` blocks (the C++ side of
// shaders/shared/) are dropped. Programs are cached per (files, defines).
// With $VGI_SHADER_DUMP naming a folder, every stage of every program composed is also written
// there as the driver receives it (NAME.DIGEST.STAGE, e.g. illum_vpl_generate.1f2e….comp), for the
// reference compiler (glslangValidator; tests/core/glslang_test.cpp) or a vendor's.
#pragma once
#include <glm/glm.hpp>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace vgi {

using ShaderDefines = std::map<std::string, std::string>;

// Where the shaders are read from at run time, first that exists:
// $VGI_SHADER_DIR; ../share/vgi/shaders beside the running executable (an
// installed vgi, or a consumer installed into the same prefix); the source
// tree's shaders/ baked in at build time; the install prefix's share/vgi/shaders.
// With none present: $VGI_SHADER_DIR or the source tree (ShaderLibrary then
// names it in its error).
std::string defaultShaderDir();

class ShaderLibrary {
 public:
  explicit ShaderLibrary(std::string root = defaultShaderDir());
  ~ShaderLibrary();
  ShaderLibrary(const ShaderLibrary&) = delete;
  ShaderLibrary& operator=(const ShaderLibrary&) = delete;

  // files: paths relative to the root; the stage comes from the name
  // (.vert/.frag/.geom/.comp before .glsl). Throws vgi::Error on failure.
  unsigned program(const std::vector<std::string>& files, const ShaderDefines& defines = {});

  // The expanded source and the file names by GLSL source-string number.
  struct Source {
    std::string text;
    std::vector<std::string> files;
  };
  Source preprocess(const std::string& file, const ShaderDefines& defines) const;

  // Checked uniform setters (glProgramUniform*) for a program this library
  // made. A name no file of the program declares (a typo) is an error naming
  // the program's files and the uniform — GL itself would return location −1
  // and ignore the call. A declared uniform the compiler dropped (unused under
  // these defines) is skipped, as GL would.
  void setUniform(unsigned program, const std::string& name, int v);
  void setUniform(unsigned program, const std::string& name, unsigned v);
  void setUniform(unsigned program, const std::string& name, float v);
  void setUniform(unsigned program, const std::string& name, glm::vec2 v);
  void setUniform(unsigned program, const std::string& name, glm::vec3 v);
  void setUniform(unsigned program, const std::string& name, glm::vec4 v);
  void setUniform(unsigned program, const std::string& name, glm::ivec2 v);
  void setUniform(unsigned program, const std::string& name, glm::uvec2 v);
  void setUniform(unsigned program, const std::string& name, glm::ivec3 v);
  void setUniform(unsigned program, const std::string& name, glm::uvec3 v);
  void setUniform(unsigned program, const std::string& name, glm::uvec4 v);
  void setUniform(unsigned program, const std::string& name, const glm::mat4& v);
  // An array uniform `uint name[count]` (its first `count` elements).
  void setUniformArray(unsigned program, const std::string& name, const uint32_t* v, int count);
  void setUniformArray(unsigned program, const std::string& name, const glm::vec4* v, int count);
  // The location, with the check above (−1 for a dropped one).
  int uniformLocation(unsigned program, const std::string& name);
  // The uniform names a GLSL source declares (`uniform T a, b[2];`, blocks excluded).
  static std::set<std::string> declaredUniforms(const std::string& source);

  // Throws if two resources the linked program uses (storage or uniform
  // buffers, textures, images) share a unit, or a unit exceeds this GL's
  // limits — from GL's introspection, so every program the library makes is
  // checked against the binding table's promise (shaders/shared/bindings.glsl).
  static void checkBindings(unsigned program, const std::string& files);

  // Rewrites the "N:L(C)" / "N(L)" prefixes of a driver log into "file:line".
  static std::string mapLog(const std::string& log, const std::vector<std::string>& files);

 private:
  void dump(const std::string& file, const std::string& key, const Source& src) const;
  std::string root_, dumpDir_;
  std::map<std::string, unsigned> cache_;
  struct ProgramInfo {
    std::string files;
    std::set<std::string> declared;
    std::map<std::string, int> locations;
  };
  std::map<unsigned, ProgramInfo> info_;
};

}  // namespace vgi
