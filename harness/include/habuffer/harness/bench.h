/// @file
/// `habuffer bench`: techniques x scenes x sizes in one run, repetitions
/// interleaved (every combination once per round, round after round) so the
/// machine's drift hits all alike, the two floors measured in every round
/// beside them, and each image measured against the exact reference. One row
/// per combination: seed 000's Table 2, seed 001's and seed 002's Table 1 on
/// our scenes.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "habuffer/harness/result_table.h"
#include "habuffer/harness/technique_spec.h"
#include "habuffer/harness/workload.h"

namespace habuffer::harness {

/// What `habuffer bench` runs (validate_bench checks it).
struct BenchSettings {
  RenderPath path = RenderPath::Gl;      ///< GPU or CPU path
  std::vector<WorkloadSpec> scenes;      ///< at least one
  std::vector<TechniqueSpec> techniques; ///< at least one
  std::vector<Extent> sizes;             ///< screens, pixels; at least one
  std::uint32_t repeats = 3;             ///< rounds (at least 1)
  std::uint32_t threads = 0;  ///< CPU path
  InsertOrder insert_order = InsertOrder::Auto;  ///< CPU path, the HA-buffer
  std::uint64_t seed = 1;     ///< the HA-buffer's offsets
  bool floors = true;  ///< measure the two floors in every round
  /// Add the GPU traffic model's columns (model_*, habuffer/harness/gpu_model.h)
  /// to the rows of the techniques it covers: the frame replayed through the
  /// technique's traced kernel in the configuration the bench ran, once
  /// (the rows' replays in parallel, fork_join).
  bool model_gpu = false;
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;  ///< (runs done, runs)
  /// Receives each warning (one line, no newline): a scene that puts no
  /// transparent fragment on the screen, whose rows time an empty pass.
  /// Unset: "habuffer bench: warning: ..." on stderr. Kept in the table's
  /// notes ("warnings") either way.
  std::function<void(const std::string&)> on_warning;
};

/// Throws std::invalid_argument for empty lists, zero repeats, or a
/// technique the path cannot render (wboit and blend on GL).
void validate_bench(const BenchSettings& s);
/// Whether technique `t` runs on workload `w`: everywhere, but on a
/// multisampled scene neither a technique storing no lists (wboit, blend: no
/// masks to keep) nor early cull (its opacity is a whole pixel's): those
/// cells have no row, and run_bench warns once naming them.
bool bench_cell_applies(const TechniqueSpec& t, const WorkloadSpec& w);

/// Runs the bench (validated first). Needs a current GL context for scenes.
ResultTable run_bench(const BenchSettings& s);

}  // namespace habuffer::harness
