/// @file
/// `habuffer plan`: model only what a scene requires. From one counting pass
/// (the exact capture: fragment count, depth complexity per pixel, and the
/// fragments' colours for the lossy techniques) predict, per technique and
/// setting, the memory, the HA-buffer's max age and failure risk (SPEC 3's
/// insertion modelled on a synthetic stream with the same per-pixel counts
/// and random depths, over several seeds), the layers' overflow, and the PSNR
/// of the truncating techniques (fixed arrays keep the first K in stream
/// order, which parallel insertion only approximates); then recommend the cheapest configuration
/// that is lossless, or that meets a target PSNR, within a memory budget when
/// one is given (the most accurate within it when none meets the aim there).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "habuffer/harness/result_table.h"
#include "habuffer/harness/workload.h"

namespace habuffer::harness {

/// What `habuffer plan` predicts over and aims for.
struct PlanSettings {
  std::optional<double> target_psnr;  ///< dB, finite and above 0; none: the cheapest lossless configuration
  /// Bytes per fragment (memory_bytes / the capture's fragments), finite and
  /// at least 0: only configurations within it are recommended; none: no budget.
  std::optional<double> memory_budget;
  /// The HA-buffer's table loads predicted (those the screen cannot give are skipped).
  std::vector<double> loads{0.5, 0.6, 0.7, 0.8, 0.9, 0.95};
  std::uint32_t trials = 3;           ///< synthetic streams per HA-buffer load
  std::uint64_t seed = 1;  ///< trial t: stream depths seed + t, offsets seed + 1000 + t
  std::uint32_t age_bits = HABUFFER_DEFAULT_AGE_BITS;  ///< the HA-buffer's age bits (fix AMAX)
  /// Called after each load's HA-buffer prediction (done, total).
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;
};

/// One row per configuration: technique, memory_bytes, bytes_per_fragment,
/// predicted_max_age (mean over trials) and its largest, predicted_failures
/// (fragments lost), failure_risk (share of trials losing any),
/// predicted_psnr (inf when exact), lossless, meets_target, within_budget
/// (with a budget), recommended. The recommendation: the least memory among
/// the configurations that meet the aim (lossless: no trial lost anything;
/// a target: predicted PSNR at least it, a hash table's only without failure
/// risk) within the budget; when none does, the most accurate within the
/// budget (highest predicted PSNR, then fewest predicted failures, then least
/// memory; a hash table with failure risk ranks below every predicted PSNR),
/// which the note `budget` says; "none" when nothing fits the budget. Notes
/// give the depth complexity and the recommendation. A pixel with more fragments than AMAX
/// fails the HA-buffer at every load: its rows are predicted from that
/// (failures at least the excess, risk 1) without simulating, and a note
/// names the pixel and the age bits that would hold it.
/// Needs a current GL context for scenes (the capture); notes name the scene and size.
ResultTable run_plan(const Workload& workload, const PlanSettings& s);
/// The same from a capture already made (needs no GL context).
ResultTable plan_from_capture(const ExactCapture& capture, Extent screen, const PlanSettings& s);

}  // namespace habuffer::harness
