/// @file
/// Seed 000's figures as runs of the harness, each a table:
///   Fig. 2  early cull vs opacity: stored fragments, gather time and fill rate
///           with and without cull, opacity 1 inserted like the rest;
///   Fig. 8  the stress test: quads pulled together over frames (spread 1 to
///           0) into a table fixed at one load; time and max age per frame,
///           with and without cull;
///   Table 1 memory by formula (the paper's and ours), allocated by the CPU
///           containers, and the paper's published values, at its fragment
///           counts and loads.
/// (Seed 001's Fig. 10, planes front vs back with and without saturation, is
/// a bench preset: fig10_bench_settings.)
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "habuffer/harness/bench.h"
#include "habuffer/harness/result_table.h"
#include "habuffer/harness/workload.h"

namespace habuffer::harness {

/// What the figure runs share.
struct FigureSettings {
  RenderPath path = RenderPath::Gl;  ///< GPU or CPU path
  Extent size{256, 256};             ///< the screen, pixels
  std::uint32_t repeats = 3;         ///< repetitions per point
  std::uint32_t threads = 0;         ///< CPU path: worker threads, 0 for the default
  float tau = 0.99f;                 ///< early cull's tau for the "with cull" runs
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;  ///< (runs done, runs)
};

/// The scene words Fig. 2 and Fig. 8 accept: fig2 varies the opacity (not a
/// fragment file, no opacity= of its own), fig8 the spread (a scene that
/// takes spread, no spread= of its own). Throw std::invalid_argument naming
/// the word; the runs check them first too.
void check_fig2_scene(const WorkloadSpec& scene);
/// See check_fig2_scene.
void check_fig8_scene(const WorkloadSpec& scene);
/// Fig. 2 on `scene` (the command's default: hairball) at each opacity.
ResultTable run_fig2(const WorkloadSpec& scene, const std::vector<float>& opacities, const FigureSettings& s);
/// Fig. 8: `quads` scene words (count, seed, opacity kept; spread set per
/// frame), `frames` frames, the table sized for `load` of frame 0's fragments.
ResultTable run_fig8(const WorkloadSpec& quads, std::uint32_t frames, double load, const FigureSettings& s);
/// Seed 001's Fig. 10 as bench settings: planes (count) front and back, the
/// HA-buffer and sorted lists, exact, with cull, with cull and saturation.
BenchSettings fig10_bench_settings(std::uint32_t planes, const FigureSettings& s);
/// Table 1's bounds: fragment counts in 1..kMaxTableFragments, loads in
/// (0, 1] with F / L slots below 2^32; a row whose model exceeds
/// kMaxTableAllocationBytes is not allocated (its note says so).
inline constexpr std::uint64_t kMaxTableFragments = std::uint64_t{1} << 31;        ///< 2^31 fragments
inline constexpr std::uint64_t kMaxTableAllocationBytes = std::uint64_t{4} << 30;  ///< 4 GiB
/// Throws std::invalid_argument naming the option and value out of bounds.
void validate_memory_table(Extent screen, const std::vector<std::uint64_t>& fragments, const std::vector<double>& loads);
/// Table 1 on `screen` (the paper: 1024x1024) for each fragment count and load; `allocate`: also measure
/// the CPU containers' allocations (rows within kMaxTableAllocationBytes).
ResultTable run_memory_table(Extent screen, const std::vector<std::uint64_t>& fragments, const std::vector<double>& loads,
                             bool allocate);

}  // namespace habuffer::harness
