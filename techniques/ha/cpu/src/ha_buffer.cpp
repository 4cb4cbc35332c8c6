#include "habuffer/techniques/ha/ha_buffer.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>


#include "habuffer/build_report.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/cache_sizes.h"
#include "habuffer/hash_kernel.h"
#include "habuffer/slot_storage.h"
#include "habuffer/techniques/ha/owner_computes.h"
#include "habuffer/parallel.h"
#include "pixel_order.h"
#include "habuffer/detail/technique_parallel.h"
#include "wavefront_composite.h"

namespace habuffer {
namespace {

std::string hex_word(std::uint64_t w) {
  char digits[17] = {};
  const auto end = std::to_chars(digits, digits + 16, w, 16).ptr;
  return "0x" + std::string(digits, end);
}

KernelParams make_params(const BufferConfig& c, const MaxAgeTable& m) {
  KernelParams p;
  p.age_bits = c.age_bits;
  p.coverage_bits = c.record_layout().coverage_bits();
  p.payload_bits = c.layout == Layout::L64 ? 32 : 0;
  p.table = c.table_or_screen();
  p.block = c.block;
  p.max_age_cells_x = m.cells().x;
  p.iter_limit = c.iter_limit;
  p.cull_tau = c.early_cull_tau;
  p.screen = c.screen;
  return p;
}

}  // namespace

struct HaBuffer::Impl {
  BufferConfig config;
  RecordLayout layout;
  OffsetSequence offsets;
  MaxAgeTable max_age;
  KernelParams params;
  std::vector<std::uint32_t> saturation;  // early cull with saturation: a code per pixel
  std::variant<SlotStorage<std::uint64_t>, SlotStorage<std::uint32_t>> storage;
  // Pixel order's buckets, kept between calls (a frame then touches no fresh
  // pages); a call that finds them taken by an overlapping call makes its own.
  std::mutex buckets_mutex;
  detail::PixelOrderScratch<std::uint64_t> scratch64;
  detail::PixelOrderScratch<std::uint32_t> scratch32;

  // The on-screen check's coverage bitmaps (Auto's order rule), kept likewise.
  std::mutex coverage_mutex;
  std::vector<std::vector<std::uint64_t>> coverage_bits;
  std::atomic<InsertOrder> last_order{InsertOrder::Arrival};

  // Checks the batch lies on the screen (throws naming the first fragment
  // off it) and returns the order it inserts in: Auto's rule reads the
  // pixels it covers, counted in the same pass.
  InsertOrder check_and_order(std::span<const Fragment> frags, const InsertOptions& options, std::uint32_t threads) {
    if (!insert_order_needs_coverage(options, frags.size(), config.screen)) {
      check_on_screen(frags, config.screen);
      return choose_insert_order(options, frags.size(), 0, config.screen);
    }
    std::unique_lock<std::mutex> kept(coverage_mutex, std::try_to_lock);
    std::vector<std::vector<std::uint64_t>> own;
    const std::uint64_t covered =
        detail::check_and_count_covered(frags, config.screen, threads, kept.owns_lock() ? coverage_bits : own);
    return choose_insert_order(options, frags.size(), covered, config.screen);
  }

  template <class Word>
  detail::PixelOrderScratch<Word>& kept_scratch() {
    if constexpr (std::is_same_v<Word, std::uint64_t>)
      return scratch64;
    else
      return scratch32;
  }

  Impl(const BufferConfig& c, OffsetSequence o)
      : config(c), layout(c.record_layout()), offsets(std::move(o)), max_age(c.screen, c.block) {
    config.table = c.table_or_screen();
    params = make_params(config, max_age);
    if (config.saturation) {
      saturation.assign(config.screen.area(), 0);
      params.saturation = saturation.data();
    }
    if (layout.layout() == Layout::L64)
      storage = SlotStorage<std::uint64_t>(config.table.area());
    else
      storage = SlotStorage<std::uint32_t>(config.table.area());
  }

  template <bool Concurrent, class F>
  decltype(auto) with_kernel(F&& f) {
    return std::visit(
        [&](auto& s) {
          using Word = std::remove_pointer_t<decltype(s.data())>;
          HashKernel<Word, Concurrent> k(params, offsets.values().data(), s.data(), max_age.data());
          return f(k);
        },
        storage);
  }
  template <class F>
  decltype(auto) with_kernel(F&& f) const {
    return const_cast<Impl*>(this)->with_kernel<false>(std::forward<F>(f));
  }

