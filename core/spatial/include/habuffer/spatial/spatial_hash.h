/// @file
/// The coherent hash as a general spatial hash table (issue 22): 2D or 3D
/// integer keys in a bounded domain, 32-bit values, on the HA-buffer's
/// coherent Robin Hood hashing (García, Lefebvre, Hornus, Lasram, *Coherent
/// Parallel Hashing*, 2011).
///
/// Design
/// ======
///
/// Keys and the table. A key is a point of the domain: (x, y) for 2D keys,
/// (x, y, z) for 3D ones, which are folded onto a 2D domain (FoldedDomain:
/// z slices laid side by side, so neighbours in x and y stay neighbours).
/// The table is Hx x Hy slots, smaller than the domain: a key k = (u, v) is
/// hashed to its position p = (u mod Hx, v mod Hy) and probes p + O[a - 1]
/// at ages a = 1, 2, ... (SPEC 3), so neighbouring keys probe neighbouring
/// slots (coherence: a sweep over an image's pixels walks the table in
/// order). Age equivalence (SPEC 4) gives p back from a record's slot and
/// age; the rest of the key is its quotient q = (u / Hx) + qx (v / Hy),
/// stored in the record. The record is one 64-bit word compared as an
/// unsigned integer, | age | quotient | live | value | (sh_spatial.glsl),
/// and the insert is SPEC 6's atomicMax loop over it: the table is the same
/// for every insertion order and thread count (SPEC 9's deferred-acceptance
/// argument; docs/spec-notes.md, "The spatial hash", gives the proofs).
///
/// One key once. Two records of one key meet in a slot (they walk the same
/// probes and the larger one is refused wherever the smaller one is), and
/// the larger stays. The rules are encodings of "larger": Max stores the
/// value, Min its complement, and First and Last (by position in the batch)
/// deduplicate a batch through a table of batch indexes before merging it:
/// every rule gives the same table for every thread count.
///
/// Lookups read ages 1 .. M[cell(p)] of the max-age table and stop at the
/// first slot younger than the age probed (SPEC 7's early stop), so an absent
/// key costs a few probes, not AMAX.
///
/// Misses in one line (issue 36). A few probes are still two or three slots
/// at random places, where a table of control bytes (absl) answers a miss
/// from one byte. The miss filter (`miss_filter_bits`: 16 bits a slot by
/// default, 8, or none) is a blocked Bloom filter laid over the table's
/// positions: one 64-byte line per 8 x 4 positions (8 x 8 at 8 bits), each
/// key 4 bits of its position's 32-bit word: one in its position's own
/// field, chosen by the quotient (exact where the domain has at most 8
/// quotients, 4 at 8 bits), 3 hashed into the word's shared half
/// (sh_spatial.glsl). Every insert call sets its key's bits; a lookup reads
/// that word first and, when a bit is clear, answers "absent" without the
/// max-age cell or any slot. Neighbouring keys read the same line, so
/// row-major and neighbourhood misses stay coherent. Measured beside an
/// occupancy bit and a fingerprint byte per position (docs/performance.md,
/// issue 36): an occupancy bit cannot tell apart the keys that share a
/// position (a table smaller than the domain puts several there: 57-62 %
/// of misses pass), a byte a position lets 11 % of the voxel shell's misses
/// through, this filter 1.7 % (7.4 % at 8 bits), and none of the sparse
/// image's. Hits pay the filter's word too (about a third slower at load
/// 0.95 on this project's VM): a table looked up mostly for keys it holds
/// is faster with `miss_filter_bits` 0. The filter is
/// derived state: it holds every record's key and possibly keys since
/// pushed out (only a rebuild or clear() empties it), no answer depends on
/// it, and restore() and set_miss_filter() make it again from the records
/// (files hold none: their format is unchanged).
///
/// Erase leaves a tombstone: the key's age and quotient with live 0 and value
/// 0. Every other key compares with it as with the erased key, so the Robin
/// Hood order of the table (and every lookup's early stop) is unchanged; the
/// key inserted again replaces it; rehash and compact() drop tombstones.
/// Shifting records back instead would need, for each hole, the records of
/// other positions that were refused there, which no slot names.
///
/// Sizing. The table is sized for the keys at `target_load`; with `adaptive`
/// an insert that would pass `grow_at` rehashes to 25 % more area (or what the
/// keys need), and an erase that leaves the live load under `shrink_at`
/// rehashes 25 % smaller (SPEC 8's 80/30 rule). An insert whose call fails
/// (a record past AMAX ages, or the iteration limit) is never dropped
/// silently: with `lossless` (the default) the table grows and every key is
/// inserted again, up to `max_growths` times; without it the lost keys are
/// counted in the report.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "habuffer/extent.h"
#include "habuffer/offset_sequence.h"
#include "habuffer/spatial/sh_constants.h"
#include "habuffer/spatial/spatial_hash_kernel.h"

