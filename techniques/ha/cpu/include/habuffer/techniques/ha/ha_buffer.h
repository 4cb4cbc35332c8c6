/// @file
/// The HA-buffer on the CPU: table T, max-age table M and offsets O of one
/// configuration, with concurrent insertion (SPEC 6), traversal and
/// compositing (SPEC 7) and clear-with-count (SPEC 8).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "habuffer/buffer_config.h"
#include "habuffer/fragment.h"
#include "habuffer/fragment_buffer.h"
#include "habuffer/max_age_table.h"
#include "habuffer/offset_sequence.h"

namespace habuffer {

/// The HA-buffer's CPU container (see above); move-only.
class HaBuffer final : public FragmentBuffer {
 public:
  /// Validates the configuration (BufferConfig::validate) and that the offsets
  /// were made for this table with one offset per age (AMAX of them).
  HaBuffer(const BufferConfig& config, OffsetSequence offsets);
  /// Releases T, M and O.
  ~HaBuffer() override;
  HaBuffer(HaBuffer&&) noexcept;
  HaBuffer& operator=(HaBuffer&&) noexcept;

  /// The configuration, with `table` resolved (never zero).
  [[nodiscard]] const BufferConfig& config() const;
  /// The configuration's record layout.
  [[nodiscard]] const RecordLayout& record_layout() const;
  /// The offsets O, one per age.
  [[nodiscard]] const OffsetSequence& offsets() const;
  /// FragmentBuffer interface (see fragment_buffer.h).
  [[nodiscard]] Technique technique() const override { return Technique::Ha; }
  [[nodiscard]] Extent screen() const override;
  /// The table H, in slots.
  [[nodiscard]] Extent table() const;

  /// Inserts a batch; throws std::out_of_range (naming the index and pixel) if
  /// any fragment lies off the screen, before inserting anything. Calls may
  /// overlap from any number of threads: Auto inserts with plain stores only
  /// while no other call changes the buffer, else through atomics beside the
  /// other atomic calls; Atomic calls run together; Serial and OwnerComputes
  /// calls (plain stores) run alone, overlapping calls waiting for them. The
  /// table is the same in every case (SPEC 9).
  Counters insert(std::span<const Fragment> fragments, const InsertOptions& options = {}) override;
  /// The order insert(fragments, options) uses: options.order, with Auto
  /// resolved (InsertOrder's rule; it reads the pixels the batch covers, in
  /// a pass over it). Throws std::invalid_argument for Pixel with
  /// OwnerComputes (whose owners follow the probes, not the pixels), and
  /// std::out_of_range for a fragment off the screen.
  [[nodiscard]] InsertOrder insert_order(std::span<const Fragment> fragments,
                                         const InsertOptions& options) const override;
  /// FragmentBuffer interface: the order the last insert() ran in.
  [[nodiscard]] InsertOrder last_insert_order() const override;
  /// FragmentBuffer interface: records, load, ages and the max-age table's largest cell.
  void measure(BuildReport& report) const override;
  /// FragmentBuffer interface: "table WxH".
  [[nodiscard]] std::string capacity_text() const override;
  /// Inserts one fragment and returns its HA_* outcome; may overlap other
  /// calls as insert() in the Auto mode does.
  std::uint32_t insert_one(const Fragment& fragment);

  /// Zeroes T and M; returns the number of records T held. Runs alone.
  std::uint64_t clear() override;
  /// Zeroes T and M without counting. Runs alone.
  void reset() override;
  /// FragmentBuffer interface: T's non-empty slots, counted.
  [[nodiscard]] std::uint64_t count_stored() const override;
  /// FragmentBuffer interface: slot_count().
  [[nodiscard]] std::uint64_t capacity() const override { return slot_count(); }
  /// The slots of T: Hx * Hy.
  [[nodiscard]] std::uint64_t slot_count() const;
  /// Slot s as an unsigned integer (L32 records in the low 32 bits).
  [[nodiscard]] std::uint64_t slot(std::uint64_t s) const;
  /// The max-age table M.
  [[nodiscard]] const MaxAgeTable& max_age() const;
  /// T's storage itself, read-only (zero-copy views: the Python module's
  /// table()): slot_count() words, row-major, each word_bytes wide (8 for
  /// L64, 4 for L32). Valid while the buffer lives (the storage never moves:
  /// a larger table is a new buffer); insert and clear change the words.
  struct TableWords {
    const void* data = nullptr;  ///< the first slot
    std::uint64_t slots = 0;     ///< Hx * Hy
    std::uint32_t word_bytes = 8;  ///< 8 (L64) or 4 (L32)
  };
  /// See TableWords.
  [[nodiscard]] TableWords table_words() const;

