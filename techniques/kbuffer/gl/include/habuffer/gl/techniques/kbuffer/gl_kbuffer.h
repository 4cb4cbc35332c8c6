/// @file
/// The k-buffer on the GPU (seed 003): K layers per pixel, layer-major, in the
/// atomic mode's slot table (native32: L32 records, native64: 64-bit
/// atomicMax, emulated64: the HA-buffer's lock words and its deferral of
/// calls cut short, resumed by the frame driver), kept sorted by atomic max
/// (no sort pass). With occupancy on, each gather is two passes of the host's
/// scene: a fill pass setting one bit per occupied depth bucket, then this
/// technique's count pass (the bucket of each pixel's k-th occupied bit),
/// then the insertion, which rejects fragments beyond it
/// (occupancy_rejected). What falls behind the K-th layer is dropped and
/// counted (dropped_layers); lossless mode doubles K.
#pragma once

#include <memory>

#include "habuffer/gl/gl_technique.h"

namespace habuffer::gl {

/// The k-buffer's container on the GPU (see the file comment).
class GlKBuffer final : public GlTechnique {
 public:
  /// Throws std::invalid_argument for a bad config, GlError beyond the context's limits.
  GlKBuffer(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings);
  /// Deletes the layers, lock words, occupancy buffers and count pass.
  ~GlKBuffer() override;

  /// The configuration, validated; `layers` is the current K.
  [[nodiscard]] const TechniqueConfig& config() const { return config_; }

  /// GlTechnique interface (see gl_technique.h). With occupancy it declares a
  /// Fill pass: a gather that fills the occupancy map, then its count pass
  /// (the limits); before_gather zeroes the
  /// layers and the occupancy map, reset the layers; grow doubles K, false
  /// beyond the context's limits; insert calls are deferred in emulated64 only.
  void write_params(GlParams& params) const override;
  void bind() const override;
  void begin_frame(FrameReport&, const GlFrameOptions&) override {}
  void before_gather() override;
  void reset() override;
  bool grow(const FrameReport& report, const GlFrameOptions& options) override;
  [[nodiscard]] bool defers_calls() const override { return mode() == AtomicMode::Emulated64; }
  [[nodiscard]] std::uint64_t capacity() const override { return std::uint64_t{config_.layers} * screen().area(); }
  [[nodiscard]] std::uint64_t memory_bytes() const override;
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;

 protected:
  /// resize_screen (gl_technique.h): K layers per pixel of the new screen
  /// (zeroed), K kept, new lock words (emulated64) and occupancy buffers.
  void change_screen(Extent screen) override;

 private:
  struct Gpu;
  /// The Fill pass's count pass: each pixel's limit from its occupancy map.
  void count_limits() const;
  void allocate_layers(std::uint32_t layers);
  [[nodiscard]] std::uint64_t word_bytes() const;

  TechniqueConfig config_;
  std::unique_ptr<Gpu> gpu_;
};

/// The k-buffer's occupancy count pass.
std::string kbuffer_count_compute(AtomicMode mode, const GlBindings& bindings = {});

}  // namespace habuffer::gl