namespace habuffer::spatial {

/// The key space: 0 <= x < size.x, 0 <= y < size.y, 0 <= z < size.z (size.z
/// 1 for 2D keys).
struct Domain {
  std::uint32_t x = 0, y = 0, z = 1;
  friend bool operator==(const Domain&, const Domain&) = default;
  /// "XxY" or "XxYxZ".
  [[nodiscard]] std::string str() const;
};

/// 3D keys on a 2D domain: each group of G consecutive z slices (G the
/// largest power of two up to min(Dz, 4)) is interleaved along x (key
/// (x, y, z) at column x G + z mod G of its group, so x-neighbours lie G
/// columns apart and z-neighbours in a group side by side), and the groups
/// are laid side by side, F per row, F chosen so that the folded domain is
/// about square. 2D keys (Dz = 1) fold to themselves. No hardware divide on
/// the way: G is a shift, F a FastDivisor.
class FoldedDomain {
 public:
  /// Slices interleaved along x at most.
  static constexpr std::uint32_t kInterleave = 4;
  /// Throws std::invalid_argument for a zero side, or a folded side of 2^32
  /// or more, naming the sizes.
  explicit FoldedDomain(Domain domain);
  FoldedDomain() = default;
  [[nodiscard]] Domain domain() const { return domain_; }
  /// The folded 2D domain (Du, Dv).
  [[nodiscard]] Extent folded() const { return folded_; }
  /// Groups of slices per row of the fold (F).
  [[nodiscard]] std::uint32_t slices_per_row() const { return per_row_; }
  /// Slices interleaved along x (G).
  [[nodiscard]] std::uint32_t interleave() const { return 1u << shift_; }
  [[nodiscard]] bool contains(glm::uvec3 k) const { return k.x < domain_.x && k.y < domain_.y && k.z < domain_.z; }
  [[nodiscard]] glm::uvec2 fold(glm::uvec3 k) const {
    if (domain_.z == 1) return {k.x, k.y};
    const std::uint32_t group = k.z >> shift_, slice = k.z & ((1u << shift_) - 1u);
    const std::uint32_t row = rows_.div(group), col = group - row * per_row_;
    return {(k.x << shift_) + slice + (domain_.x << shift_) * col, k.y + domain_.y * row};
  }
  [[nodiscard]] glm::uvec3 unfold(glm::uvec2 f) const {
    if (domain_.z == 1) return {f.x, f.y, 0u};
    const std::uint32_t width = domain_.x << shift_;
    const std::uint32_t col = f.x / width, rest = f.x - col * width, row = f.y / domain_.y;
    return {rest >> shift_, f.y - row * domain_.y, ((row * per_row_ + col) << shift_) + (rest & ((1u << shift_) - 1u))};
  }