  // Contiguous slices of the stream, one per thread, all sharing the table
  // through atomics (one slice and plain stores for one thread, unless
  // `shared`: other calls may be inserting at the same time).
  Counters insert_slices(std::span<const Fragment> frags, std::uint32_t threads, bool shared) {
    return std::visit(
        [&](auto& st) {
          using Word = std::remove_pointer_t<decltype(st.data())>;
          return detail::insert_slices(
              frags, threads,
              [&](auto concurrent) {
                return HashKernel<Word, decltype(concurrent)::value>(params, offsets.values().data(), st.data(),
                                                                     max_age.data());
              },
              [](auto& k, const Fragment& f) { return k.ha_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage, f.rgba); },
              shared);
        },
        storage);
  }

  // The batch bucketed by pixel, nearest first, with the jump start
  // (pixel_order.h): bands of rows, one per thread.
  Counters insert_pixel_ordered(std::span<const Fragment> frags, std::uint32_t threads, bool shared,
                                const InsertOptions& options) {
    return std::visit(
        [&](auto& st) {
          using Word = std::remove_pointer_t<decltype(st.data())>;
          const auto make_kernel = [&](auto concurrent) {
            return HashKernel<Word, decltype(concurrent)::value>(params, offsets.values().data(), st.data(),
                                                                 max_age.data());
          };
          std::unique_lock<std::mutex> kept(buckets_mutex, std::try_to_lock);
          detail::PixelOrderScratch<Word> own;
          const detail::InterleaveRule rule{options.interleave, st.bytes() > cache_sizes().l2};
          return detail::insert_pixel_ordered<Word>(frags, config.screen, threads, make_kernel, shared, rule,
                                                    options.step, kept.owns_lock() ? kept_scratch<Word>() : own);
        },
        storage);
  }

  // Arrival or pixel order, as `order` says.
  Counters insert_ordered(std::span<const Fragment> frags, InsertOrder order, std::uint32_t threads, bool shared,
                          const InsertOptions& options) {
    if (order == InsertOrder::Pixel) return insert_pixel_ordered(frags, threads, shared, options);
    return insert_slices(frags, threads, shared);
  }

  Counters insert_owner_computes(std::span<const Fragment> frags, const InsertOptions& options,
                                 std::uint32_t threads) {
    return std::visit(
        [&](auto& st) {
          return habuffer::insert_owner_computes(params, offsets.values().data(), st.data(), max_age, frags,
                                                 OwnerComputesOptions{threads, options.band_rows});
        },
        storage);
  }

};

HaBuffer::HaBuffer(const BufferConfig& config, OffsetSequence offsets) {
  config.validate();
  const Extent table = config.table_or_screen();
  if (offsets.table() != table)
    throw std::invalid_argument("offsets were made for table " + offsets.table().str() + ", not " + table.str());
  const std::uint32_t amax = config.record_layout().max_age();
  if (offsets.size() != amax)
    throw std::invalid_argument("need " + std::to_string(amax) + " offsets (one per age), got " +
                                std::to_string(offsets.size()));
  impl_ = std::make_unique<Impl>(config, std::move(offsets));
}

HaBuffer::~HaBuffer() = default;
HaBuffer::HaBuffer(HaBuffer&&) noexcept = default;
HaBuffer& HaBuffer::operator=(HaBuffer&&) noexcept = default;

const BufferConfig& HaBuffer::config() const { return impl_->config; }
const RecordLayout& HaBuffer::record_layout() const { return impl_->layout; }
const OffsetSequence& HaBuffer::offsets() const { return impl_->offsets; }
Extent HaBuffer::screen() const { return impl_->config.screen; }
Extent HaBuffer::table() const { return impl_->config.table; }

std::string HaBuffer::capacity_text() const { return "table " + table().str(); }

