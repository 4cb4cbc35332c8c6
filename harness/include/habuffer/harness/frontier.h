/// @file
/// The speed-accuracy frontier: a bench over techniques and their knobs (HA
/// early-cull tau, age bits, load; arrays K; k-buffer k with and without
/// occupancy; sorted-lists tau; wboit; blend), each row marked when it is
/// Pareto-optimal per scene and size in time vs PSNR and in memory vs PSNR:
/// which configuration to pick for an accuracy, measured rather than guessed.
#pragma once

#include <string>
#include <vector>

#include "habuffer/harness/bench.h"
#include "habuffer/harness/result_table.h"

namespace habuffer::harness {

/// The knob grid (wboit and blend only on the CPU path).
std::vector<TechniqueSpec> frontier_techniques(RenderPath path);

/// Marks `pareto_time` and `pareto_memory` on every row of a bench table:
/// true when no other row of the same scene, size and path is at least as
/// good in both (cost no larger, psnr no smaller) and better in one.
void mark_pareto(ResultTable& bench);

/// For each PSNR threshold, per scene and size: the fastest row reaching it
/// (`target_psnr`, `technique`, `total_ms`, `memory_bytes`, `psnr`).
ResultTable frontier_picks(const ResultTable& bench, const std::vector<double>& thresholds_db);

}  // namespace habuffer::harness