 private:
  Domain domain_;
  Extent folded_;
  std::uint32_t per_row_ = 1, shift_ = 0;
  FastDivisor rows_;  // group / F
};

/// Which value a key inserted twice keeps.
enum class DuplicateRule {
  Max,    ///< the larger value
  Min,    ///< the smaller value
  First,  ///< the value inserted first (a batch's earlier index; the table's over a batch's)
  Last,   ///< the value inserted last (a batch's later index; a batch's over the table's)
};
/// "max", "min", "first", "last".
std::string to_string(DuplicateRule rule);
/// The rule named `text`; std::nullopt for another word.
std::optional<DuplicateRule> parse_duplicate_rule(const std::string& text);

/// What a table is made with.
struct SpatialHashConfig {
  Domain domain;                                        ///< the key space
  DuplicateRule rule = DuplicateRule::Last;             ///< one key once: which value stays
  std::uint32_t age_bits = HABUFFER_SH_DEFAULT_AGE_BITS;         ///< A: AMAX = 2^A - 1 probes; quotients get 31 - A bits
  std::uint32_t block = 8;                              ///< the max-age table's block side (SPEC 5)
  OffsetGenerator offsets = OffsetGenerator::Random;    ///< random or farthest (SPEC 3)
  std::uint64_t seed = 1;                               ///< the offsets' seed
  double target_load = 0.8;                             ///< the load a table is sized for
  bool adaptive = true;                                 ///< rehash by grow_at / shrink_at after a change
  double grow_at = 0.8;                                 ///< adaptive: grow when an insert would pass this load
  double shrink_at = 0.3;                               ///< adaptive: shrink when an erase leaves the live load under this
  bool lossless = true;                                 ///< grow and insert again when a call fails
  std::uint32_t max_growths = 24;                       ///< lossless: growths of one insert before it throws
  std::uint32_t iter_limit = HABUFFER_SH_DEFAULT_ITER_LIMIT;     ///< probes of one insert call (SPEC 6's LIMIT)
  std::uint32_t threads = 0;                            ///< inserting and querying threads, 0..kMaxThreads; 0: the default count
  /// The miss filter's bits a slot: 16, 8 or 0 (none); see the file comment.
  std::uint32_t miss_filter_bits = HABUFFER_SH_DEFAULT_FILTER_BITS;