void HaBuffer::measure(BuildReport& r) const {
  std::vector<std::uint64_t> hist = age_histogram();
  std::uint64_t weighted = 0;
  r.stored = 0;
  for (std::uint32_t a = 1; a < hist.size(); ++a) {
    r.stored += hist[a];
    weighted += std::uint64_t{a} * hist[a];
    if (hist[a] != 0) r.max_age = a;
  }
  hist.resize(r.max_age + 1);
  r.age_histogram = std::move(hist);
  r.load_factor = static_cast<double>(r.stored) / static_cast<double>(slot_count());
  r.mean_age = r.stored == 0 ? 0.0 : static_cast<double>(weighted) / static_cast<double>(r.stored);
  r.max_age_table_max = max_age().max();
  r.table = table();
}
const MaxAgeTable& HaBuffer::max_age() const { return impl_->max_age; }

HaBuffer::TableWords HaBuffer::table_words() const {
  return std::visit(
      [](const auto& st) {
        using Word = std::remove_cvref_t<decltype(*st.data())>;
        return TableWords{st.data(), st.size(), static_cast<std::uint32_t>(sizeof(Word))};
      },
      impl_->storage);
}

InsertOrder HaBuffer::insert_order(std::span<const Fragment> fragments, const InsertOptions& options) const {
  if (options.order == InsertOrder::Pixel && options.mode == InsertMode::OwnerComputes)
    throw std::invalid_argument("owner-computes insertion follows the probes, not the pixels: it has no pixel order");
  return const_cast<Impl&>(*impl_).check_and_order(fragments, options, 1);
}

InsertOrder HaBuffer::last_insert_order() const { return impl_->last_order.load(std::memory_order_relaxed); }

Counters HaBuffer::insert(std::span<const Fragment> fragments, const InsertOptions& options) {
  if (options.order == InsertOrder::Pixel && options.mode == InsertMode::OwnerComputes)
    throw std::invalid_argument("owner-computes insertion follows the probes, not the pixels: it has no pixel order");
  const std::uint32_t threads = resolve_threads(options.threads, fragments.size());
  const InsertOrder order = impl_->check_and_order(fragments, options, threads);
  impl_->last_order.store(order, std::memory_order_relaxed);
  switch (options.mode) {
    case InsertMode::Auto:
      // One thread and no other call running: plain stores, the call alone.
      // Else atomics, beside any other atomic call (InsertGate).
      if (threads == 1)
        if (const auto alone = gate_.alone_if_free())
          return impl_->insert_ordered(fragments, order, 1, false, options);
      break;
    case InsertMode::Serial: {
      if (threads != 1)
        throw std::invalid_argument("serial insertion runs on one thread, not " + std::to_string(threads));
      const auto alone = gate_.alone();
      return impl_->insert_ordered(fragments, order, 1, false, options);
    }
    case InsertMode::Atomic: break;
    case InsertMode::OwnerComputes: {
      if (options.band_rows == 0) throw std::invalid_argument("band_rows must be at least 1");
      if (impl_->config.saturation)
        throw std::invalid_argument("owner-computes insertion has no saturation depth (its owners share no atomics)");
      const auto alone = gate_.alone();  // its owners store without atomics
      Counters counters;
      run_with_threads(threads, [&] { counters = impl_->insert_owner_computes(fragments, options, threads); });
      return counters;
    }
  }
  const auto shared = gate_.shared();
  return impl_->insert_ordered(fragments, order, threads, true, options);
}

std::uint32_t HaBuffer::insert_one(const Fragment& f) {
  check_on_screen({&f, 1}, impl_->config.screen);
  const auto insert = [&](auto& k) { return k.ha_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.coverage, f.rgba); };
  if (const auto alone = gate_.alone_if_free()) return impl_->with_kernel<false>(insert);
  const auto shared = gate_.shared();
  return impl_->with_kernel<true>(insert);
}

std::uint64_t HaBuffer::clear() {
  const auto alone = gate_.alone();
  impl_->max_age.clear();
  std::fill(impl_->saturation.begin(), impl_->saturation.end(), 0u);
  return std::visit([](auto& s) { return s.clear_and_count(); }, impl_->storage);
}

void HaBuffer::reset() {
  const auto alone = gate_.alone();
  impl_->max_age.clear();
  std::fill(impl_->saturation.begin(), impl_->saturation.end(), 0u);
  std::visit([](auto& s) { s.clear(); }, impl_->storage);
}

std::uint64_t HaBuffer::count_stored() const {
  return std::visit([](const auto& s) { return s.count_nonempty(); }, impl_->storage);
}

