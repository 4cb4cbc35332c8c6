/// @file
/// The one interface every technique's CPU container implements: insert a
/// stream (counting every outcome, SPEC invariant 1), read each pixel's sorted
/// list, composite, clear and say its memory. Lists of every technique are
/// the same (code, data) entries in the same order, identical entries merged,
/// so an exact technique's lists equal the HA-buffer's when nothing is dropped.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "habuffer/extent.h"
#include "habuffer/fragment.h"
#include "habuffer/insert_gate.h"
#include "habuffer/parallel.h"
#include "habuffer/technique.h"

namespace habuffer {

class HaBuffer;
struct BuildReport;

/// Every mode builds the same result (SPEC 9); they differ in speed only.
/// docs/performance.md compares them. Each is safe when insert() calls
/// overlap on one container (insert_gate.h): the modes with plain stores
/// then run alone, the others wait for them.
enum class InsertMode {
  /// HA-buffer: Serial for one thread while no other call changes the
  /// container, else Atomic (beside any other atomic call): correct when
  /// calls overlap. Other techniques on several threads: rows of pixels
  /// dealt out to the threads, each inserting its own pixels' fragments in
  /// stream order with plain stores, so the result is one thread's, bit for
  /// bit (core/model/include/habuffer/detail/technique_parallel.h); the call runs alone.
  Auto,
  Serial,         ///< one thread, plain loads and stores (in the InsertOrder); the call runs alone
  Atomic,         ///< the GPU's model: threads split the stream and share every slot through atomics
  OwnerComputes,  ///< HA-buffer only: no atomics, table rows dealt out to threads (owner_computes.h); runs alone
};

/// The order the HA-buffer inserts a batch in (issue 26). Without early cull
/// and failures both give the same table, max-age table and counters (SPEC
/// 9); they differ in speed, and in the probes made (the statistics of
/// probes per fragment describe the arrival process).
enum class InsertOrder {
  /// Pixel where it pays: a batch of at least kPixelOrderMinFragments, with
  /// one fragment per kPixelOrderPixelsPerFragment screen pixels or more
  /// (bucketing touches every pixel once), and at least kPixelOrderMinDepth
  /// fragments per pixel it covers (shallow pixels probe about once each in
  /// arrival order: there bucketing costs more than the jump start saves;
  /// the covered pixels are counted in the on-screen check's pass). Under
  /// early cull too: there pixel order is another conservative schedule of
  /// SPEC 6's rules (it culls at least what arrival order culls and keeps
  /// SPEC invariant 5's bound; docs/spec-notes.md). Else, and for
  /// owner-computes insertion, Arrival.
  Auto,
  Arrival,  ///< the batch's order: each fragment probes from age 1
  /// Bucketed by pixel, nearest first, each record started one age past
  /// where its pixel's previous record was first written (the "jump start";
  /// docs/spec-notes.md has the proof). With early cull, a different
  /// schedule of the same rules (no jump start): culls can only grow.
  Pixel,
};

/// The mode named "auto", "serial", "atomic" or "owner" (OwnerComputes);
/// nullopt for anything else.
std::optional<InsertMode> parse_insert_mode(std::string_view name);

/// "auto", "arrival", "pixel".
std::string to_string(InsertOrder order);
/// The order named `name`; nullopt for anything else.
std::optional<InsertOrder> parse_insert_order(std::string_view name);
/// Auto's rule: smaller batches insert in arrival order, since bucketing
/// touches every pixel of the screen once.
inline constexpr std::uint64_t kPixelOrderMinFragments = 64;
/// Auto's rule (see kPixelOrderMinFragments).
inline constexpr std::uint64_t kPixelOrderPixelsPerFragment = 16;
/// Auto's rule: fragments per covered pixel below which arrival order is
/// faster (measured on the CPU path, issue 36: spider, 1.15 probes a record,
/// 0.68x in arrival order; wuson 0.85x; engine and hairball, 2.8-3.0, faster
/// in pixel order).
inline constexpr double kPixelOrderMinDepth = 3.5;
/// Pixel order without early cull interleaves several pixels per thread
/// (latency hiding: a slot's miss overlaps other pixels' probes) when the
/// table no longer fits this machine's L2 (cache_sizes.h; techniques/ha/cpu/src/pixel_order.h,
/// InterleaveRule), unless InsertOptions::interleave says otherwise; within
/// the L2 interleaving only adds work (docs/performance.md, issues 26 and 36).

/// Pixels one thread interleaves when pixel order hides latency (AMAC-style):
/// enough independent probes in flight to cover a miss to memory.
inline constexpr std::size_t kInterleavedPixels = 16;

/// The probe step pixel order's jump start runs (issue 36). Both give the
/// same table, max-age table and counters; they differ in speed.
enum class InsertStep {
  /// techniques/ha/cpu/src/jump_start_lanes.h: the step written out for the cull-free jump
  /// start (one load per probe, each lane's next slot computed once).
  Specialised,
  /// The shared GLSL step (ha_insert_step_at), which every path runs: the
  /// reference the tests hold the specialised one to.
  Shared,
};

/// How FragmentBuffer::insert runs a batch.
struct InsertOptions {
  std::uint32_t threads = 1;  ///< 0: the default count for the batch (resolve_threads(threads, work))
  InsertMode mode = InsertMode::Auto;  ///< how the threads share the buffer
  InsertOrder order = InsertOrder::Auto;  ///< the HA-buffer's order (others insert in arrival order)
  /// Pixel order: interleave pixels on each thread (true), or not (false);
  /// nullopt: by the table's size against the L2 (InterleaveRule). The same table either way.
  std::optional<bool> interleave;
  /// Pixel order without early cull: the jump start's probe step. The same table either way.
  InsertStep step = InsertStep::Specialised;
  std::uint32_t band_rows = 16;  ///< OwnerComputes: table rows per band; other techniques' Auto: screen rows
};

/// Auto's rule as a function of what it reads: the order for a batch of
/// `fragments` covering `covered_pixels` of `screen` (mode: owner-computes
/// has no pixel order). Explicit orders are returned as they are.
InsertOrder choose_insert_order(const InsertOptions& options, std::uint64_t fragments, std::uint64_t covered_pixels,
                                Extent screen);
/// Whether Auto's rule needs the covered pixels at all (a batch too small
/// for pixel order, an explicit order or owner-computes does not).
bool insert_order_needs_coverage(const InsertOptions& options, std::uint64_t fragments, Extent screen);

/// One record of a pixel's list, front to back. `age` is the HA-buffer's
/// (1-based probe count); other techniques give 0.
struct ListEntry {
  std::uint32_t age = 0;  ///< HA-buffer: the record's age; 0 for other techniques
  std::uint32_t code = 0;  ///< depth code (SPEC 2): larger is nearer
  std::uint32_t data = 0;  ///< data word (0 for L32)
  /// Memberwise equality.
  friend bool operator==(const ListEntry&, const ListEntry&) = default;
};

/// A technique's CPU container, used through this interface (see above).
class FragmentBuffer {
 public:
  /// Containers are deleted through this interface.
  virtual ~FragmentBuffer() = default;

