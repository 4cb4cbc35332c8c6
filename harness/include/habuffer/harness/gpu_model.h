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

/// A time from the counts, pass by pass: the gather's gather_frame_ms plus
/// gather_instruction_ns per warp memory instruction of the gather; the
/// resolve's (sort and composite) resolve_frame_ms plus
/// resolve_instruction_ns per warp memory instruction of both; sector_ns per
/// sector in every pass. Sectors, atomics, conflicts and chains are counted
/// and reported; only what the H100's times were found to follow is priced
/// (docs/performance.md, "GPU traffic model": the forms tried). Constants
/// and where they come from: h100().
struct GpuCostModel {
  double gather_frame_ms = 0.0;         ///< per gather (what it costs besides its traffic)
  double gather_instruction_ns = 0.0;   ///< per warp memory instruction of the gather
  double resolve_frame_ms = 0.0;        ///< per resolve (sort and composite)
  double resolve_instruction_ns = 0.0;  ///< per warp memory instruction of the sort and composite
  double sector_ns = 0.0;               ///< per sector moved, every pass
  std::string source;                   ///< where the constants come from, one line
  /// The H100's: sector_ns a priori (32 bytes at HBM3's 3.35 TB/s), the
  /// other four fitted on the H100's 512x512 round (gather_ms and resolve_ms
  /// apart; 1024x1024 held out).
  static GpuCostModel h100();
  /// The gather's milliseconds.
  [[nodiscard]] double gather_ms(const GpuTraffic& t) const;
  /// The sort's and composite's milliseconds (as the bench's resolve_ms).
  [[nodiscard]] double resolve_ms(const GpuTraffic& t) const;
};

/// Adds the model's columns to a bench row: model_{gather,sort,resolve}_{sectors,
/// lines,atomics,conflicts,chain,chain_max,instructions}, and the predicted
/// model_gather_ms, model_resolve_ms (sort and composite, as the bench's
/// resolve_ms) and model_total_ms.
void set_gpu_model_columns(ResultRow& row, const GpuTraffic& traffic, const GpuCostModel& model);

}  // namespace habuffer::harness
