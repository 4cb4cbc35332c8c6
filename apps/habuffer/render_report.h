// What `habuffer render` reports: the stats JSON (SPEC counters, timings,
// memory, load, table, max age, one entry per frame) and the three-line
// summary it prints.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "habuffer/render/image.h"
#include "habuffer/render/render_job.h"

namespace habuffer::cli {

struct SceneDescription {
  std::string name;
  std::size_t meshes = 0;
  std::uint64_t triangles = 0;
};

struct HeatmapOutput {
  std::string kind, path;
  double max = 0.0;
};

struct RenderOutputs {
  std::string image, stats, reference;
  std::vector<HeatmapOutput> heatmaps;
  std::optional<ImageDifference> reference_difference;  // the image against the reference (8-bit files)
  std::optional<ImageDifference> error;                 // the float image against the exact reference (--error, --reference)
};

struct RenderSummary {
  SceneDescription scene;
  const RenderSettings* settings = nullptr;
  const RenderResult* result = nullptr;
  const RenderOutputs* outputs = nullptr;
  std::uint32_t max_depth_complexity = 0;
  double mean_depth_complexity = 0.0;  // over pixels with at least one fragment
  std::uint64_t covered_pixels = 0;
};

RenderSummary summarize_render(const SceneDescription& scene, const RenderSettings& settings, const RenderResult& result,
                               const RenderOutputs& outputs);
void write_render_stats(const std::string& path, const RenderSummary& summary);
void print_render_summary(const RenderSummary& summary, const RenderOutputs& outputs);

}  // namespace habuffer::cli
