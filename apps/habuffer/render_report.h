/// @file
/// What `habuffer render` reports: the stats JSON (SPEC counters, timings,
/// memory, load, table, max age, one entry per frame) and the three-line
/// summary it prints. Private to the CLI.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "habuffer/render/image.h"
#include "habuffer/render/render_job.h"
#include "habuffer/render/shadow_accuracy.h"

namespace habuffer::cli {

/// The scene as the report names it.
struct SceneDescription {
  std::string name;              ///< scene name, mesh file or fragment stream
  std::size_t meshes = 0;        ///< meshes in the scene
  std::uint64_t triangles = 0;   ///< triangles of every mesh
};

/// One heat map written.
struct HeatmapOutput {
  std::string kind, path;  ///< "depth", "age" or "culled"; the file written
  double max = 0.0;        ///< the largest value (write_heatmap's range.max)
};

/// The files a render wrote (empty: not asked for) and the comparisons made.
struct RenderOutputs {
  std::string image, stats, reference;   ///< --out, --stats, --reference paths
  std::vector<HeatmapOutput> heatmaps;   ///< in the order asked for
  std::optional<ImageDifference> reference_difference;  ///< the image against the reference (8-bit files)
  /// The float image against the exact reference (--error, --reference).
  std::optional<ImageDifference> error;
  /// --shadow-error: the light buffer's T against the ray-traced reference.
  std::optional<ShadowAccuracy> shadow_error;
};

/// Everything the stats and the summary say; the pointers are borrowed from summarize_render's
/// arguments, which must outlive it.
struct RenderSummary {
  SceneDescription scene;                    ///< what was rendered
  const RenderSettings* settings = nullptr;  ///< borrowed
  const RenderResult* result = nullptr;      ///< borrowed
  const RenderOutputs* outputs = nullptr;    ///< borrowed
  std::uint32_t max_depth_complexity = 0;    ///< the last frame's most fragments in one pixel
  double mean_depth_complexity = 0.0;  ///< over pixels with at least one fragment
  std::uint64_t covered_pixels = 0;    ///< pixels with at least one fragment
};

/// The summary of one render (result.frames must not be empty).
RenderSummary summarize_render(const SceneDescription& scene, const RenderSettings& settings, const RenderResult& result,
                               const RenderOutputs& outputs);
/// Writes the stats JSON to `path` (whole or not at all); throws DataError.
void write_render_stats(const std::string& path, const RenderSummary& summary);
/// Prints the summary lines on stdout.
void print_render_summary(const RenderSummary& summary, const RenderOutputs& outputs);

}  // namespace habuffer::cli