  /// Throws std::invalid_argument naming the field and its bounds.
  void validate() const;
};

/// The counters of one insert (or of a table's life: SpatialHash::totals()).
struct InsertReport {
  std::uint64_t calls = 0;              ///< records inserted (the batch's keys)
  std::uint64_t stored = 0;             ///< keys new to the table
  std::uint64_t duplicates = 0;         ///< records of a key already there or in the batch (one kept by the rule)
  std::uint64_t failed_age = 0;         ///< calls that ended past AMAX (inserted again when lossless)
  std::uint64_t failed_iter = 0;        ///< calls that ended at the iteration limit (inserted again when lossless)
  std::uint64_t lost = 0;               ///< keys not in the table afterwards (lossless: always 0)
  std::uint64_t tombstones_dropped = 0; ///< erased keys' markers pushed out (they hold no key)
  std::uint32_t rehashes = 0;           ///< tables built anew (adaptive sizing and lossless growth)
  InsertReport& operator+=(const InsertReport& o);
};

/// A table's state.
struct SpatialHashStats {
  Extent table;                     ///< H
  std::uint64_t slots = 0;          ///< Hx * Hy
  std::uint64_t keys = 0;           ///< live keys
  std::uint64_t tombstones = 0;     ///< erased keys' markers
  double load = 0.0;                ///< (keys + tombstones) / slots
  std::uint32_t max_age = 0;        ///< the oldest record's age
  double mean_age = 0.0;            ///< over live keys (1: every key at its first probe)
  std::vector<std::uint64_t> ages;  ///< live keys per age, ages[a] for a = 0..AMAX (ages[0] = 0)
  std::uint32_t quotient_bits = 0;  ///< bits the domain's quotients need (at most 31 - A)
  std::uint64_t memory_bytes = 0;   ///< table, max-age cells, miss filter and offsets
  double bytes_per_key = 0.0;       ///< memory_bytes / keys
};

/// One key and its value.
struct Entry {
  glm::uvec3 key{0};
  std::uint32_t value = 0;
  friend bool operator==(const Entry&, const Entry&) = default;
};

class SpatialHash;

/// A non-owning, read-only view of a table for lookups in a hot loop (the
/// owner's find() checks and throws; this one inlines the probe loop). Valid
/// while the table is neither changed nor destroyed. A key outside the
/// domain is absent here.
class SpatialHashView {
 public:
  explicit SpatialHashView(const SpatialHash& table);
  /// The key's value, or nothing.
  [[nodiscard]] std::optional<std::uint32_t> find(glm::uvec3 key) const {
    if (!fold_.contains(key)) return std::nullopt;
    std::uint32_t probes = 0;
    const std::uint64_t s = kernel_.sh_find_slot(fold_.fold(key), probes);
    if (s == ~std::uint64_t{0}) return std::nullopt;
    const std::uint64_t r = slots_[s];
    if ((r >> 32 & 1u) == 0u) return std::nullopt;  // a tombstone
    return complement_ ? ~static_cast<std::uint32_t>(r) : static_cast<std::uint32_t>(r);
  }
  [[nodiscard]] bool contains(glm::uvec3 key) const { return find(key).has_value(); }
  /// Asks the cache for the key's filter word, first probe and max-age cell: a batch
  /// of scattered lookups issues it some keys ahead, so their memory
  /// latencies overlap.
  void prefetch(glm::uvec3 key) const {
    if (!fold_.contains(key)) return;
    const glm::uvec2 p = kernel_.sh_position(fold_.fold(key));
    if (filter_ != nullptr) __builtin_prefetch(filter_ + kernel_.sh_filter_word(p));
    __builtin_prefetch(max_age_ + kernel_.ha_cell(p));
    __builtin_prefetch(slots_ + kernel_.ha_slot(kernel_.ha_probe(p, 1u)));
  }

 private:
  mutable SpatialHashKernel<false> kernel_;  // its finds only read
  FoldedDomain fold_;
  const std::uint64_t* slots_;
  const std::uint32_t* max_age_;
  const std::uint32_t* filter_;  // null without a miss filter
  bool complement_;
};

/// The owning table (see the file comment).
class SpatialHash {
 public:
  /// The largest table this container allocates (8 bytes a slot): 2^33 slots, 64 GiB.
  static constexpr std::uint64_t kMaxSlots = std::uint64_t{1} << 33;

  /// An empty table sized for `capacity` keys at the target load (at least
  /// one slot). Throws std::invalid_argument for a bad config.
  explicit SpatialHash(SpatialHashConfig config, std::uint64_t capacity = 0);

  /// Inserts keys[i] with values[i] (values empty: every value 0, a set),
  /// concurrently. Throws std::invalid_argument naming the first key outside
  /// the domain (nothing inserted), or sizes that differ; std::runtime_error
  /// when lossless growth gives up (the table keeps every key it held before).
  InsertReport insert(std::span<const glm::uvec3> keys, std::span<const std::uint32_t> values = {});
  /// One key.
  InsertReport insert(glm::uvec3 key, std::uint32_t value = 0);

  /// The key's value, or nothing. Throws std::invalid_argument for a key outside the domain.
  [[nodiscard]] std::optional<std::uint32_t> find(glm::uvec3 key) const;
  [[nodiscard]] bool contains(glm::uvec3 key) const { return find(key).has_value(); }
  /// Batched find, concurrently: values[i] and found[i] (1 or 0) for keys[i];
  /// values[i] is 0 where absent. Returns the keys found. Throws
  /// std::invalid_argument naming the first key outside the domain or sizes that differ.
  std::uint64_t find(std::span<const glm::uvec3> keys, std::span<std::uint32_t> values,
                     std::span<std::uint8_t> found) const;
  /// Probes a find of `key` makes (slots read), for the statistics.
  [[nodiscard]] std::uint32_t probes(glm::uvec3 key) const;

