// vgi — the command line of the voxel GI framework.
//
// Exit status (the same for every subcommand):
//   0    done: every output was written
//   2    usage or input error (bad option, parameter, scene, image or path);
//        the message names the option/file and the value; nothing was written
//   3    internal error (a bug: please report it with the command line)
//   130  interrupted (Ctrl-C): what was complete was written and the stats say
//        how far it got (`interrupted`, `spp_completed`); a still interrupted
//        before its first full sample writes nothing
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "apps/commands.h"
#include "core/build_info.h"
#include "core/error.h"
#include "core/shader_library.h"
#include "voxelize/setup_cache.h"

namespace {

// Levenshtein distance, for "did you mean".
size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string closest(const std::string& word, const std::vector<std::string>& known) {
  std::string best;
  size_t bestD = std::max<size_t>(2, word.size() / 3) + 1;
  for (auto& k : known) {
    size_t d = editDistance(word, k);
    if (d < bestD) {
      bestD = d;
      best = k;
    }
  }
  return best;
}

// The subcommand argv names (`vgi bench motion`: motion), and the index of its first argument.
CLI::App* commandOf(CLI::App& app, int argc, char** argv, int& first) {
  CLI::App* cmd = &app;
  first = 1;
  while (first < argc) {
    CLI::App* sub = nullptr;
    for (CLI::App* s : cmd->get_subcommands([](CLI::App*) { return true; }))
      if (s->get_name() == argv[first]) sub = s;
    if (!sub) break;
    cmd = sub;
    ++first;
  }
  return cmd;
}

// The words that name it: "render", "bench motion".
std::string commandName(char** argv, int first) {
  std::string name;
  for (int i = 1; i < first; ++i) name += (i > 1 ? " " : "") + std::string(argv[i]);
  return name;
}

// Every spelling of every option of `cmd` ("--scene", "-o"), with its option.
std::vector<std::pair<std::string, const CLI::Option*>> optionWords(const CLI::App* cmd) {
  std::vector<std::pair<std::string, const CLI::Option*>> words;
  for (const CLI::Option* o : cmd->get_options()) {
    for (auto& l : o->get_lnames()) words.emplace_back("--" + l, o);
    for (auto& n : o->get_snames()) words.emplace_back("-" + n, o);
  }
  return words;
}

// The word a parse error is about, and the closest known option or command.
std::string suggestion(CLI::App& app, int argc, char** argv) {
  int first = 1;
  CLI::App* sub = commandOf(app, argc, argv, first);
  if (sub == &app) {
    if (argc < 2) return "";
    std::vector<std::string> commands;
    for (CLI::App* s : app.get_subcommands([](CLI::App*) { return true; })) commands.push_back(s->get_name());
    std::string c = closest(argv[1], commands);
    return c.empty() ? "" : " (did you mean 'vgi " + c + "'?)";
  }
  const std::string name = commandName(argv, first);
  std::vector<std::string> options;
  for (auto& [word, o] : optionWords(sub)) options.push_back(word);
  for (int i = first; i < argc; ++i) {
    std::string w = argv[i];
    if (w.size() < 2 || w[0] != '-') continue;
    w = w.substr(0, w.find('='));
    if (std::find(options.begin(), options.end(), w) != options.end()) continue;
    std::string c = closest(w, options);
    return " ('" + w + "' is not an option of 'vgi " + name + "'" +
           (c.empty() ? "" : "; did you mean '" + c + "'?") + " see vgi " + name + " --help)";
  }
  return "";
}

// An empty value ("--help-module=", "--scene ''", an empty positional argument). CLI11 reads
// "--opt=" as the option without a value and takes the next argument for it ("--spp= -o x.exr" became
// "--spp = -o"; "--help-module= --size 16x16" complained about 16x16), and "--opt ''" as not given: no
// option of vgi means anything by an empty value, so it is refused naming the option.
std::string emptyValue(CLI::App& app, int argc, char** argv) {
  int first = 1;
  CLI::App* cmd = commandOf(app, argc, argv, first);
  if (cmd == &app) return "";
  const std::string see = " (see vgi " + commandName(argv, first) + " --help)";
  const auto words = optionWords(cmd);
  for (int i = first; i < argc; ++i) {
    const std::string w = argv[i];
    if (w == "--") break;
    if (w.empty()) return "an empty argument (argument " + std::to_string(i) + " of the command line)" + see;
    if (w[0] != '-') continue;
    const size_t eq = w.find('=');
    const std::string name = w.substr(0, eq);
    const auto it = std::find_if(words.begin(), words.end(), [&](const auto& p) { return p.first == name; });
    if (it == words.end() || it->second->get_type_size_max() == 0) continue;  // not an option, or a flag
    if (eq != std::string::npos && eq + 1 == w.size()) return name + " was given an empty value" + see;
    if (eq == std::string::npos && i + 1 < argc && argv[i + 1][0] == 0)
      return name + " was given an empty value" + see;
    if (eq == std::string::npos) ++i;  // its value
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vgi: atlas-voxelized hierarchical ray-voxel global illumination framework"};
  app.require_subcommand(1);
  app.set_version_flag("--version", [] {
    return std::string("vgi ") + vgi::version() + " (" + vgi::gitRevision() + ")\nshaders " +
           vgi::defaultShaderDir();
  });
  vgi::app::addRenderCommand(app);
  vgi::app::addInfoCommand(app);
  vgi::app::addDiffCommand(app);
  vgi::app::addCompareCommand(app);
  vgi::app::addSweepCommand(app);
  vgi::app::addViewCommand(app);
  vgi::app::addVoxelizeCommand(app);
  vgi::app::addBenchCommand(app);
  if (const std::string empty = emptyValue(app, argc, argv); !empty.empty()) {
    std::fprintf(stderr, "vgi: error: %s\n", empty.c_str());
    return 2;
  }
  try {
    // vgi's own environment variables are checked before any command runs: one read as something else
    // (VGI_CACHE_LIMIT_MB=2GB was the default 2 GiB, without a word) is refused naming it.
    vgi::setupCacheLimit();
    vgi::defaultShaderDir();
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    std::fprintf(stderr, "vgi: error: %s%s\n", e.what(), suggestion(app, argc, argv).c_str());
    return 2;
  } catch (const vgi::app::Interrupted&) {
    return 130;
  } catch (const vgi::app::ExitCode& e) {
    return e.code;
  } catch (const vgi::Error& e) {
    std::fprintf(stderr, "vgi: error: %s\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path the checks did not foresee (the operating system refused it): still the user's path.
    std::fprintf(stderr, "vgi: error: '%s': %s\n", e.path1().string().c_str(), e.code().message().c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vgi: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