  /// The technique this container implements.
  [[nodiscard]] virtual Technique technique() const = 0;
  /// The screen, in pixels.
  [[nodiscard]] virtual Extent screen() const = 0;

  /// Inserts a batch (and, for techniques that sort afterwards, sorts the
  /// touched lists, merging identical entries as duplicates). Throws
  /// std::out_of_range naming the first fragment off the screen, before
  /// inserting anything. Calls may overlap on one container from any number
  /// of threads: the HA-buffer's atomic calls run together, every other call
  /// runs alone, an overlapping call waiting for it (insert_gate.h); the
  /// counters of the calls add up to one call's over their fragments.
  virtual Counters insert(std::span<const Fragment> fragments, const InsertOptions& options = {}) = 0;
  /// Empties the buffer; returns the records it held. Runs alone (waits for
  /// overlapping insert() calls).
  virtual std::uint64_t clear() = 0;
  /// Empties the buffer without counting what it held (a frame's start when
  /// nobody reads the count; the HA-buffer's count walks the whole table).
  /// Runs alone. Containers that count for free use clear().
  virtual void reset() { (void)clear(); }
  /// The records held now, counted on the buffer.
  [[nodiscard]] virtual std::uint64_t count_stored() const = 0;
  /// Records the buffer can hold in all (slots, nodes, layers of every pixel).
  [[nodiscard]] virtual std::uint64_t capacity() const = 0;