  /// Erases the key (a tombstone; see the file comment); whether it was there.
  bool erase(glm::uvec3 key);
  /// Erases keys; returns how many were there.
  std::uint64_t erase(std::span<const glm::uvec3> keys);
  /// Rebuilds the table at its size without tombstones.
  void compact();
  /// Rebuilds the table at `table` slots (every key kept; lossless growth beyond it if needed).
  void rehash(Extent table);
  /// Rebuilds for `keys` keys at `load`.
  void reserve(std::uint64_t keys, double load);
  /// Removes every key; the table keeps its size.
  void clear();

  /// Calls f(Entry) for every key, in slot order.
  template <class F>
  void for_each(F f) const {
    SpatialHashKernel<false> k = reader();
    for (std::uint64_t s = 0; s < table_.size(); ++s)
      if (const std::optional<Entry> e = entry_at(k, s)) f(*e);
  }
  /// Every key, in slot order.
  [[nodiscard]] std::vector<Entry> entries() const;
  /// The keys of the cube of side 2 radius + 1 around `centre` (clipped to the
  /// domain) that are in the table, x fastest (neighbours in x probe
  /// neighbouring slots). Throws std::invalid_argument for a centre outside
  /// the domain or a radius above 64.
  [[nodiscard]] std::vector<Entry> neighbourhood(glm::uvec3 centre, std::uint32_t radius) const;

  [[nodiscard]] std::uint64_t size() const { return live_; }
  [[nodiscard]] bool empty() const { return live_ == 0; }
  [[nodiscard]] std::uint64_t slots() const { return table_.size(); }
  [[nodiscard]] Extent table_extent() const { return extent_; }
  [[nodiscard]] double load() const;
  /// Erased keys' markers in the table (they count in the load).
  [[nodiscard]] std::uint64_t tombstones() const { return tombstones_; }
  [[nodiscard]] std::uint64_t memory_bytes() const;
  [[nodiscard]] SpatialHashStats stats() const;
  [[nodiscard]] const SpatialHashConfig& config() const { return config_; }
  /// The threads of later inserts and batched finds (0: the default count),
  /// the table unchanged (a loaded table's own, say). Throws
  /// std::invalid_argument above kMaxThreads.
  void set_threads(std::uint32_t threads);
  /// Makes the miss filter again from the records at `bits` bits a slot
  /// (16, 8; 0 drops it), the table unchanged: lookups answer the same,
  /// misses at another cost. Files hold no filter: a loaded table gets the
  /// default `miss_filter_bits`. Throws std::invalid_argument for other bits.
  void set_miss_filter(std::uint32_t bits);
  [[nodiscard]] const FoldedDomain& domain() const { return fold_; }
  /// Counters summed over every insert since construction.
  [[nodiscard]] const InsertReport& totals() const { return totals_; }
  /// The slots, row-major (records as sh_spatial.glsl packs them; the values
  /// as the rule encodes them: Min stores complements).
  [[nodiscard]] std::span<const std::uint64_t> table() const { return table_; }
  /// The max-age cells, row-major over ceil(Hx / B) x ceil(Hy / B).
  [[nodiscard]] std::span<const std::uint32_t> max_age() const { return max_age_; }
  /// The miss filter's words, 16 per block of 8 x 4 positions (8 x 8 at 8
  /// bits a slot), blocks row-major (sh_spatial.glsl); empty without one.
  [[nodiscard]] std::span<const std::uint32_t> filter() const { return filter_; }
  [[nodiscard]] const OffsetSequence& offsets() const { return *offsets_; }
  /// qx = ceil(Du / Hx): quotients per row of table tiles.
  [[nodiscard]] std::uint32_t quotient_x() const { return quotient_x_; }
  /// The kernel's parameters for this table (the GPU path's uniforms too).
  [[nodiscard]] const SpatialKernelParams& kernel_params() const { return *params_; }
  /// A lookup view (see SpatialHashView).
  [[nodiscard]] SpatialHashView view() const { return SpatialHashView(*this); }

