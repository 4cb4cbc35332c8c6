/// @file
/// Paged per-pixel lists on the GPU (technique paged-lists): the linked
/// lists' head image (zeroed before every gather), node entries and links,
/// nodes taken in pages of K = 4 per pixel (the node counter is a word of
/// the driver's counters, advanced by a page), and the sort pass after the
/// gather. A pixel whose page is full when no page is left drops and counts
/// (dropped_pool); adaptive sizing applies SPEC 8's rule to the nodes the
/// previous frame asked for; lossless mode regathers into a pool of at least
/// the nodes the gather asked for. `pool_capacity` 0 is the automatic pool:
/// one page per pixel at first, a frame that dropped gathered again at once
/// into a pool of the nodes it asked for, and SPEC 8's rule every frame.
#pragma once

#include <memory>
#include <string>

#include "habuffer/gl/gl_technique.h"

namespace habuffer::gl {

/// Paged lists' container on the GPU (see the file comment).
class GlPagedLists final : public GlTechnique {
 public:
  /// Throws std::invalid_argument for a bad config, GlError beyond the
  /// context's limits. `config.pool_capacity` 0: the automatic pool.
  GlPagedLists(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings);
  /// Deletes the head image, node pool and sort pass.
  ~GlPagedLists() override;

  /// The configuration, validated; `pool_capacity` is the current pool (nodes).
  [[nodiscard]] const TechniqueConfig& config() const { return config_; }
  /// Sets the pool for the next frame (a host's own estimate).
  void resize_pool(std::uint64_t nodes);
  /// GlTechnique interface: the pool of wanted.pool_capacity nodes, or the
  /// most the context's storage-buffer limit holds.
  bool fit_automatic_size(const TechniqueConfig& wanted) override;

  /// GlTechnique interface (see gl_technique.h), as GlLinkedLists' for
  /// technique lists: begin_frame resizes the pool by SPEC 8's rule
  /// (adaptive or automatic), before_gather zeroes the head image,
  /// after_gather runs the sort pass, grow makes the pool at least the
  /// nodes the gather asked for, gathered keeps that request.
  void write_params(GlParams& params) const override;
  void bind() const override;
  void begin_frame(FrameReport& report, const GlFrameOptions& options) override;
  void before_gather() override;
  void reset() override {}
  PassTiming after_gather(bool finish_timing) override;
  [[nodiscard]] bool sorts() const override { return true; }
  bool grow(const FrameReport& report, const GlFrameOptions& options) override;
  /// The automatic pool grows at once, in the frame that dropped.
  [[nodiscard]] bool grows_at_once() const override { return auto_pool_; }
  [[nodiscard]] std::uint64_t capacity() const override { return config_.pool_capacity; }
  [[nodiscard]] std::uint64_t memory_bytes() const override;
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;
  void gathered(const FrameReport& report) override;

 protected:
  /// resize_screen (gl_technique.h): a new zeroed head image; the pool
  /// scaled by the ratio of the areas, rounded up (an automatic pool at
  /// least a page per pixel; kept when the scaled one is beyond the limits);
  /// the last frame's node request forgotten.
  void change_screen(Extent screen) override;

 private:
  struct Gpu;
  void allocate_pool(std::uint64_t nodes);
  /// Why a pool of `nodes` cannot be allocated here, or empty.
  [[nodiscard]] std::string pool_limit(std::uint64_t nodes) const;

  TechniqueConfig config_;
  bool auto_pool_ = false;
  std::uint64_t last_requested_ = 0;
  bool has_request_ = false;
  std::unique_ptr<Gpu> gpu_;
};

}  // namespace habuffer::gl
