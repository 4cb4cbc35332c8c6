/// @file
/// Fixed per-pixel arrays on the GPU (seed 004): per-pixel counters (zeroed
/// before every gather) and K layers per pixel, layer-major, sorted by the
/// sort pass after the gather. A full pixel drops and counts
/// (dropped_layers); lossless mode regathers with K raised to the most
/// fragments a pixel received.
#pragma once

#include <memory>

#include "habuffer/gl/gl_technique.h"

namespace habuffer::gl {

/// Fixed per-pixel arrays' container on the GPU (see the file comment).
class GlFixedArrays final : public GlTechnique {
 public:
  /// Throws std::invalid_argument for a bad config, GlError beyond the context's limits.
  GlFixedArrays(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings);
  /// Deletes the counters, the layers and the sort pass.
  ~GlFixedArrays() override;

  /// The configuration, validated; `layers` is the current K.
  [[nodiscard]] const TechniqueConfig& config() const { return config_; }

  /// GlTechnique interface (see gl_technique.h). before_gather zeroes the
  /// counters; its Sort pass sorts each pixel's layers; grow raises K to the
  /// most fragments a pixel received (at least one more), false beyond the
  /// context's limits; gathered reports that most and keeps it for read_back.
  void write_params(GlParams& params) const override;
  void bind() const override;
  void begin_frame(FrameReport&, const GlFrameOptions&) override {}
  void before_gather() override;
  void reset() override {}
  bool grow(const FrameReport& report, const GlFrameOptions& options) override;
  [[nodiscard]] std::uint64_t capacity() const override {
    return std::uint64_t{config_.layers} * config_.buffer.screen.area();
  }
  [[nodiscard]] std::uint64_t memory_bytes() const override;
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;
  void gathered(std::span<const std::uint32_t> counter_words, FrameReport& report) override;

 protected:
  /// resize_screen (gl_technique.h): new zeroed counters and K layers per
  /// pixel of the new screen, K kept (the depth of a pixel does not grow
  /// with the screen; lossless mode's K stays).
  void change_screen(Extent screen) override;

 private:
  struct Gpu;
  void allocate_layers(std::uint32_t layers);

  TechniqueConfig config_;
  std::uint32_t most_arrived_ = 0;
  std::unique_ptr<Gpu> gpu_;
};

}  // namespace habuffer::gl
