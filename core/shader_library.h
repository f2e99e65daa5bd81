// GLSL programs from files under the shader root, with `#include "file"`
// (relative to the including file, then to the root; each file once),
// injected `#define`s, and `#line` directives so compile errors name the real
// file and line. `#ifdef __cplusplus … #endif` blocks (the C++ side of
// shaders/shared/) are dropped. Programs are cached per (files, defines).
#pragma once
#include <map>
#include <string>
#include <vector>

namespace vgi {

using ShaderDefines = std::map<std::string, std::string>;

// $VGI_SHADER_DIR, else the source tree's shaders/ folder baked in at build time.
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

  // Rewrites the "N:L(C)" / "N(L)" prefixes of a driver log into "file:line".
  static std::string mapLog(const std::string& log, const std::vector<std::string>& files);

 private:
  std::string root_;
  std::map<std::string, unsigned> cache_;
};

}  // namespace vgi
