/// @file
/// The GPU traffic model (issue 36, part 7), for the rounds without a GPU:
/// one frame of a technique replayed on the CPU through its shared GLSL
/// (harness/traced_kernels.h), its memory accesses counted as a GPU's warps
/// would issue them (habuffer/harness/warp_traffic.h), and a time predicted
/// from the counts by a cost model with stated constants. docs/performance.md
/// ("GPU traffic model (issue 36)") holds its validation against the H100
/// and docs/spec-notes.md its definitions.
///
/// Passes, as the GPU path runs them: gather, the captured fragments in
/// their order (the CPU path's capture keeps the rasterizer's append order)
/// in warps of 32 consecutive fragments, each through habuffer_insert's call
/// and outcome tally (the k-buffer's occupancy fill and count passes added
/// to it, as the GPU runs them inside its gather); sort (lists and arrays), then resolve (composite), one
/// lane per pixel, 32 consecutive pixels of a row-major screen a warp. The
/// memory starts empty, as after the frame's clear; lanes run one after the
/// other, so the table and lists end as the GPU's do (SPEC 9) while their
/// intermediate states are one of the orders a GPU may take.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "habuffer/fragment.h"
#include "habuffer/harness/result_table.h"
#include "habuffer/harness/warp_traffic.h"
#include "habuffer/lossless_build.h"
#include "habuffer/technique.h"

namespace habuffer::harness {

/// One frame's counts, pass by pass.
struct GpuTraffic {
  TrafficCounts gather;   ///< the insert calls
  TrafficCounts sort;     ///< lists and arrays: the per-pixel sort pass; else empty
  TrafficCounts resolve;  ///< the composite pass
};

/// Whether the model has a traced kernel for `t` (ha, lists, sorted-lists, arrays, kbuffer).
bool gpu_model_covers(Technique t);

/// Replays `fragments` through `c`'s technique (c.buffer.table resolved: the
/// HA-buffer's table; an automatic pool holds every fragment). Throws
/// std::invalid_argument for a technique gpu_model_covers refuses.
GpuTraffic model_gpu_frame(const TechniqueConfig& c, const OffsetSource& offsets, std::span<const Fragment> fragments);

/// A time from the counts: per pass, fragment_ns per lane of the gather (the
/// rasterizer and the entry), and sector_ns, atomic_ns, conflict_ns and
/// chain_ns per sector, lane atomic, conflict and chain link summed over the
/// warps. Constants and where they come from: h100().
struct GpuCostModel {
  double fragment_ns = 0.0;  ///< per gathered fragment
  double sector_ns = 0.0;    ///< per sector moved
  double atomic_ns = 0.0;    ///< per lane atomic
  double conflict_ns = 0.0;  ///< per same-address atomic serialized
  double chain_ns = 0.0;     ///< per warp chain link (latency over the warps in flight)
  std::string source;        ///< where the constants come from, one line
  /// The H100 constants (docs/performance.md: a priori from its data sheet,
  /// the conflict and chain ones fitted on the 512x512 round, 1024x1024 held out).
  static GpuCostModel h100();
  /// Milliseconds of one pass.
  [[nodiscard]] double pass_ms(const TrafficCounts& pass, bool gather) const;
};

/// Adds the model's columns to a bench row: model_{gather,sort,resolve}_{sectors,
/// lines,atomics,conflicts,chain,chain_max,instructions}, and the predicted
/// model_gather_ms, model_resolve_ms (sort and composite, as the bench's
/// resolve_ms) and model_total_ms.
void set_gpu_model_columns(ResultRow& row, const GpuTraffic& traffic, const GpuCostModel& model);

}  // namespace habuffer::harness
