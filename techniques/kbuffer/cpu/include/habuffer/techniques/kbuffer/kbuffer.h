/// @file
/// The k-buffer on the CPU (seed 003): the K nearest fragments of each pixel
/// kept sorted by atomic max, what falls behind the K-th dropped and counted
/// (dropped_layers); with the occupancy map on, each insert batch first fills
/// the map and counts each pixel's limit, then rejects fragments beyond it
/// (occupancy_rejected) before they touch the layers.
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/fragment_buffer.h"
#include "habuffer/techniques/kbuffer/detail/kbuffer_kernel.h"
#include "habuffer/technique_params.h"

namespace habuffer {
namespace detail {
struct InsertPlan;  // how an insert call runs its threads (core/model/include/habuffer/detail/technique_parallel.h)
}  // namespace detail

/// The k-buffer's CPU container (see above).
class KBuffer final : public FragmentBuffer {
 public:
  /// Throws std::invalid_argument for a bad configuration (TechniqueConfig::validate).
  explicit KBuffer(const TechniqueConfig& config);

  /// FragmentBuffer interface (see fragment_buffer.h).
  [[nodiscard]] Technique technique() const override { return Technique::KBuffer; }
  [[nodiscard]] Extent screen() const override { return config_.buffer.screen; }
  [[nodiscard]] TechniqueConfig technique_config() const override { return config_; }
  /// K, layers per pixel.
  [[nodiscard]] std::uint32_t layers() const { return params_.habuffer_layers; }

  /// FragmentBuffer interface: with the occupancy map on, a fill pass and a count
  /// pass come first; the layers stay sorted without a sort pass. Throws
  /// std::invalid_argument for InsertMode::OwnerComputes or Serial with more
  /// than one thread. Each call runs alone: calls overlapping on this
  /// container wait for it (insert_gate.h).
  Counters insert(std::span<const Fragment> fragments, const InsertOptions& options = {}) override;
  /// FragmentBuffer interface: zeroes the layers, the occupancy map and the limits.
  std::uint64_t clear() override;
  /// The same without counting (a kept container's next frame).
  void reset() override;
  /// The non-empty layer slots.
  [[nodiscard]] std::uint64_t count_stored() const override;
  /// K per pixel.
  [[nodiscard]] std::uint64_t capacity() const override { return std::uint64_t{params_.habuffer_layers} * screen().area(); }

  /// FragmentBuffer interface; returns the layers read (up to the first empty one, at most K).
  std::uint32_t list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const override;
  /// FragmentBuffer interface; throws std::invalid_argument unless `backgrounds`
  /// has screen area entries.
  [[nodiscard]] std::vector<glm::vec4> composite_pixels(std::span<const glm::vec3> backgrounds,
                                                       std::uint32_t threads = 0) const override;
  /// Layers, and the occupancy map and limits when on.
  [[nodiscard]] std::uint64_t memory_bytes() const override;

  /// The GPU path's read-back: the layers as record words (32-bit words,
  /// two per L64 record, low first), and the occupancy limits (occupancy on);
  /// throws std::invalid_argument when the sizes differ.
  void import_state(std::span<const std::uint32_t> slot_words, std::span<const std::uint32_t> limits);
  /// Pixel (x, y)'s occupancy limit (the bucket of the k-th occupied one, or
  /// 32 * occupancy_words when fewer are occupied); throws std::logic_error when occupancy is off.
  [[nodiscard]] std::uint32_t occupancy_limit(std::uint32_t x, std::uint32_t y) const;

 private:
  // Empties every slot (the caller holds the container alone).
  void empty();
  template <class Word>
  Counters insert_words(std::span<const Fragment> fragments, const detail::InsertPlan& plan);
  template <class Word>
  [[nodiscard]] KBufferBuffers<Word> buffers() const;
  [[nodiscard]] bool wide() const { return config_.buffer.layout == Layout::L64; }
  [[nodiscard]] std::uint64_t record(std::uint64_t slot) const;

  TechniqueConfig config_;
  KernelUniforms params_;
  std::vector<std::uint64_t> slots64_;  ///< L64
  std::vector<std::uint32_t> slots32_;  ///< L32
  std::vector<std::uint32_t> occupancy_;
  std::vector<std::uint32_t> limits_;
};

}  // namespace habuffer
