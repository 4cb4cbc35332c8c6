#include "habuffer/ha_buffer.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>


#include "habuffer/hash_kernel.h"
#include "habuffer/slot_storage.h"
#include "habuffer/owner_computes.h"
#include "habuffer/parallel.h"
#include "technique_parallel.h"

namespace habuffer {
namespace {

KernelParams make_params(const BufferConfig& c, const MaxAgeTable& m) {
  KernelParams p;
  p.age_bits = c.age_bits;
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
  // through atomics (one slice and plain stores for one thread).
  Counters insert_slices(std::span<const Fragment> frags, std::uint32_t threads) {
    return std::visit(
        [&](auto& st) {
          using Word = std::remove_pointer_t<decltype(st.data())>;
          return detail::insert_slices(
              frags, threads,
              [&](auto concurrent) {
                return HashKernel<Word, decltype(concurrent)::value>(params, offsets.values().data(), st.data(),
                                                                     max_age.data());
              },
              [](auto& k, const Fragment& f) { return k.ha_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.rgba); });
        },
        storage);
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
const MaxAgeTable& HaBuffer::max_age() const { return impl_->max_age; }

Counters HaBuffer::insert(std::span<const Fragment> fragments, const InsertOptions& options) {
  check_on_screen(fragments, impl_->config.screen);
  const std::uint32_t threads = resolve_threads(options.threads);
  InsertMode mode = options.mode;
  if (mode == InsertMode::Auto) mode = threads == 1 ? InsertMode::Serial : InsertMode::Atomic;
  if (mode == InsertMode::Serial && threads != 1)
    throw std::invalid_argument("serial insertion runs on one thread, not " + std::to_string(threads));
  if (mode != InsertMode::OwnerComputes) return impl_->insert_slices(fragments, threads);
  if (options.band_rows == 0) throw std::invalid_argument("band_rows must be at least 1");
  if (impl_->config.saturation)
    throw std::invalid_argument("owner-computes insertion has no saturation depth (its owners share no atomics)");
  Counters counters;
  run_with_threads(threads, [&] { counters = impl_->insert_owner_computes(fragments, options, threads); });
  return counters;
}

std::uint32_t HaBuffer::insert_one(const Fragment& f) {
  check_on_screen({&f, 1}, impl_->config.screen);
  return impl_->with_kernel<false>([&](auto& k) { return k.ha_insert_fragment(glm::uvec2(f.x, f.y), f.depth, f.rgba); });
}

std::uint64_t HaBuffer::clear() {
  impl_->max_age.clear();
  std::fill(impl_->saturation.begin(), impl_->saturation.end(), 0u);
  return std::visit([](auto& s) { return s.clear_and_count(); }, impl_->storage);
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
  std::visit(
      [&](auto& st) {
        using Word = std::remove_pointer_t<decltype(st.data())>;
        for (std::size_t s = 0; s < table_words.size(); ++s) {
          if (table_words[s] > std::numeric_limits<Word>::max())
            throw std::invalid_argument("imported slot " + std::to_string(s) + " does not fit the L32 layout");
          st.data()[s] = static_cast<Word>(table_words[s]);
        }
      },
      impl_->storage);
  std::copy(max_ages.begin(), max_ages.end(), impl_->max_age.data());
}

std::uint32_t HaBuffer::list(std::uint32_t x, std::uint32_t y, std::vector<ListEntry>& out) const {
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
  return impl_->with_kernel([&](auto& k) { return k.ha_composite(glm::uvec2(x, y), background); });
}

std::vector<glm::vec4> HaBuffer::composite_image(glm::vec3 background, std::uint32_t threads) const {
  return impl_->with_kernel([&](auto& k) {
    return detail::composite_pixels(
        screen(), threads, [&] { return k; },
        [](auto& kernel, glm::uvec2 p, glm::vec3 bg) { return kernel.ha_composite(p, bg); },
        [&](std::size_t) { return background; });
  });
}

std::vector<glm::vec4> HaBuffer::composite_image(std::span<const glm::vec3> backgrounds, std::uint32_t threads) const {
  return impl_->with_kernel([&](auto& k) {
    return detail::composite_image(
        screen(), backgrounds, threads, [&] { return k; },
        [](auto& kernel, glm::uvec2 p, glm::vec3 bg) { return kernel.ha_composite(p, bg); });
  });
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

}  // namespace habuffer
