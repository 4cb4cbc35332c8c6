/// @file
/// `habuffer sweep`: one fixed view, the technique sized for each load (the
/// HA-buffer's table, the lists' pool, the arrays' or k-buffer's layers),
/// N repetitions with fresh offsets (seed + repetition, so a run is
/// reproducible), interleaved load by load so the machine's drift hits every
/// load alike. One row per load: seed 000's Fig. 5 and its age statistics.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "habuffer/harness/result_table.h"
#include "habuffer/harness/technique_spec.h"
#include "habuffer/harness/workload.h"

namespace habuffer::harness {

/// What `habuffer sweep` runs (validate_sweep checks it).
struct SweepSettings {
  RenderPath path = RenderPath::Gl;  ///< GPU or CPU path
  TechniqueSpec technique;            ///< its own load is replaced by each load
  std::vector<double> loads{0.5, 0.8, 0.9};  ///< in (0, 1], increasing, no repeats
  std::uint32_t repeats = 3;  ///< repetitions per load
  std::uint64_t seed = 1;             ///< offsets of repetition r: seed + r
  OffsetGenerator offsets = OffsetGenerator::Random;  ///< how each repetition's offsets are made
  std::uint32_t threads = 0;          ///< CPU path
  InsertOrder insert_order = InsertOrder::Auto;  ///< CPU path, the HA-buffer
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;  ///< (runs done, runs)
};

/// Throws std::invalid_argument for loads outside (0, 1], repeated or out of
/// order, a technique without a size knob, or a load the screen cannot give.
void validate_sweep(const SweepSettings& s);

/// Runs the sweep (validated first). Needs a current GL context for scenes.
ResultTable run_sweep(const Workload& workload, const SweepSettings& s);

/// Stored records per age (index = age) over every pixel's list.
std::vector<std::uint64_t> age_histogram(const FragmentBuffer& buffer);
/// The mean age of a histogram (0 when empty).
double histogram_mean(const std::vector<std::uint64_t>& h);
/// The q-quantile (0 < q <= 1) of a histogram: the smallest age with at least q of the records at or below it.
std::uint32_t histogram_quantile(const std::vector<std::uint64_t>& h, double q);

}  // namespace habuffer::harness
