/// @file
/// The two baselines that store no lists, on the CPU: weighted blended OIT
/// (McGuire and Bavoil 2013) and plain over-blending in submission order.
/// Every valid fragment is blended into per-pixel accumulators (outcome
/// blended); nothing is stored, so there are no lists to read and nothing is
/// ever dropped. Each pixel sees its fragments in stream order whatever the
/// threads (threads own bands of rows and each scans the whole stream), so
/// the image is the serial one bit for bit.
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/fragment_buffer.h"
#include "habuffer/technique_params.h"

namespace habuffer {

/// The wboit and blend baselines: per-pixel accumulators, no stored records.
class BlendedImage final : public FragmentBuffer {
 public:
  /// config.technique wboit or blend; throws std::invalid_argument otherwise
  /// or for a bad configuration.
  explicit BlendedImage(const TechniqueConfig& config);

  /// `c` validated as a blended image's (wboit or blend; throws
  /// std::invalid_argument otherwise), for the GPU container too.
  [[nodiscard]] static TechniqueConfig checked_config(const TechniqueConfig& c);

  /// FragmentBuffer interface (see fragment_buffer.h).
  [[nodiscard]] Technique technique() const override { return config_.technique; }
  [[nodiscard]] Extent screen() const override { return config_.buffer.screen; }
  [[nodiscard]] TechniqueConfig technique_config() const override { return config_; }

  /// FragmentBuffer interface: blends every valid fragment into its pixel (counted
  /// blended), one band of rows per thread. Throws std::invalid_argument for
  /// InsertMode::OwnerComputes or Serial with more than one thread. Each call
  /// runs alone: calls overlapping on this container wait for it
  /// (insert_gate.h), so a pixel's blend order is the calls' order.
  Counters insert(std::span<const Fragment> fragments, const InsertOptions& options = {}) override;
  /// Resets the accumulators; returns 0 (nothing is stored).
  std::uint64_t clear() override;
  /// Always 0: nothing is stored.
  [[nodiscard]] std::uint64_t count_stored() const override { return 0; }
  /// Always 0: nothing is stored.
  [[nodiscard]] std::uint64_t capacity() const override { return 0; }
  /// No lists: `out` is left empty; returns 0.
  std::uint32_t list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const override;
  /// FragmentBuffer interface: resolves each pixel's accumulators over its
  /// background; throws std::invalid_argument unless `backgrounds` has screen
  /// area entries.
  [[nodiscard]] std::vector<glm::vec4> composite_pixels(std::span<const glm::vec3> backgrounds,
                                                       std::uint32_t threads = 0) const override;
  /// The accumulators: 16 bytes per pixel (blend), 20 (wboit: RGBA and revealage, float32).
  [[nodiscard]] std::uint64_t memory_bytes() const override;

  /// The GPU path's read-back: RGBA accumulators (and wboit's revealage) per
  /// pixel; throws std::invalid_argument when the sizes differ.
  void import_state(std::span<const glm::vec4> accum, std::span<const float> revealage);

 private:
  [[nodiscard]] bool weighted() const { return config_.technique == Technique::Wboit; }

  TechniqueConfig config_;
  KernelUniforms params_;
  std::vector<glm::vec4> accum_;    ///< blend: (C, T); wboit: the weighted sums
  std::vector<float> revealage_;    ///< wboit
};

}  // namespace habuffer
