/// @file
/// The HA-buffer on the GPU: the frame driver (gl_frame_driver.h) running the
/// HA-buffer's container (gl_ha_table.h), with the table's accessors at hand.
/// Other techniques run in a GlFrameDriver with their own container.
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/buffer_config.h"
#include "habuffer/gl/gl_frame_driver.h"
#include "habuffer/gl/techniques/ha/gl_ha_table.h"

namespace habuffer::gl {

/// The HA-buffer on the GPU: a GlFrameDriver running a GlHaTable.
class GlHaBuffer : public GlFrameDriver {
 public:
  /// Throws std::invalid_argument for a bad config, GlError when the mode cannot
  /// hold the layout, the context lacks what the mode needs, or a buffer would
  /// exceed the context's limits (the message names the sizes).
  GlHaBuffer(const BufferConfig& config, OffsetSource offsets, AtomicMode mode, const GlFrameOptions& options = {},
             const GlBindings& bindings = {});

  /// The configuration, validated.
  [[nodiscard]] const BufferConfig& config() const { return table_.config(); }  // config().table: the current table
  /// The current table.
  [[nodiscard]] Extent table() const { return table_.table(); }
  /// The HA-buffer's container (a light buffer for GlShadowLookup, ...).
  [[nodiscard]] const GlHaTable& container() const { return table_; }
  /// The offsets of the current table.
  [[nodiscard]] const OffsetSequence& offsets() const { return table_.offsets(); }

  /// Sets the table for the next frame (at least the screen; offsets
  /// regenerated), e.g. from a host's own estimate before the first frame
  /// (an automatic table then skips its counting gather, and still adapts).
  /// Throws std::invalid_argument or GlError (beyond the context's limits).
  /// The table only; a window resize is resize_screen (GlFrameDriver), which
  /// also scales the table (GlHaTable::change_screen).
  void resize(Extent table);
  /// Runs the counting pass without clearing: the records in the table, by
  /// occlusion query.
  std::uint64_t count_stored();
  /// Slots widened to 64 bits (L32 records in the low half), row-major.
  [[nodiscard]] std::vector<std::uint64_t> read_table() const { return table_.read_table(); }
  /// The max-age table: one word per cell of block x block pixels, row-major.
  [[nodiscard]] std::vector<std::uint32_t> read_max_age() const { return table_.read_max_age(); }

 private:
  GlHaTable& table_;
};

}  // namespace habuffer::gl
