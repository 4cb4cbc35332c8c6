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
#include "habuffer/lossless_build.h"  // OffsetSource
#include "habuffer/offset_sequence.h"

namespace habuffer::gl {

class GlHaTable final : public GlTechnique {
 public:
  /// Throws std::invalid_argument for a bad config, GlError when the mode
  /// cannot hold the layout, the context lacks what the mode needs, or the
  /// table exceeds the context's limits (the message names the sizes).
  GlHaTable(const BufferConfig& config, OffsetSource offsets, AtomicMode mode, const GlBindings& bindings,
            std::uint32_t clear_tile = 0);
  ~GlHaTable() override;

  [[nodiscard]] const BufferConfig& config() const { return config_; }  // config().table: the current table
  [[nodiscard]] Extent table() const override { return config_.table; }
  [[nodiscard]] const OffsetSequence& offsets() const { return offsets_; }

  /// Sets the table for the next frame (at least the screen; offsets regenerated).
  void resize(Extent table);
  /// Why `table` cannot be allocated here (slot indices, buffer size), or empty.
  [[nodiscard]] std::string table_limit(Extent table) const;
  /// The counting pass without clearing (needs the buffers bound and a state guard).
  std::uint64_t count_stored();

  [[nodiscard]] std::vector<std::uint64_t> read_table() const;
  [[nodiscard]] std::vector<std::uint32_t> read_max_age() const;

  void write_params(GlParams& params) const override;
  void bind() const override;
  void begin_frame(FrameReport& report, const GlFrameOptions& options) override;
  [[nodiscard]] bool draws_at_frame_start() const override { return holds_frame_; }  // the clear pass
  void before_gather() override;
  void reset() override;
  bool grow(const FrameReport& report, const GlFrameOptions& options) override;
  [[nodiscard]] bool defers_calls() const override { return true; }
  [[nodiscard]] std::uint64_t capacity() const override { return config_.table.area(); }
  [[nodiscard]] std::uint64_t memory_bytes() const override;
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;

 private:
  struct Gpu;
  /// Fresh zeroed table (and locks); offsets regenerated for it unless new_offsets is false.
  void allocate_table(Extent table, bool new_offsets = true);

  BufferConfig config_;
  OffsetSource source_;
  OffsetSequence offsets_;
  std::uint32_t cells_ = 0;
  std::uint32_t clear_tile_ = 0;
  bool holds_frame_ = false;  ///< the table holds a gathered frame the next clear pass must count
  std::optional<Extent> pending_count_table_;  ///< the table a count in the query buffer was measured in
  std::unique_ptr<Gpu> gpu_;
};

}  // namespace habuffer::gl
