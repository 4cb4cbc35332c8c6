/// @file
/// Stats JSON of one build (keys of the core issue), for every command that builds,
/// so build-lists, demo and the GL path write the same keys.
#pragma once

#include <string>

#include "habuffer/build_report.h"
#include "habuffer/json_writer.h"
#include "hash_options.h"

namespace habuffer::cli {

/// What a build measured besides the buffer's own counts.
struct BuildTiming {
  double build_ms = 0.0;  ///< insertion of all attempts, including tile binning
  std::uint32_t threads = 1;  ///< CPU threads the insertion ran on
  std::string insert_order = "arrival";  ///< the CPU path's HA-buffer: the order used (auto resolved)
  std::string gl_atomic_mode;  ///< --path gl: the mode that ran, and the renderer
  std::string gl_renderer;     ///< --path gl: GL_RENDERER
  std::uint64_t gl_deferred = 0;         ///< insert calls cut short and resumed (summed over rounds)
  std::uint32_t gl_resume_rounds = 0;      ///< --path gl: passes that resumed deferred calls
  std::uint32_t gl_cut_short_retries = 0;  ///< --path gl: gathers retried because calls were cut short
  std::string vk_atomic_mode;  ///< --path vk: the mode that ran, and the device
  std::string vk_device;       ///< --path vk: the device's name
  std::uint64_t vk_ended_by_driver = 0;  ///< --path vk: insert calls the driver ended without an outcome
  std::uint64_t vk_deferred = 0;         ///< --path vk: insert calls cut short and resumed (emulated64)
  std::uint32_t vk_resume_rounds = 0;    ///< --path vk: resume passes
};

/// "key": [x, y], the stats files' form of a size.
void write_extent(JsonWriter& json, std::string_view key, Extent e);
// "fragments", "stored" and every counter of kCounterFields.
void write_counters(JsonWriter& json, const Counters& c);
// The technique's configuration fields (technique_report_fields).
void write_technique_fields(JsonWriter& json, const TechniqueConfig& config, std::uint64_t capacity);

/// Writes the body of the stats object (the caller opens and closes it).
void write_build_stats(JsonWriter& json, const HashOptions& options, const FragmentBuffer& buffer,
                       const std::vector<BuildAttempt>& attempts, const BuildReport& report, const BuildTiming& timing);

}  // namespace habuffer::cli