  /// Runs alone. Replaces T and M with state built elsewhere (the GPU path's read-back),
  /// so traversal, compositing and the dumps work on it. Throws
  /// std::invalid_argument, changing nothing, when the sizes differ from this
  /// buffer's or a word cannot be there: above 32 bits in an L32 buffer, a
  /// record of age 0, one whose age makes it a pixel off the screen or one
  /// beyond its pixel's max-age cell (traversal would miss it), a max-age
  /// cell above AMAX.
  void import_state(std::span<const std::uint64_t> table_words, std::span<const std::uint32_t> max_ages);

  /// Pixel (x, y)'s list, nearest first, by traversal (SPEC 7). Returns the
  /// slots read: the walk stops at the first age whose slot holds a younger
  /// record (Proposition A), before the cell's max age when it can. Throws
  /// std::out_of_range for a pixel off the screen; like every const call it
  /// may overlap other const calls, not insert, clear or import_state.
  std::uint32_t list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const override;
  /// Front-to-back float32 compositing of pixel (x, y) over `background`;
  /// throws std::out_of_range for a pixel off the screen.
  [[nodiscard]] glm::vec4 composite(std::uint32_t x, std::uint32_t y, glm::vec3 background) const;
  /// The whole screen, row-major (resolved per pixel when multisampled, as
  /// FragmentBuffer::composite_image).
  [[nodiscard]] std::vector<glm::vec4> composite_image(glm::vec3 background, std::uint32_t threads = 0) const;
  using FragmentBuffer::composite_image;
  /// Each pixel over its own background (row-major, screen area entries).
  [[nodiscard]] std::vector<glm::vec4> composite_pixels(std::span<const glm::vec3> backgrounds,
                                                       std::uint32_t threads = 0) const override;

  /// The light's transmittance at pixel (x, y) of a buffer built from a
  /// light's view, for a receiver whose depth code from the light is `code`:
  /// the product of (1 - alpha) over the records nearer than code + `bias`
  /// (shared/ha_traverse.glsl's ha_transmittance, the GPU path's very
  /// code). Throws std::out_of_range for a pixel off the screen and
  /// std::invalid_argument for L32 records, which carry no opacity.
  [[nodiscard]] float transmittance(std::uint32_t x, std::uint32_t y, std::uint32_t code, std::uint32_t bias) const;

  /// Stored records per age: result[a] for a = 0..AMAX (result[0] is 0).
  [[nodiscard]] std::vector<std::uint64_t> age_histogram() const;
  /// Bytes of T, M and O.
  [[nodiscard]] std::uint64_t memory_bytes() const override;
  /// FragmentBuffer interface: config() as a technique configuration.
  [[nodiscard]] TechniqueConfig technique_config() const override { return ha_technique_config(config()); }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Per pixel, row-major, the age of its deepest record (ages start at 1, so
/// 0 where the pixel holds none): the max-age heat maps of `render` and habuffer-view.
std::vector<std::uint32_t> max_age_per_pixel(const HaBuffer& buffer);

/// The coherent hash table `buffer` stores its records in, for what only such
/// a table has (ages, the max-age table, slot dumps), or nullptr. A capability
/// its technique's descriptor states (CapacityKind::TableSlots: its capacity
/// is a hash table's slots), not a hook of FragmentBuffer's: the generic
/// interface names no technique. Throws std::bad_cast should a container
/// whose descriptor says so not be an HaBuffer.
[[nodiscard]] const HaBuffer* as_hash_table(const FragmentBuffer& buffer);

}  // namespace habuffer
