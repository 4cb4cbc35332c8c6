// The techniques' shared GLSL compiled a third time, over host arrays whose
// every access is recorded into a WarpRecorder (habuffer/harness/warp_traffic.h)
// at the address and with the kind the GPU path's environment gives it
// (gl/glsl/shaders/ha_env.glsl, techniques/*/gl/glsl/ *_env.glsl):
// the GPU traffic model runs the techniques' real insert, sort and composite
// code, not a re-implementation. Serial (one lane at a time), so plain loads
// and stores stand for the GPU's atomics; the kernels of hash_kernel.h and
// the techniques' *_kernel.h are untouched. Private to the harness.
#pragma once

#include <bit>
#include <cstdint>
#include <type_traits>

#include "habuffer/glsl_env.h"
#include "habuffer/hash_kernel.h"
#include "habuffer/harness/warp_traffic.h"
#include "habuffer/technique_params.h"

namespace habuffer::harness::traced {

/// Each buffer its own region of one address space, so no two buffers share a sector.
enum class Buffer : std::uint64_t {
  Counters = 1, Offsets, Table, MaxAge, Saturation, Heads, Nodes, Links, Counts, Layers, Occupancy, Limits
};
/// The byte address of `offset` in `b`.
inline std::uint64_t address(Buffer b, std::uint64_t offset) { return (static_cast<std::uint64_t>(b) << 44) + offset; }

/// Static access sites: accesses at different sites never share a warp instruction.
enum Site : std::uint16_t {
  kTally = 1, kHaOffset, kHaSlotLoad, kHaSlotAtomic, kHaMaxAgeRaise, kHaMaxAgeLoad, kSaturationLoad, kSaturationRaise,
  kNodeCounter, kHeadExchange, kHeadLoad, kHeadStore, kEntryLoad, kEntryStore, kLinkLoad, kLinkStore, kLinkSwap,
  kCountAdd, kCountLoad, kCountStore, kLayerLoad, kLayerStore, kOverflowNote, kOccupancyLoad, kOccupancyOr,
  kLimitLoad, kLimitStore
};

/// What every traced environment shares: the recorder and the outcome tally
/// of gl/glsl/shaders/entry_common.glsl (one reduction per call, striped by pixel).
class Tracer {
 public:
  explicit Tracer(WarpRecorder& r) : rec_(&r) {}
  /// Records one access (see WarpRecorder::record); a link of the chain when
  /// the lane waits for it: loads and atomics, not stores or reductions.
  void touch(Site site, Buffer b, std::uint64_t offset, AccessKind kind) const {
    rec_->record(site, address(b, offset), kind, kind == AccessKind::Load || kind == AccessKind::Atomic);
  }
  /// A load of a read-only buffer: no chain link (L1-resident on a GPU).
  void touch_constant(Site site, Buffer b, std::uint64_t offset) const {
    rec_->record(site, address(b, offset), AccessKind::Load, false);
  }
  /// Element i of `base`, one of buffer b's arrays: a recorded load.
  template <class T>
  T load(Site site, Buffer b, const T* base, std::uint64_t i) const {
    touch(site, b, sizeof(T) * i, AccessKind::Load);
    return base[i];
  }
  /// Element i of `base` set to v: a recorded store.
  template <class T>
  void store(Site site, Buffer b, T* base, std::uint64_t i, std::type_identity_t<T> v) const {
    touch(site, b, sizeof(T) * i, AccessKind::Store);
    base[i] = v;
  }
  /// habuffer_insert's tally of `outcome` at pixel (x, y): atomicAdd to the pixel's stripe.
  void tally(std::uint32_t x, std::uint32_t y, std::uint32_t outcome) const {
    if (outcome >= HABUFFER_OUTCOME_COUNT) return;
    const std::uint32_t stripe = (x + y * 5u) & (HABUFFER_COUNTER_STRIPES - 1u);
    touch(kTally, Buffer::Counters, 4ull * (stripe * HABUFFER_COUNTER_STRIDE + outcome), AccessKind::Reduction);
  }

