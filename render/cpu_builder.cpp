#include "cpu_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "habuffer/fixed_arrays.h"
#include "habuffer/fragment_streams.h"
#include "habuffer/linked_lists.h"
#include "habuffer/memory_model.h"

namespace habuffer {

Extent initial_table(const RenderSettings& s, std::uint64_t fragments) {
  const double target = (s.policy.grow_at + s.policy.shrink_at) / 2.0;
  return table_for_load(s.config.screen, fragments, target);
}

std::uint64_t initial_pool(const RenderSettings& s, std::uint64_t fragments) {
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(static_cast<double>(fragments) / s.policy.grow_at)));
}

namespace {

InsertOptions frame_insert_options(const RenderSettings& s) {
  InsertOptions o;
  o.threads = s.threads;
  o.order = s.insert_order;
  return o;
}

}  // namespace

CpuBuilder::CpuBuilder(const RenderSettings& settings)
    : settings_(settings),
      config_(technique_config(settings)),
      frames_(settings.offsets, frame_insert_options(settings), settings.policy, frame_attempts(settings)) {}

void CpuBuilder::size_for(std::uint64_t fragments) {
  if (!automatic_size(settings_)) return;
  if (config_.technique == Technique::Ha) config_.buffer.table = initial_table(settings_, fragments);
  if (config_.technique == Technique::Lists) config_.pool_capacity = initial_pool(settings_, fragments);
}

const TechniqueBuild& CpuBuilder::build(std::span<const Fragment> fragments, FrameStats& fs) {
  if (automatic_size(settings_) && previous_use_) {
    if (config_.technique == Technique::Ha) {
      const Extent next = settings_.policy.next(config_.buffer.table, settings_.config.screen, *previous_use_);
      fs.resized = next != config_.buffer.table;
      config_.buffer.table = next;
    } else {
      const std::uint64_t next = settings_.policy.next(config_.pool_capacity, *previous_use_);
      fs.resized = next != config_.pool_capacity;
      config_.pool_capacity = next;
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  const TechniqueBuild& b = frames_.build(config_, fragments);
  fs.gather_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  fs.attempts = static_cast<std::uint32_t>(b.attempts.size());
  fs.counters = b.counters;
  fs.capacity = b.buffer->capacity();
  if (const auto* ha = dynamic_cast<const HaBuffer*>(b.buffer.get())) {
    fs.insert_order = ha->insert_order(fragments.size(), frame_insert_options(settings_));
    config_.buffer.table = ha->table();
    fs.table = ha->table();
    fs.max_age = ha->max_age().max();
    previous_use_ = b.counters.stored();
  } else if (const auto* lists = dynamic_cast<const LinkedLists*>(b.buffer.get())) {
    config_.pool_capacity = lists->capacity();
    previous_use_ = lists->requested();
  } else if (const auto* arrays = dynamic_cast<const FixedArrays*>(b.buffer.get())) {
    config_.layers = arrays->layers();  // a lossless frame's K holds the next frames too
  }
  return b;
}

}  // namespace habuffer

namespace habuffer {
namespace {

std::vector<std::uint32_t> culled_per_pixel(const HaBuffer& like, std::span<const Fragment> fragments) {
  HaBuffer replay(BufferConfig(like.config()), like.offsets());
  std::vector<std::uint32_t> culled(like.screen().area(), 0);
  for (const Fragment& f : fragments)
    if (replay.insert_one(f) == HABUFFER_CULLED) ++culled[f.x + std::size_t{f.y} * like.screen().x];
  return culled;
}

}  // namespace

void finish_cpu_result(const RenderSettings& settings, TechniqueBuild last, RenderResult& result) {
  if (settings.per_pixel_culled) {
    if (const auto* ha = dynamic_cast<const HaBuffer*>(last.buffer.get()))
      result.pixel_culled = culled_per_pixel(*ha, result.fragments);
    else
      result.pixel_culled.assign(settings.config.screen.area(), 0);  // no early cull: nothing culled
  }
  result.memory_bytes = last.buffer->memory_bytes();
  result.memory_model_bytes = memory_model_bytes(*last.buffer);
  result.buffer = std::move(last.buffer);
}

}  // namespace habuffer