  /// Pixel (x, y)'s list, nearest first; returns the storage words read to
  /// find it. Throws std::out_of_range for a pixel off the screen. This and
  /// the other const calls may overlap each other, not a call that changes
  /// the container (insert, clear, import_state).
  virtual std::uint32_t list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const = 0;
  /// Each pixel over its own background (row-major, screen area entries).
  /// One sample per pixel: the technique's composite_pixels. A multisampled
  /// buffer (BufferConfig::samples above 1) resolves per pixel: each pixel's
  /// list (list()) walked once, every sample compositing the records its
  /// mask names, the samples averaged (ha_blend.glsl's ha_samples_*).
  /// Throws std::invalid_argument unless there is one background per pixel.
  [[nodiscard]] std::vector<glm::vec4> composite_image(std::span<const glm::vec3> backgrounds,
                                                       std::uint32_t threads = 0) const;
  /// Each pixel over its own background by the technique's own walk, every
  /// record blended whatever its coverage mask (one sample per pixel).
  [[nodiscard]] virtual std::vector<glm::vec4> composite_pixels(std::span<const glm::vec3> backgrounds,
                                                                std::uint32_t threads = 0) const = 0;
  /// Bytes of every buffer the technique allocated.
  [[nodiscard]] virtual std::uint64_t memory_bytes() const = 0;
  /// What the last insert asked for beyond what the container held (nodes
  /// of a pool, layers of the deepest pixel): lossless mode sizes the next
  /// attempt from it (TechniqueConfig::grown). Containers that grow by a
  /// rule of their own (the HA-buffer's table, the k-buffer's K) say nothing.
  [[nodiscard]] virtual GrowthNeed growth_need() const { return {}; }
  /// The order insert(fragments, options) would use for a batch of
  /// `fragments` (InsertOrder's rule): arrival order unless the container
  /// orders batches itself (the HA-buffer).
  [[nodiscard]] virtual InsertOrder insert_order(std::span<const Fragment> fragments,
                                                 const InsertOptions& options) const {
    (void)fragments, (void)options;
    return InsertOrder::Arrival;
  }
  /// The order the last insert() call ran in (Arrival before any, and for
  /// containers that do not order batches).
  [[nodiscard]] virtual InsertOrder last_insert_order() const { return InsertOrder::Arrival; }
  /// Fills what build_report.h's summarize() measures on the container
  /// itself: records held and load by default; the HA-buffer adds its ages.
  virtual void measure(BuildReport& report) const;
  /// "table 1859x1859" or "777 records": what the container holds, for messages.
  [[nodiscard]] virtual std::string capacity_text() const;
  /// The configuration it holds now (sizes grown by lossless builds included).
  [[nodiscard]] virtual TechniqueConfig technique_config() const = 0;

 protected:
  /// Overlapping calls that change the container hold it (insert_gate.h).
  InsertGate gate_;
};

/// A multisampled pixel's per-pixel resolve (FragmentBuffer::composite_image's
/// for one pixel): `records`, the pixel's list nearest first, each blended
/// into the samples of its mask (a sample's repeat of the depth code and data
/// it blended last skipped), every sample finished over `background`, the
/// mean of the layout's samples.
[[nodiscard]] glm::vec4 resolve_samples(std::span<const ListEntry> records, const RecordLayout& layout,
                                        glm::vec3 background);

/// Throws std::out_of_range naming the first fragment outside `screen`.
void check_on_screen(std::span<const Fragment> fragments, Extent screen);
/// Throws std::out_of_range naming pixel (x, y) and `screen` when the pixel
/// lies outside it (every per-pixel call checks its pixel so).
void check_pixel(std::uint32_t x, std::uint32_t y, Extent screen);

}  // namespace habuffer