  /// A table from its parts (a saved table): `config` as made, the table's
  /// extent, its slots and its max-age cells. Every record is checked (its
  /// age, its quotient, its key in the domain, its max-age cell covering its
  /// age); throws std::invalid_argument naming the first slot or size that
  /// is wrong. The miss filter is made from the records.
  static SpatialHash restore(SpatialHashConfig config, Extent table, std::vector<std::uint64_t> slots,
                             std::vector<std::uint32_t> max_age);

  /// The table for `keys` keys at `load` over a folded domain (the aspect of
  /// the domain, at most the domain, large enough for the quotients to fit
  /// 31 - age_bits bits). Throws std::invalid_argument when no table fits.
  static Extent table_for(const FoldedDomain& fold, std::uint32_t age_bits, std::uint64_t keys, double load);
  /// The bytes a table of `table` slots made with `config` holds (its
  /// memory_bytes(): slots, max-age cells, miss filter and offsets), saturating: what a
  /// caller checks against the machine before making it.
  static std::uint64_t memory_for(const SpatialHashConfig& config, Extent table);

 private:
  // A table of `table` slots (restore: no sizing from a key count).
  SpatialHash(SpatialHashConfig config, Extent table, bool);
  struct Pending {
    glm::uvec2 key;       // folded
    std::uint32_t word;   // stored value (encoded)
  };
  void reset(Extent table);
  void check_key(glm::uvec3 key, std::size_t index, bool batch) const;
  [[nodiscard]] std::optional<Entry> entry_at(SpatialHashKernel<false>& kernel, std::uint64_t slot) const;
  [[nodiscard]] std::uint64_t find_slot(glm::uvec2 folded) const;
  [[nodiscard]] std::uint32_t decode(std::uint32_t word) const;
  [[nodiscard]] std::uint32_t encode(std::uint32_t value) const;
  [[nodiscard]] std::vector<Pending> live_records() const;
  // The miss filter made again from the records (restore, set_miss_filter).
  void fill_filter();
  // Inserts distinct-or-ruled records as they are (the atomicMax loop),
  // growing losslessly; `report` gets the counts.
  void insert_records(std::vector<Pending> records, InsertReport& report);
  // One concurrent pass of records into the current table; returns the live
  // records dropped (failed calls).
  std::vector<Pending> insert_pass(std::span<const Pending> records, InsertReport& report);
  void rebuild(Extent table, std::vector<Pending> extra, InsertReport& report);
  void grow_if_needed(std::uint64_t incoming, InsertReport& report);
  void shrink_if_needed();
  [[nodiscard]] std::uint32_t threads() const;
  // A kernel over this table for reads (plain loads).
  [[nodiscard]] SpatialHashKernel<false> reader() const;

  SpatialHashConfig config_;
  FoldedDomain fold_;
  Extent extent_;
  std::uint32_t quotient_x_ = 1;
  std::optional<OffsetSequence> offsets_;  // always set (reset() makes them per table)
  std::optional<SpatialKernelParams> params_;  // always set, with the table (reset())
  std::vector<std::uint64_t> table_;
  std::vector<std::uint32_t> max_age_;
  std::vector<std::uint32_t> filter_;  // the miss filter (empty without one)
  std::uint32_t cells_x_ = 1;
  std::uint64_t live_ = 0, tombstones_ = 0;
  InsertReport totals_;
};

}  // namespace habuffer::spatial
