// What a render writes, and under which names: <stem>.exr/.png/.json, an AOV's <stem>.<aov>.exr/.png,
// a checkpoint's <stem>.sppNNNNN.*, an animation frame's <stem>_NNNN.* (the render itself:
// illum/run/render_job.h).
#pragma once
#include <string>
#include <vector>

#include "illum/run/render_job.h"

namespace vgi {

// The names the render outputs below take: <stem>.sppNNNNN (a checkpoint), <stem>_NNNN (a frame).
std::string checkpointStem(const std::string& stem, int spp);
std::string frameStem(const std::string& stem, int frame);
// Every file a render with options `o` writes for output path `path` (images, AOVs, checkpoints,
// frames, the stats JSON — first): what another output of the same command must not be.
std::vector<std::string> renderOutputNames(const std::string& path, const RenderOptions& o);

// Writes <stem>.exr, <stem>.png and <stem>.json (stats) for output path `path`
// (.exr or .png), and <stem>.<aov>.exr/.png per extra output; returns the files written.
std::vector<std::string> writeRenderOutputs(const RenderOutput& out, const std::string& path, float exposure);
// A checkpoint of a still: <stem>.sppNNNNN.exr/.png/.json (+ outputs); returns the files written.
std::vector<std::string> writeCheckpointOutputs(const RenderOutput& out, const std::string& path, int spp,
                                                float exposure);
// An animation's frame: <stem>_NNNN.exr/.png and <stem>_NNNN.<aov>.exr/.png (no JSON);
// returns the files written.
std::vector<std::string> writeFrameImages(const RenderOutput& out, const std::string& path, int frame,
                                          float exposure);
// The stats JSON <stem>.json of an animation, listing `files`; returns its path.
std::string writeAnimationStats(const RenderOutput& out, const std::string& path,
                                const std::vector<std::string>& files, float exposure);

// Throws if `path` cannot be written (bad extension, see core/output_files.h) —
// checked before a long render, so nothing is lost at the end.
void checkOutputPath(const std::string& path);

}  // namespace vgi