 private:
  WarpRecorder* rec_;
};

/// A tracer whose technique keeps the saturation depth (shared/ha_saturation.glsl's
/// environment: a code per pixel, raised by atomic max).
class SaturationTracer : public Tracer {
 public:
  SaturationTracer(WarpRecorder& r, std::uint32_t* saturation) : Tracer(r), saturation_(saturation) {}
  uint ha_load_saturation(uint pixel) const {
    return load(kSaturationLoad, Buffer::Saturation, saturation_, pixel);
  }
  void ha_max_saturation(uint pixel, uint code) {
    touch(kSaturationRaise, Buffer::Saturation, 4ull * pixel, AccessKind::Reduction);
    if (saturation_[pixel] < code) saturation_[pixel] = code;
  }

 private:
  std::uint32_t* saturation_;
};

// The GPU path's defaults with native atomics (gl/module_variant.h): no plain
// slot load before a probe's atomicMax, one atomicMax per placement on the
// max-age cell, its result unused.
#pragma push_macro("HABUFFER_SLOT_READ_FIRST")
#undef HABUFFER_SLOT_READ_FIRST
#define HABUFFER_SLOT_READ_FIRST 0

/// The HA-buffer (shared/ha_*.glsl) over `Word` slots.
template <class Word>
class HashKernel : public SaturationTracer {
 public:
  HABUFFER_GLSL_CLASS_PRELUDE
  using ha_word = Word;
  using ha_index = std::uint64_t;

  HashKernel(const KernelParams& params, const glm::uvec2* offsets, Word* table, std::uint32_t* max_age,
             WarpRecorder& r)
      : SaturationTracer(r, params.saturation),
        habuffer_age_bits(params.age_bits),
        habuffer_coverage_bits(params.coverage_bits),
        ha_payload_bits(params.payload_bits),
        ha_table_size(params.table.x, params.table.y),
        ha_block(params.block),
        ha_max_age_cells_x(params.max_age_cells_x),
        habuffer_iter_limit(params.iter_limit),
        habuffer_cull_tau(params.cull_tau),
        habuffer_screen_size(params.screen.x, params.screen.y),
        habuffer_saturation(params.saturation != nullptr ? 1u : 0u),
        offsets_(offsets),
        table_(table),
        max_age_(max_age) {}

  static constexpr uint ha_word_bits = sizeof(Word) * 8;
  uint habuffer_age_bits;
  uint habuffer_coverage_bits;
  uint ha_payload_bits;
  uvec2 ha_table_size;
  uint ha_block;
  uint ha_max_age_cells_x;
  uint habuffer_iter_limit;
  float habuffer_cull_tau;
  uvec2 habuffer_screen_size;
  uint habuffer_saturation;

  uvec2 ha_offset(uint i) const {
    touch_constant(kHaOffset, Buffer::Offsets, 8ull * i);
    return offsets_[i];
  }
  uint ha_div_block(uint v) const { return v / ha_block; }
  Word ha_atomic_max_slot(ha_index s, Word r) {
    touch(kHaSlotAtomic, Buffer::Table, sizeof(Word) * s, AccessKind::Atomic);
    const Word old = table_[s];
    if (old < r) table_[s] = r;
    return old;
  }
  static uint ha_atomic_missed() { return 0u; }
  void ha_atomic_max_age(uint cell, uint age) {
    touch(kHaMaxAgeRaise, Buffer::MaxAge, 4ull * cell, AccessKind::Reduction);
    if (max_age_[cell] < age) max_age_[cell] = age;
  }
  Word ha_load_slot(ha_index s) const {
    return load(kHaSlotLoad, Buffer::Table, table_, s);
  }
  uint ha_load_max_age(uint cell) const {
    return load(kHaMaxAgeLoad, Buffer::MaxAge, max_age_, cell);
  }

#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_probe.glsl"
#include "habuffer/shared/ha_carry.glsl"
#include "habuffer/shared/ha_saturation.glsl"
#include "habuffer/shared/ha_insert.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/shared/ha_shadow.glsl"
#include "habuffer/shared/ha_traverse.glsl"

