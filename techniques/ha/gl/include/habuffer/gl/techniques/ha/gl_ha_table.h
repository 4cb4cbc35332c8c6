/// @file
/// The HA-buffer's container on the GPU: table, per-slot locks (emulated64),
/// max-age table and offsets in shader-storage buffers; the paper's clear
/// pass, which counts the previous frame's records under an occlusion query
/// into a query buffer read one frame later without a stall; adaptive sizing
/// of SPEC 8 from that count (offsets regenerated for every new size); and
/// lossless growth of the table.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "habuffer/buffer_config.h"
#include "habuffer/gl/gl_technique.h"
#include "habuffer/offset_source.h"
#include "habuffer/offset_sequence.h"

namespace habuffer::gl {

/// The HA-buffer's container on the GPU (see the file comment).
class GlHaTable final : public GlTechnique {
 public:
  /// Throws std::invalid_argument for a bad config, GlError when the mode
  /// cannot hold the layout, the context lacks what the mode needs, or the
  /// table exceeds the context's limits (the message names the sizes).
  GlHaTable(const BufferConfig& config, OffsetSource offsets, AtomicMode mode, const GlBindings& bindings,
            std::uint32_t clear_tile = 0);
  /// Deletes the table's buffers and the clear pass.
  ~GlHaTable() override;

  /// The configuration, validated.
  [[nodiscard]] const BufferConfig& config() const { return config_; }  // config().table: the current table
  /// The current table.
  [[nodiscard]] Extent table() const { return config_.table; }
  /// The offsets of the current table.
  [[nodiscard]] const OffsetSequence& offsets() const { return offsets_; }

  /// Sets the table for the next frame (at least the screen; offsets
  /// regenerated). The table only: resize_screen changes the screen.
  void resize(Extent table);
  /// GlTechnique interface: the largest table up to wanted.buffer.table (same
  /// aspect, at least the screen) the context's storage-buffer limit holds.
  bool fit_automatic_size(const TechniqueConfig& wanted) override;
  /// GlTechnique interface: whether the config gave no table (Extent{}):
  /// the frame driver sizes it from a counting gather and adapts it.
  [[nodiscard]] bool sized_automatically() const override { return auto_table_; }
  /// GlTechnique interface: the largest cell of read_max_age().
  [[nodiscard]] std::uint32_t read_largest_max_age() const override;
  /// Why `table` cannot be allocated here (slot indices, buffer size), or empty.
  [[nodiscard]] std::string table_limit(Extent table) const;
  /// Binds the table, max-age table and offsets at these points (indexed
  /// bindings only), for another frame's shaders to read it as a light
  /// buffer (GlShadowLookup).
  void bind_for_lookup(unsigned table, unsigned max_age, unsigned offsets) const;
  /// The counting pass without clearing (needs the buffers bound and a state guard).
  std::uint64_t count_stored();

  /// Slots widened to 64 bits (L32 records in the low half), row-major.
  [[nodiscard]] std::vector<std::uint64_t> read_table() const;
  /// The max-age table: one word per cell of block x block pixels, row-major.
  [[nodiscard]] std::vector<std::uint32_t> read_max_age() const;

  /// GlTechnique interface (see gl_technique.h). Its FrameStart pass, once
  /// a gather filled the table, reads the count the previous clear pass
  /// left and runs this frame's clear pass; begin_frame adapts the table
  /// from that count; before_gather zeroes the max-age table and saturation
  /// codes; reset zeroes the table; gathered reports the table; grow
  /// enlarges it by the policy's step, false beyond the context's limits;
  /// insert calls are deferred.
  void write_params(GlParams& params) const override;
  void bind() const override;
  void begin_frame(FrameReport& report, const GlFrameOptions& options) override;
  void before_gather() override;
  void reset() override;
  void gathered(std::span<const std::uint32_t> counter_words, FrameReport& report) override;
  bool grow(const FrameReport& report, const GlFrameOptions& options) override;
  [[nodiscard]] bool defers_calls() const override { return true; }
  [[nodiscard]] std::uint64_t capacity() const override { return config_.table.area(); }
  [[nodiscard]] Extent table_extent() const override { return config_.table; }
  [[nodiscard]] std::uint64_t memory_bytes() const override;
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;

 protected:
  /// resize_screen (gl_technique.h): the table scaled by each side's ratio
  /// of the new screen to the old, rounded up and at least the new screen
  /// (SPEC 1), so an automatic table (the screen) becomes the new screen as
  /// in a fresh container and an explicit or adapted one keeps its load;
  /// when that table is beyond the context's limits, the screen itself.
  /// Offsets regenerated for a new table (as lossless growth and adaptive
  /// sizing do); a fresh zeroed table, max-age table and saturation image;
  /// the count of a clear pass in flight is dropped (the first frame after
  /// runs no clear pass, adaptive sizing resumes a frame later).
  void change_screen(Extent screen) override;

 private:
  struct Gpu;
  /// The FrameStart pass (see above).
  void clear(GlPassContext& context);
  /// Fresh zeroed table (and locks); offsets regenerated for it unless new_offsets is false.
  void allocate_table(Extent table, bool new_offsets = true);

  BufferConfig config_;
  OffsetSource source_;
  OffsetSequence offsets_;
  std::uint32_t cells_ = 0;
  std::uint32_t clear_tile_ = 0;
  bool auto_table_ = false;   ///< no table given: sized by the frame driver's counting gather
  bool holds_frame_ = false;  ///< the table holds a gathered frame the next clear pass must count
  std::optional<Extent> pending_count_table_;  ///< the table a count in the query buffer was measured in
  std::unique_ptr<Gpu> gpu_;
};

/// The clear pass's fragment shader (the HA-buffer's module plus its code).
std::string clear_pass_fragment(AtomicMode mode, const GlBindings& bindings);

}  // namespace habuffer::gl
