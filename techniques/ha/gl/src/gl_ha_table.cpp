#include "habuffer/gl/techniques/ha/gl_ha_table.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "clear_pass.h"
#include "habuffer/gl/gl_technique.h"
#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_buffer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/techniques/ha/ha_param_block.h"

namespace habuffer::gl {

bool GlHaTable::fit_automatic_size(const TechniqueConfig& wanted) {
  const Extent want = wanted.buffer.table;
  Extent fitted = want;
  const std::uint64_t max_slots = max_storage_bytes() / config_.record_layout().word_bytes();
  if (want.area() > max_slots) {
    const double scale = std::sqrt(static_cast<double>(max_slots) / static_cast<double>(want.area()));
    fitted = {std::max(screen().x, static_cast<std::uint32_t>(want.x * scale)),
              std::max(screen().y, static_cast<std::uint32_t>(want.y * scale))};
  }
  resize(fitted);
  return fitted != want;
}

std::uint32_t GlHaTable::read_largest_max_age() const {
  const std::vector<std::uint32_t> cells = read_max_age();
  return cells.empty() ? 0u : *std::max_element(cells.begin(), cells.end());
}

namespace {

BufferConfig validated(BufferConfig c) {
  c.validate();
  c.table = c.table_or_screen();
  return c;
}

// Cells of the max-age table of `c`'s screen (GlError beyond 32-bit cell indices).
std::uint32_t max_age_cells(const BufferConfig& c) {
  const std::uint64_t cells = ha_max_age_cells(c);
  if (cells > UINT32_MAX) throw GlError("max-age table of " + std::to_string(cells) + " cells is too large");
  return static_cast<std::uint32_t>(cells);
}

// One side of a table scaled from screen side `from` to `to`, rounded up.
std::uint64_t scaled_side(std::uint32_t side, std::uint32_t from, std::uint32_t to) {
  return (std::uint64_t{side} * to + from - 1) / from;
}

}  // namespace

struct GlHaTable::Gpu {
  GlStorage table, locks, max_age, offsets, saturation;
  GlStorage count;  // the query buffer the clear pass's count lands in, read a frame later
  std::unique_ptr<ClearPass> clear;
};

GlHaTable::GlHaTable(const BufferConfig& config, OffsetSource offsets, AtomicMode mode, const GlBindings& bindings,
                     std::uint32_t clear_tile)
    : GlTechnique(Technique::Ha, mode, bindings, validated(config).screen, config.samples),
      config_(validated(config)),
      source_(std::move(offsets)),
      offsets_(source_.make(config_.table, config_.record_layout().max_age())),
      clear_tile_(clear_tile),
      auto_table_(config.table == Extent{}),
      gpu_(std::make_unique<Gpu>()) {
  check_atomic_mode(mode, config_.layout);
  cells_ = max_age_cells(config_);
  if (const std::string why = table_limit(config_.table); !why.empty()) throw GlError(why);
  gpu_->max_age = GlStorage(std::uint64_t{cells_} * 4);
  gpu_->count = GlStorage(sizeof(std::uint64_t));
  if (config_.saturation) gpu_->saturation = GlStorage(config_.screen.area() * 4);
  allocate_table(config_.table, false);
  gpu_->clear = std::make_unique<ClearPass>(mode, bindings);
  declare_pass({GlPassStage::FrameStart, "the HA-buffer's clear pass", [this](GlPassContext& c) { clear(c); }});
}

GlHaTable::~GlHaTable() = default;

std::string GlHaTable::table_limit(Extent table) const {
  const std::uint64_t slots = table.area();
  if (slots > UINT32_MAX) return "the GPU path indexes at most 2^32 - 1 slots, table " + table.str();
  const std::uint64_t bytes = slots * config_.record_layout().word_bytes();
  if (bytes > max_storage_bytes())
    return "table " + table.str() + " needs " + std::to_string(bytes) + " bytes, this OpenGL allows " +
           std::to_string(max_storage_bytes()) + " per shader-storage buffer";
  return {};
}

void GlHaTable::allocate_table(Extent table, bool new_offsets) {
  if (const std::string why = table_limit(table); !why.empty()) throw GlError(why);
  const std::uint64_t slots = table.area();
  config_.table = table;
  if (new_offsets) offsets_ = source_.make(table, config_.record_layout().max_age());
  gpu_->table = GlStorage();  // the old table goes first: the new one may need its memory
  gpu_->locks = GlStorage();
  gpu_->offsets = GlStorage();
  gpu_->table = GlStorage(slots * config_.record_layout().word_bytes());  // zeroed
  // Zeroed too: every critical section leaves its lock at 0 again.
  if (mode() == AtomicMode::Emulated64) gpu_->locks = GlStorage(emulated64_lock_words(slots) * 4);
  gpu_->offsets = GlStorage(offsets_.size() * sizeof(glm::uvec2), offsets_.values().data());
  holds_frame_ = false;
  pending_count_table_.reset();  // a count in flight belongs to a table no longer in use
}

void GlHaTable::write_params(GlParams& p) const { write_ha_params(config_, p); }

void GlHaTable::bind() const {
  const GlBindings& b = bindings();
  gpu_->table.bind_storage(b.table);
  gpu_->max_age.bind_storage(b.max_age);
  gpu_->offsets.bind_storage(b.offsets);
  gpu_->locks.bind_storage(b.locks);
  gpu_->saturation.bind_storage(b.saturation);
}

void GlHaTable::bind_for_lookup(unsigned table, unsigned max_age, unsigned offsets) const {
  gpu_->table.bind_storage(table);
  gpu_->max_age.bind_storage(max_age);
  gpu_->offsets.bind_storage(offsets);
}

void GlHaTable::resize(Extent table) {
  BufferConfig c = config_;
  c.table = table;
  c.validate();
  if (table != config_.table) allocate_table(table);
}

void GlHaTable::change_screen(Extent screen) {
  // The table keeps its ratio to the screen side by side (so the load stays
  // about what it was; an automatic table, the screen, becomes the new
  // screen as in a fresh container), falling back to the screen itself when
  // that scaled table is beyond the rules or this context's limits.
  BufferConfig next = config_;
  next.screen = screen;
  const auto why_not = [&](Extent table) -> std::string {
    BufferConfig c = next;
    c.table = table;
    try {
      c.validate();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return table_limit(table);
  };
  const std::uint64_t tx = std::max<std::uint64_t>(scaled_side(config_.table.x, config_.screen.x, screen.x), screen.x);
  const std::uint64_t ty = std::max<std::uint64_t>(scaled_side(config_.table.y, config_.screen.y, screen.y), screen.y);
  next.table = screen;
  if (tx <= (1u << 31) && ty <= (1u << 31)) {
    const Extent scaled{static_cast<std::uint32_t>(tx), static_cast<std::uint32_t>(ty)};
    if (why_not(scaled).empty()) next.table = scaled;
  }
  if (const std::string why = why_not(next.table); !why.empty()) {
    next.validate();  // the configuration's own message first (std::invalid_argument)
    throw GlError(why);
  }
  const std::uint32_t cells = max_age_cells(next);
  if (next.saturation) check_storage_fits(screen.area() * 4, "the saturation image of screen " + screen.str());
  check_storage_fits(std::uint64_t{cells} * 4, "the max-age table of screen " + screen.str());
  // Everything new is made before anything old goes: a throw leaves the
  // container as it was (fresh's destructor frees what was made).
  const bool new_table = next.table != config_.table;
  OffsetSequence offsets = new_table ? source_.make(next.table, next.record_layout().max_age()) : offsets_;
  Gpu fresh;
  const std::uint64_t slots = next.table.area();
  fresh.table = GlStorage(slots * next.record_layout().word_bytes());
  if (mode() == AtomicMode::Emulated64) fresh.locks = GlStorage(emulated64_lock_words(slots) * 4);
  fresh.offsets = GlStorage(offsets.size() * sizeof(glm::uvec2), offsets.values().data());
  fresh.max_age = GlStorage(std::uint64_t{cells} * 4);
  if (next.saturation) fresh.saturation = GlStorage(screen.area() * 4);
  check_gl_errors("resizing the HA-buffer's screen");
  gpu_->table = std::move(fresh.table);
  gpu_->locks = std::move(fresh.locks);
  gpu_->offsets = std::move(fresh.offsets);
  gpu_->max_age = std::move(fresh.max_age);
  gpu_->saturation = std::move(fresh.saturation);
  config_ = next;
  cells_ = cells;
  offsets_ = std::move(offsets);
  holds_frame_ = false;          // the new table is empty: nothing for a clear pass to count
  pending_count_table_.reset();  // a count in flight was of the old screen
}

std::uint64_t GlHaTable::count_stored() {
  const std::uint64_t stored = gpu_->clear->run(config_.table, clear_tile_, false, ClockMode::Finish).stored;
  check_gl_errors("the counting pass");
  return stored;
}

void GlHaTable::clear(GlPassContext& context) {
  if (!holds_frame_) return;  // nothing gathered since the table was made or cleared
  FrameReport& report = context.report;
  // The count the previous frame's clear pass left in the query buffer (the
  // GPU wrote it a frame ago: reading it does not stall), then this frame's
  // clear pass, whose count will be read next frame. Informative (sizing
  // reads the outcome counters): a Deferred readback, which reads nothing
  // back at once, clears without counting.
  const bool count = context.options.readback == Readback::Immediate;
  if (pending_count_table_ && count) {
    report.counted_stored = gpu_->count.read<std::uint64_t>(1)[0];
    report.counted_table = *pending_count_table_;
  }
  const ClearPass::Result r =
      gpu_->clear->run(config_.table, clear_tile_, true, clock_mode(context.options), gpu_->count.id(), count);
  report.clear = {r.wall_ms, r.gpu_ms};
  check_gl_errors("the clear pass");
  if (count) pending_count_table_ = config_.table;
  report.cleared = true;
  holds_frame_ = false;
}

void GlHaTable::begin_frame(FrameReport& report, const GlFrameOptions& options) {
  // Adaptive sizing (SPEC 8, ResizePolicy's rule) from the latest complete
  // count of the records a frame asked to keep (stored + failed, whatever
  // table it was gathered into): asked for, or the table is automatic.
  if ((options.adaptive || auto_table_) && report.sized_by) {
    const Extent next = options.policy.next(config_.table, config_.screen, report.sized_by->records);
    if (next != config_.table) {
      if (table_limit(next).empty()) {
        allocate_table(next);
        report.resized = true;
      } else {
        report.resize_limited = true;  // keep the largest table this context holds
      }
    }
  }
}

void GlHaTable::before_gather() {
  gpu_->max_age.zero();
  gpu_->saturation.zero();
  holds_frame_ = true;  // even if the gather throws halfway, the next frame clears what it inserted
}

void GlHaTable::reset() { gpu_->table.zero(); }

void GlHaTable::gathered(std::span<const std::uint32_t>, FrameReport& report) { report.table = config_.table; }

bool GlHaTable::grow(const FrameReport& report, const GlFrameOptions& options) {
  // Every fragment the gather received has an outcome: the table for what it
  // asked to keep, at the middle of the band (one regather for any jump).
  const Extent grown = options.policy.grown(config_.table, config_.screen, growth_need(report).records);
  if (!table_limit(grown).empty()) return false;
  allocate_table(grown);
  return true;
}

std::vector<std::uint64_t> GlHaTable::read_table() const {
  const std::uint64_t slots = config_.table.area();
  std::vector<std::uint64_t> out(slots);
  if (config_.record_layout().word_bytes() == 8) {
    out = gpu_->table.read<std::uint64_t>(slots);
  } else {
    const auto words = gpu_->table.read_words(slots);
    std::copy(words.begin(), words.end(), out.begin());
  }
  return out;
}

std::vector<std::uint32_t> GlHaTable::read_max_age() const { return gpu_->max_age.read_words(cells_); }

std::uint64_t GlHaTable::memory_bytes() const {
  return bytes_of(gpu_->table, gpu_->locks, gpu_->max_age, gpu_->offsets, gpu_->saturation, gpu_->count,
                  *gpu_->clear);
}

std::unique_ptr<FragmentBuffer> GlHaTable::read_back() const {
  auto buffer = std::make_unique<HaBuffer>(config_, offsets_);
  buffer->import_state(read_table(), read_max_age());
  return buffer;
}

}  // namespace habuffer::gl
