/// @file
/// The speed-accuracy frontier: a bench over techniques and their knobs (HA
/// early-cull tau, age bits, load; arrays K; k-buffer k with and without
/// occupancy; sorted-lists tau; wboit; blend), each row marked when it is
/// Pareto-optimal per scene and size in time vs PSNR, in memory vs PSNR and
/// in all three at once: which configuration to pick for an accuracy and a
/// memory budget, measured rather than guessed.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "habuffer/harness/bench.h"
#include "habuffer/harness/result_table.h"

namespace habuffer::harness {

/// The knob grid (wboit and blend only on the CPU path).
std::vector<TechniqueSpec> frontier_techniques(RenderPath path);

/// Marks three fronts on every row of a bench table, each among the rows of
/// the same scene, size and path: `pareto_time` (total_ms vs psnr),
/// `pareto_memory` (memory_bytes vs psnr) and `pareto_3d` (total_ms,
/// memory_bytes and psnr together). A row is on a front when no other row is
/// at least as good in every one of its axes (cost no larger, psnr no
/// smaller; identical images, psnr inf or null, above every finite psnr) and
/// strictly better in one. Ties: rows equal in every axis dominate nobody, so
/// all of them stay on the front.
void mark_pareto(ResultTable& bench);

/// No memory budget: a pick among every row.
inline constexpr double kNoMemoryBudget = std::numeric_limits<double>::infinity();

/// For each PSNR threshold and each memory budget (bytes per fragment,
/// bytes_per_fragment of the row; kNoMemoryBudget for none), per scene and
/// size: the fastest row (total_ms) reaching the threshold within the
/// budget. Columns `scene`, `size`, `target_psnr`, `memory_budget` (bytes
/// per fragment; inf, null in JSON, for no budget), then the pick's
/// `technique`, `total_ms`, `memory_bytes`, `bytes_per_fragment` and `psnr`;
/// `technique` is "none" (and the rest absent) when no row qualifies.
/// Rows are in the order scene and size, threshold, budget as given.
ResultTable frontier_picks(const ResultTable& bench, const std::vector<double>& thresholds_db,
                           const std::vector<double>& budgets_bytes_per_fragment = {kNoMemoryBudget});

}  // namespace habuffer::harness
