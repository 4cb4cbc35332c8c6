#include "report_json.h"

#include <type_traits>

#include "habuffer/technique_descriptor.h"

namespace habuffer::cli {
void write_extent(JsonWriter& json, std::string_view key, Extent e) {
  json.key(key).begin_array().value(e.x).value(e.y).end_array();
}

void write_technique_fields(JsonWriter& json, const TechniqueConfig& config, std::uint64_t capacity) {
  for (const ReportField& f : technique_report_fields(config, capacity))
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, DepthRange>)
            json.key(f.name).begin_array().value(static_cast<double>(v.near_t)).value(static_cast<double>(v.far_t))
                .end_array();
          else
            json.field(f.name, v);
        },
        f.value);
}

void write_counters(JsonWriter& json, const Counters& c) {
  json.field("fragments", c.fragments).field("stored", c.stored());
  for (const CounterField& f : kCounterFields) json.field(f.name, c.*f.member);
}

void write_build_stats(JsonWriter& json, const HashOptions& options, const FragmentBuffer& buffer,
                       const std::vector<BuildAttempt>& attempts, const BuildReport& report, const BuildTiming& timing) {
  const Counters& c = report.counters;
  const Technique technique = buffer.technique();
  json.field("path", options.gl ? "gl" : options.vk ? "vk" : "cpu").field("technique", to_string(technique));
  json.field("layout", to_string(options.config.layout));
  json.field("age_bits", options.config.age_bits).field("samples", options.config.samples);
  json.field("block", options.config.block);
  write_extent(json, "screen", options.config.screen);
  write_extent(json, "table", report.table);
  json.field("capacity", report.capacity);
  write_technique_fields(json, buffer.technique_config(), report.capacity);
  json.field("saturation", options.config.saturation);
  json.field("offsets", options.offsets_name).field("seed", options.offsets.seed);
  json.field("early_cull", static_cast<double>(options.config.early_cull_tau));
  json.field("fragments", c.fragments).field("stored", report.stored);
  for (const CounterField& f : kCounterFields) json.field(f.name, c.*f.member);
  json.field("load_factor", report.load_factor);
  json.field("max_age", report.max_age).field("mean_age", report.mean_age);
  json.key("age_histogram").begin_array();
  for (auto n : report.age_histogram) json.value(n);
  json.end_array();
  json.field("memory_bytes", report.memory_bytes).field("memory_model_bytes", report.memory_model_bytes);
  json.field("bytes_per_fragment",
             report.stored > 0 ? static_cast<double>(report.memory_bytes) / static_cast<double>(report.stored) : 0.0);
  json.field("build_ms", timing.build_ms);
  json.field("fragments_per_second", timing.build_ms > 0 ? static_cast<double>(c.fragments) / timing.build_ms * 1e3 : 0.0);
  json.field("threads", timing.threads).field("insert_order", timing.insert_order).field("lossless", options.lossless);
  if (!timing.vk_atomic_mode.empty())
    json.field("vk_atomic_mode", timing.vk_atomic_mode).field("vk_device", timing.vk_device)
        .field("vk_ended_by_driver", timing.vk_ended_by_driver)
        .field("vk_deferred", timing.vk_deferred)
        .field("vk_resume_rounds", timing.vk_resume_rounds);
  if (!timing.gl_atomic_mode.empty())
    json.field("gl_atomic_mode", timing.gl_atomic_mode).field("gl_renderer", timing.gl_renderer)
        .field("gl_deferred", timing.gl_deferred).field("gl_resume_rounds", timing.gl_resume_rounds)
        .field("gl_cut_short_retries", timing.gl_cut_short_retries);
  json.key("attempts").begin_array();
  for (const auto& a : attempts) {
    json.begin_object();
    write_extent(json, "table", a.table);
    json.field("capacity", a.capacity).field("failed_age", a.counters.failed_age);
    json.field("failed_iter", a.counters.failed_iter).field("dropped_pool", a.counters.dropped_pool);
    json.field("dropped_layers", a.counters.dropped_layers).end_object();
  }
  json.end_array();
}

}  // namespace habuffer::cli