 private:
  const glm::uvec2* offsets_;
  Word* table_;
  std::uint32_t* max_age_;
};

#pragma pop_macro("HABUFFER_SLOT_READ_FIRST")

/// Linked lists, sorted after the gather or while inserting
/// (techniques/linked_lists/lists.glsl, sorted_lists.glsl), over the
/// GPU's buffers (lists_env.glsl): heads, 8-byte entries, 4-byte links, and
/// the node counter, one word of the counters buffer.
class ListsKernel : public KernelUniforms, public SaturationTracer {
 public:
  HABUFFER_GLSL_CLASS_PRELUDE
  HABUFFER_GLSL_CLASS_LOCAL_ARRAY
  using ha_word = std::uint64_t;
  static constexpr uint ha_word_bits = 64;

  ListsKernel(const KernelUniforms& u, std::uint32_t* heads, glm::uvec2* entries, std::uint32_t* next,
              std::uint32_t* saturation, WarpRecorder& r)
      : KernelUniforms(u), SaturationTracer(r, saturation), heads_(heads), entries_(entries), next_(next) {}

  uint ll_allocate_node() {
    touch(kNodeCounter, Buffer::Counters, 4ull * HABUFFER_COUNTER_NODES, AccessKind::Atomic);
    return nodes_++;
  }
  uint ll_exchange_head(uint pixel, uint link) {
    touch(kHeadExchange, Buffer::Heads, 4ull * pixel, AccessKind::Atomic);
    const uint old = heads_[pixel];
    heads_[pixel] = link;
    return old;
  }
  uint ll_load_head(uint pixel) const {
    return load(kHeadLoad, Buffer::Heads, heads_, pixel);
  }
  void ll_store_head(uint pixel, uint link) {
    store(kHeadStore, Buffer::Heads, heads_, pixel, link);
  }
  uvec2 ll_load_entry(uint node) const {
    return load(kEntryLoad, Buffer::Nodes, entries_, node);
  }
  void ll_store_entry(uint node, uvec2 e) {
    store(kEntryStore, Buffer::Nodes, entries_, node, e);
  }
  uint ll_load_next(uint node) const {
    return load(kLinkLoad, Buffer::Links, next_, node);
  }
  void ll_store_next(uint node, uint link) {
    store(kLinkStore, Buffer::Links, next_, node, link);
  }
  uint sl_load_link(uint pixel, uint where) const {
    if (where == 0) return ll_load_head(pixel);
    return ll_load_next(where - 1);
  }
  uint sl_swap_link(uint pixel, uint where, uint expected, uint link) {
    uint& w = where == 0 ? heads_[pixel] : next_[where - 1];
    touch(kLinkSwap, where == 0 ? Buffer::Heads : Buffer::Links, 4ull * (where == 0 ? pixel : where - 1),
          AccessKind::Atomic);
    const uint found = w;
    if (found == expected) w = link;
    return found;
  }

#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/shared/ha_entries.glsl"
#include "habuffer/techniques/linked_lists/lists.glsl"
#include "habuffer/shared/ha_saturation.glsl"
#include "habuffer/techniques/linked_lists/sorted_lists.glsl"

 private:
  std::uint32_t* heads_;
  glm::uvec2* entries_;
  std::uint32_t* next_;
  std::uint32_t nodes_ = 0;  // the node counter
};

/// Fixed per-pixel arrays (techniques/arrays/arrays.glsl) over the GPU's
/// buffers (arrays_env.glsl): a count per pixel, K layer-major entries.
class ArraysKernel : public KernelUniforms, public Tracer {
 public:
  HABUFFER_GLSL_CLASS_PRELUDE
  HABUFFER_GLSL_CLASS_LOCAL_ARRAY
  using ha_word = std::uint64_t;
  static constexpr uint ha_word_bits = 64;