std::uint64_t HaBuffer::slot_count() const { return impl_->config.table.area(); }

std::uint64_t HaBuffer::slot(std::uint64_t s) const {
  if (s >= slot_count()) throw std::out_of_range("slot " + std::to_string(s) + " outside the table");
  return std::visit([&](const auto& st) { return std::uint64_t{st.data()[s]}; }, impl_->storage);
}

void HaBuffer::import_state(std::span<const std::uint64_t> table_words, std::span<const std::uint32_t> max_ages) {
  if (table_words.size() != slot_count() || max_ages.size() != impl_->max_age.ages().size())
    throw std::invalid_argument("imported state has " + std::to_string(table_words.size()) + " slots and " +
                                std::to_string(max_ages.size()) + " max-age cells, the buffer " +
                                std::to_string(slot_count()) + " and " + std::to_string(impl_->max_age.ages().size()));
  // Refuse records that cannot be there (before changing anything): traversal
  // must find every stored record in exactly its own pixel (SPEC invariant 2).
  const std::uint32_t amax = impl_->layout.max_age();
  const Extent cells = impl_->max_age.cells();
  for (std::size_t i = 0; i < max_ages.size(); ++i)
    if (max_ages[i] > amax)
      throw std::invalid_argument("imported max-age cell (" + std::to_string(i % cells.x) + "," +
                                  std::to_string(i / cells.x) + ") holds age " + std::to_string(max_ages[i]) +
                                  ", above AMAX " + std::to_string(amax));
  const Extent table = impl_->config.table, screen = impl_->config.screen;
  impl_->with_kernel([&](auto& k) {
    using Word = std::remove_cv_t<std::remove_pointer_t<decltype(k.slots())>>;
    for (std::size_t s = 0; s < table_words.size(); ++s) {
      const std::uint64_t w = table_words[s];
      if (w == 0) continue;
      const std::string where = "imported slot " + std::to_string(s) + " (record " + hex_word(w) + ")";
      if (w > std::numeric_limits<Word>::max()) throw std::invalid_argument(where + " does not fit the L32 layout");
      const std::uint32_t a = k.ha_age(static_cast<Word>(w));
      if (a == 0) throw std::invalid_argument(where + " has age 0, which no stored record has");
      const glm::uvec2 p = k.ha_owner(glm::uvec2(s % table.x, s / table.x), a);
      const std::string pixel = "pixel (" + std::to_string(p.x) + "," + std::to_string(p.y) + ")";
      if (p.x >= screen.x || p.y >= screen.y)
        throw std::invalid_argument(where + " has age " + std::to_string(a) + ", which makes it " + pixel +
                                    ", outside screen " + screen.str());
      if (max_ages[k.ha_cell(p)] < a)
        throw std::invalid_argument(where + " has age " + std::to_string(a) + " for " + pixel +
                                    ", above its max-age cell's " + std::to_string(max_ages[k.ha_cell(p)]) +
                                    " (traversal would never reach it)");
    }
  });
  const auto alone = gate_.alone();
  std::visit(
      [&](auto& st) {
        using Word = std::remove_pointer_t<decltype(st.data())>;
        for (std::size_t s = 0; s < table_words.size(); ++s) st.data()[s] = static_cast<Word>(table_words[s]);
      },
      impl_->storage);
  std::copy(max_ages.begin(), max_ages.end(), impl_->max_age.data());
}

float HaBuffer::transmittance(std::uint32_t x, std::uint32_t y, std::uint32_t code, std::uint32_t bias) const {
  check_pixel(x, y, screen());
  if (config().layout != Layout::L64)
    throw std::invalid_argument("a light buffer of L32 records carries no opacity: build it with L64 records");
  if (config().samples > 1)
    throw std::invalid_argument("a light buffer is one sample per pixel: its records' codes are depths alone "
                                "(this one has " + std::to_string(config().samples) + " samples)");
  return impl_->with_kernel([&](auto& k) { return k.ha_transmittance(glm::uvec2(x, y), code, bias); });
}

