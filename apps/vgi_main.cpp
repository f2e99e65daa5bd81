// vgi — the command line of the voxel GI framework.
#include <cstdio>
#include <exception>

#include "apps/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"vgi: atlas-voxelized hierarchical ray-voxel global illumination framework"};
  app.require_subcommand(1);
  vgi::app::addRenderCommand(app);
  vgi::app::addInfoCommand(app);
  vgi::app::addDiffCommand(app);
  vgi::app::addCompareCommand(app);
  vgi::app::addVoxelizeCommand(app);
  vgi::app::addBenchCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const vgi::Error& e) {
    std::fprintf(stderr, "vgi: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vgi: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