  ArraysKernel(const KernelUniforms& u, std::uint32_t* counts, glm::uvec2* layers, WarpRecorder& r)
      : KernelUniforms(u), Tracer(r), counts_(counts), layers_(layers) {}

  uint fa_count_add(uint pixel) {
    touch(kCountAdd, Buffer::Counts, 4ull * pixel, AccessKind::Atomic);
    return counts_[pixel]++;
  }
  uint fa_load_count(uint pixel) const {
    return load(kCountLoad, Buffer::Counts, counts_, pixel);
  }
  void fa_store_count(uint pixel, uint n) {
    store(kCountStore, Buffer::Counts, counts_, pixel, n);
  }
  uvec2 fa_load_layer(uint slot) const {
    return load(kLayerLoad, Buffer::Layers, layers_, slot);
  }
  void fa_store_layer(uint slot, uvec2 e) {
    store(kLayerStore, Buffer::Layers, layers_, slot, e);
  }
  void fa_note_overflow(uint) { touch(kOverflowNote, Buffer::Counters, 4ull * HABUFFER_COUNTER_MOST_ARRIVED, AccessKind::Reduction); }

#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/shared/ha_entries.glsl"
#include "habuffer/techniques/arrays/arrays.glsl"

 private:
  std::uint32_t* counts_;
  glm::uvec2* layers_;
};

/// The k-buffer (techniques/kbuffer/kbuffer.glsl) over `Word` slots, K
/// per pixel, layer-major, with the occupancy map and limits of
/// kbuffer_env.glsl (its or: a load, then an atomicOr when a bit is missing).
template <class Word>
class KBufferKernel : public KernelUniforms, public Tracer {
 public:
  HABUFFER_GLSL_CLASS_PRELUDE
  using ha_word = Word;
  using ha_index = std::uint64_t;
  static constexpr uint ha_word_bits = sizeof(Word) * 8;

  KBufferKernel(const KernelUniforms& u, Word* slots, std::uint32_t* occupancy, std::uint32_t* limits,
                WarpRecorder& r)
      : KernelUniforms(u), Tracer(r), slots_(slots), occupancy_(occupancy), limits_(limits) {}

  Word ha_atomic_max_slot(ha_index s, Word r) {
    touch(kHaSlotAtomic, Buffer::Layers, sizeof(Word) * s, AccessKind::Atomic);
    const Word old = slots_[s];
    if (old < r) slots_[s] = r;
    return old;
  }
  static uint ha_atomic_missed() { return 0u; }
  Word ha_load_slot(ha_index s) const {
    return load(kHaSlotLoad, Buffer::Layers, slots_, s);
  }
  void kb_or_occupancy(uint word, uint bits) {
    touch(kOccupancyLoad, Buffer::Occupancy, 4ull * word, AccessKind::Load);
    if ((occupancy_[word] & bits) == bits) return;
    touch(kOccupancyOr, Buffer::Occupancy, 4ull * word, AccessKind::Reduction);
    occupancy_[word] |= bits;
  }
  uint kb_load_occupancy(uint word) const {
    return load(kOccupancyLoad, Buffer::Occupancy, occupancy_, word);
  }
  uint kb_load_limit(uint pixel) const {
    return load(kLimitLoad, Buffer::Limits, limits_, pixel);
  }
  void kb_store_limit(uint pixel, uint bucket) {
    store(kLimitStore, Buffer::Limits, limits_, pixel, bucket);
  }
  static uint ha_lowest_bit(uint w) { return static_cast<uint>(std::countr_zero(w)); }

#include "habuffer/shared/ha_record.glsl"
#include "habuffer/shared/ha_carry.glsl"
#include "habuffer/shared/ha_blend.glsl"
#include "habuffer/techniques/kbuffer/kbuffer.glsl"

 private:
  Word* slots_;
  std::uint32_t* occupancy_;
  std::uint32_t* limits_;
};

}  // namespace habuffer::harness::traced
