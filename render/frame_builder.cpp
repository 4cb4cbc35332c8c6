#include "frame_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "habuffer/fragment_streams.h"
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/memory_model.h"

namespace habuffer {

namespace {

InsertOptions frame_insert_options(const RenderSettings& s) {
  InsertOptions o;
  o.threads = s.threads;
  o.order = s.insert_order;
  return o;
}

}  // namespace

FrameBuilder::FrameBuilder(const RenderSettings& settings) : settings_(settings), config_(technique_config(settings)) {}

std::vector<glm::vec4> CpuFrameBuilder::image(FrameStats& fs) {
  if (last_ == nullptr) throw std::logic_error("CpuFrameBuilder::image before a frame was built");
  const auto r0 = std::chrono::steady_clock::now();
  std::vector<glm::vec4> pixels = last_->buffer->composite_image(backgrounds_, settings_.threads);
  fs.resolve_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - r0).count();
  return pixels;
}

CpuFrameBuilder::CpuFrameBuilder(const RenderSettings& settings)
    : FrameBuilder(settings),
      frames_(settings.offsets, frame_insert_options(settings), settings.policy, frame_attempts(settings)) {}

void FrameBuilder::size_for(std::uint64_t fragments) {
  // The GL frame driver sizes its automatic containers by the same rule (TechniqueConfig::sized_for).
  if (automatic_size(settings_)) config_ = config_.sized_for(settings_.policy, fragments);
}

const TechniqueBuild& FrameBuilder::build(std::span<const Fragment> fragments, std::span<const glm::vec3> backgrounds,
                                          FrameStats& fs) {
  if (backgrounds.size() != settings_.config.screen.area())
    throw std::invalid_argument("a frame needs one background colour per pixel of screen " +
                                settings_.config.screen.str() + ", given " + std::to_string(backgrounds.size()));
  backgrounds_ = backgrounds;
  if (automatic_size(settings_) && previous_use_) {
    if (uses_table(config_.technique)) {
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
  const TechniqueBuild& b = build_frame(config_, fragments);
  fs.gather_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  fs.attempts = static_cast<std::uint32_t>(b.attempts.size());
  fs.counters = b.counters;
  fs.capacity = b.buffer->capacity();
  fs.insert_order = b.buffer->last_insert_order();
  // What the frame grew to holds the next frames too (a lossless table, pool or K).
  const TechniqueConfig held = b.buffer->technique_config();
  config_.buffer.table = held.buffer.table;
  config_.pool_capacity = held.pool_capacity;
  config_.layers = held.layers;
  if (const HaBuffer* table = as_hash_table(*b.buffer)) {
    fs.table = table->table();
    fs.max_age = table->max_age().max();
  }
  // The use SPEC 8's rule sizes the next frame by: records asked for (stored + failed), or a pool's nodes.
  GrowthNeed need = b.buffer->growth_need();
  need.records = b.counters.records_needed();
  previous_use_ = need.count_for(config_.technique);
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

BufferConfig capture_config(const RenderSettings& s) {
  BufferConfig c = s.config;
  c.table = c.screen;
  c.early_cull_tau = 0.0f;  // the capture keeps every fragment: the builder culls
  c.saturation = false;
  return c;
}

gl::GlFrameOptions capture_options() {
  gl::GlFrameOptions o;
  o.capture = true;
  o.capture_only = true;
  return o;
}

void finish_cpu_result(const RenderSettings& settings, TechniqueBuild last, RenderResult& result) {
  if (settings.per_pixel_culled) {
    if (const HaBuffer* table = as_hash_table(*last.buffer))
      result.pixel_culled = culled_per_pixel(*table, result.fragments);
    else
      result.pixel_culled.assign(settings.config.screen.area(), 0);  // no early cull: nothing culled
  }
  result.memory_bytes = last.buffer->memory_bytes();
  result.memory_model_bytes = memory_model_bytes(*last.buffer);
  result.buffer = std::move(last.buffer);
}

}  // namespace habuffer
