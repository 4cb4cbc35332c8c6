/// @file
/// Fixed per-pixel arrays on the CPU (seed 004): K layers per pixel and a
/// per-pixel atomic counter, sorted after each insert batch. A fragment
/// arriving at a pixel whose K layers are taken is dropped and counted
/// (dropped_layers); largest_overflow() gives the most fragments a pixel
/// received, so a caller can size K for a lossless regather. With K at least
/// the depth complexity the lists are exact.
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/fragment_buffer.h"
#include "habuffer/techniques/arrays/detail/arrays_kernel.h"
#include "habuffer/technique_params.h"

namespace habuffer {

/// Fixed per-pixel arrays of K layers (see above).
class FixedArrays final : public FragmentBuffer {
 public:
  /// Throws std::invalid_argument for a bad configuration (TechniqueConfig::validate).
  explicit FixedArrays(const TechniqueConfig& config);

  /// FragmentBuffer interface (see fragment_buffer.h).
  [[nodiscard]] Technique technique() const override { return Technique::Arrays; }
  [[nodiscard]] Extent screen() const override { return config_.buffer.screen; }
  /// The configuration, validated as technique arrays.
  [[nodiscard]] const TechniqueConfig& config() const { return config_; }
  /// FragmentBuffer interface: the same configuration.
  [[nodiscard]] TechniqueConfig technique_config() const override { return config_; }
  /// K, layers per pixel.
  [[nodiscard]] std::uint32_t layers() const { return params_.habuffer_layers; }

  /// FragmentBuffer interface: counts each pixel's fragments atomically, then
  /// sorts every pixel's layers. Throws std::invalid_argument for
  /// InsertMode::OwnerComputes, Serial with more than one thread, or a batch
  /// that could overflow a pixel's 32-bit counter. Each call runs alone: calls
  /// overlapping on this container wait for it (insert_gate.h).
  Counters insert(std::span<const Fragment> fragments, const InsertOptions& options = {}) override;
  /// FragmentBuffer interface: zeroes the counters and largest_overflow().
  std::uint64_t clear() override;
  /// The same without counting (a kept container's next frame).
  void reset() override;
  /// The sum of the pixels' sorted lengths.
  [[nodiscard]] std::uint64_t count_stored() const override;
  /// K per pixel.
  [[nodiscard]] std::uint64_t capacity() const override { return std::uint64_t{params_.habuffer_layers} * screen().area(); }
  /// The most fragments one pixel received since the last clear, when some
  /// pixel received more than K; else 0.
  [[nodiscard]] std::uint32_t largest_overflow() const { return max_arrived_; }
  /// FragmentBuffer interface: the deepest pixel (largest_overflow()).
  [[nodiscard]] GrowthNeed growth_need() const override { return {0, max_arrived_}; }

  /// FragmentBuffer interface; returns 1 + the list's length (the counter, then the layers).
  std::uint32_t list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const override;
  /// FragmentBuffer interface; throws std::invalid_argument unless `backgrounds`
  /// has screen area entries.
  [[nodiscard]] std::vector<glm::vec4> composite_pixels(std::span<const glm::vec3> backgrounds,
                                                       std::uint32_t threads = 0) const override;
  /// Counters and layers.
  [[nodiscard]] std::uint64_t memory_bytes() const override;

  /// The GPU path's read-back (after its sort pass): per-pixel sorted lengths,
  /// layers, and the largest overflow; throws std::invalid_argument when the
  /// sizes differ or a length exceeds K.
  void import_state(std::span<const std::uint32_t> counts, std::span<const glm::uvec2> layers,
                    std::uint32_t largest_overflow);

 private:
  // Empties every pixel (the caller holds the container alone).
  void empty();
  [[nodiscard]] ArraysBuffers buffers() const;

  TechniqueConfig config_;
  KernelUniforms params_;
  std::vector<std::uint32_t> counts_;
  std::vector<glm::uvec2> layers_;
  std::uint32_t max_arrived_ = 0;
};

}  // namespace habuffer