std::uint32_t HaBuffer::list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const {
  check_pixel(x, y, screen());
  out.clear();
  return impl_->with_kernel([&](auto& k) {
    const glm::uvec2 p(x, y);
    const std::uint32_t amax = k.ha_load_max_age(k.ha_cell(p));
    std::uint32_t reads = 0;
    for (std::uint32_t a = 1; a <= amax; ++a) {
      const auto r = k.ha_load_slot(k.ha_slot(k.ha_probe(p, a)));
      ++reads;
      const std::uint32_t v = k.ha_visit(r, a);
      if (v == HABUFFER_VISIT_STOP) break;
      if (v == HABUFFER_VISIT_EMIT) out.push_back({a, k.ha_code(r), k.ha_data(r)});
    }
    return reads;
  });
}

glm::vec4 HaBuffer::composite(std::uint32_t x, std::uint32_t y, glm::vec3 background) const {
  check_pixel(x, y, screen());
  if (config().samples > 1) {  // the per-pixel resolve of composite_image, for one pixel
    std::vector<ListEntry> records;
    list(x, y, records);
    return resolve_samples(records, config().record_layout(), background);
  }
  return impl_->with_kernel([&](auto& k) { return k.ha_composite(glm::uvec2(x, y), background); });
}

namespace {

// Every pixel composited over background(row-major index), a wavefront of
// pixels per row (wavefront_composite.h), bands of rows in parallel.
template <class Kernel, class Background>
std::vector<glm::vec4> composite_wavefronts(const Kernel& kernel, Extent screen, std::uint32_t threads,
                                            Background background) {
  std::vector<glm::vec4> image(screen.area());
  detail::for_row_bands(screen, resolve_threads(threads, screen.area()),
                        [&](std::uint32_t, std::uint32_t y0, std::uint32_t y1) {
                          Kernel k = kernel;
                          for (std::uint32_t y = y0; y < y1; ++y) {
                            const std::size_t row = std::size_t{y} * screen.x;
                            detail::composite_row_wavefront(
                                k, y, screen.x, [&](std::uint32_t x) { return background(row + x); },
                                image.data() + row);
                          }
                        });
  return image;
}

}  // namespace

std::vector<glm::vec4> HaBuffer::composite_image(glm::vec3 background, std::uint32_t threads) const {
  if (config().samples > 1)
    return FragmentBuffer::composite_image(std::vector<glm::vec3>(screen().area(), background), threads);
  return impl_->with_kernel(
      [&](auto& k) { return composite_wavefronts(k, screen(), threads, [&](std::size_t) { return background; }); });
}

std::vector<glm::vec4> HaBuffer::composite_pixels(std::span<const glm::vec3> backgrounds, std::uint32_t threads) const {
  detail::check_backgrounds(screen(), backgrounds);
  return impl_->with_kernel(
      [&](auto& k) { return composite_wavefronts(k, screen(), threads, [&](std::size_t p) { return backgrounds[p]; }); });
}

std::vector<std::uint64_t> HaBuffer::age_histogram() const {
  std::vector<std::uint64_t> hist(impl_->layout.max_age() + 1, 0);
  impl_->with_kernel([&](auto& k) {
    const auto* slots = k.slots();
    for (std::uint64_t s = 0; s < slot_count(); ++s)
      if (slots[s] != 0) ++hist[k.ha_age(slots[s])];
  });
  return hist;
}

std::uint64_t HaBuffer::memory_bytes() const {
  const std::uint64_t table = std::visit([](const auto& s) { return s.bytes(); }, impl_->storage);
  return table + impl_->max_age.bytes() + impl_->offsets.size() * sizeof(glm::uvec2) + impl_->saturation.size() * 4;
}

std::vector<std::uint32_t> max_age_per_pixel(const HaBuffer& buffer) {
  const Extent s = buffer.screen();
  std::vector<std::uint32_t> ages(s.area(), 0);
  std::vector<ListEntry> list;
  for (std::uint32_t y = 0; y < s.y; ++y)
    for (std::uint32_t x = 0; x < s.x; ++x) {
      buffer.list(x, y, list);
      std::uint32_t& deepest = ages[x + std::size_t{y} * s.x];
      for (const ListEntry& e : list) deepest = std::max(deepest, e.age);
    }
  return ages;
}

const HaBuffer* as_hash_table(const FragmentBuffer& buffer) {
  if (descriptor(buffer.technique()).capacity != CapacityKind::TableSlots) return nullptr;
  return &dynamic_cast<const HaBuffer&>(buffer);
}

}  // namespace habuffer
