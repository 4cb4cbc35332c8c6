#include "render_report.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>

#include "habuffer/json_writer.h"
#include "habuffer/memory_model.h"
#include "report_json.h"

namespace habuffer::cli {
namespace {


// A count, or null where it was not counted (not a zero that reads as one).
JsonWriter& counted(JsonWriter& json, std::string_view key, const std::optional<std::uint64_t>& count) {
  if (count) return json.field(key, *count);
  return json.field(key, std::numeric_limits<double>::quiet_NaN());  // the writer's null
}

void frame(JsonWriter& json, const FrameStats& f, RenderPath path) {
  const bool gpu = path == RenderPath::Gl;
  json.begin_object().field("index", f.index).field("yaw", static_cast<double>(f.yaw));
  write_extent(json, "table", f.table);
  json.field("capacity", f.capacity).field("load_factor", f.load_factor).field("resized", f.resized).field("attempts", f.attempts);
  write_counters(json, f.counters);
  json.field("opaque_rejected", f.opaque_rejected).field("max_age", f.max_age).field("resize_limited", f.resize_limited);
  json.field("insert_order", to_string(f.insert_order));
  if (gpu) counted(json, "slot_writes", f.slot_writes);
  if (path != RenderPath::Cpu) json.field("deferred", f.deferred).field("resume_rounds", f.resume_rounds);
  json.field("gather_ms", f.gather_ms).field("resolve_ms", f.resolve_ms).field("frame_ms", f.frame_ms);
  if (gpu) json.field("clear_ms", f.clear_ms);
  json.end_object();
}

std::string_view path_name(RenderPath p) { return to_string(p); }

void write_vec3(JsonWriter& json, std::string_view key, glm::vec3 v) {
  json.key(key).begin_array();
  for (int i = 0; i < 3; ++i) json.value(static_cast<double>(v[i]));
  json.end_array();
}

// Translucent shadows: the light and its buffer (LightStats).
void light(JsonWriter& json, const ShadowSettings& set, const LightStats& l, const std::optional<ShadowAccuracy>& a) {
  json.key("light").begin_object();
  json.field("kind", l.view.orthographic ? "directional" : "spot");
  write_vec3(json, "direction", l.view.direction);
  if (!l.view.orthographic) write_vec3(json, "position", l.view.position);
  write_extent(json, "size", l.size);
  json.field("technique", "ha").field("layout", "64").field("table_mode", set.table == Extent{} ? "auto" : "fixed");
  write_extent(json, "table", l.table);
  json.field("early_cull", static_cast<double>(set.early_cull_tau)).field("age_bits", set.age_bits);
  json.field("max_slope", static_cast<double>(set.max_slope)).field("bias_codes", l.bias_codes);
  json.field("filter", to_string(set.filter));
  json.field("builds", l.builds).field("attempts", l.attempts);
  write_counters(json, l.counters);
  json.field("load_factor", l.load_factor).field("max_age", l.max_age).field("memory_bytes", l.memory_bytes);
  json.field("build_ms", l.build_ms).field("lookup_ms", l.lookup_ms).field("lookup_pixels", l.lookup_pixels);
  json.field("lookup_ns_per_pixel",
             l.lookup_pixels > 0 ? l.lookup_ms * 1e6 / static_cast<double>(l.lookup_pixels) : 0.0);
  if (a) {
    // habuffer/render/shadow_accuracy.h defines the bands and the reference.
    json.key("reference").begin_object().field("receivers", a->receivers).field("stride", a->stride);
    json.field("silhouette_band", a->silhouette_band).field("depth_band", a->depth_band).field("band", a->band);
    json.field("self_shadow", a->self_shadow);
    json.field("within_1_255", a->within).field("within_fraction", a->within_fraction);
    json.field("rmse", a->rmse).field("max_error", a->max_error);
    json.field("rmse_outside_band", a->rmse_outside).field("max_error_outside_band", a->max_error_outside);
    json.field("ms", a->ms).end_object();
  }
  json.end_object();
}

}  // namespace

RenderSummary summarize_render(const SceneDescription& scene, const RenderSettings& settings, const RenderResult& result,
                               const RenderOutputs& outputs) {
  RenderSummary s;
  s.scene = scene;
  s.settings = &settings;
  s.result = &result;
  s.outputs = &outputs;
  std::uint64_t total = 0;
  for (std::uint32_t n : result.pixel_fragments) {
    s.max_depth_complexity = std::max(s.max_depth_complexity, n);
    s.covered_pixels += n > 0;
    total += n;
  }
  s.mean_depth_complexity = s.covered_pixels > 0 ? static_cast<double>(total) / static_cast<double>(s.covered_pixels) : 0.0;
  return s;
}

void write_render_stats(const std::string& path, const RenderSummary& s) {
  const RenderSettings& set = *s.settings;
  const RenderResult& r = *s.result;
  const FrameStats& last = r.frames.back();
  JsonWriter json;
  json.begin_object();
  json.key("scene").begin_object().field("name", s.scene.name).field("meshes", static_cast<std::uint64_t>(s.scene.meshes));
  json.field("triangles", s.scene.triangles).end_object();
  write_extent(json, "size", set.config.screen);
  json.field("path", path_name(set.path)).field("technique", to_string(set.technique));
  json.field("device", r.device).field("layout", to_string(set.config.layout));
  write_technique_fields(json, technique_config(set), last.capacity);
  json.field("saturation", set.config.saturation);
  json.field("age_bits", set.config.age_bits).field("samples", set.config.samples).field("block", set.config.block);
  json.field("early_cull", static_cast<double>(set.config.early_cull_tau));
  json.field("table_mode", automatic_size(set) ? "auto" : (set.lossless ? "lossless" : "fixed"));
  write_counters(json, last.counters);
  json.field("opaque_rejected", last.opaque_rejected);
  // Counted on the GPU path only, and only with --slot-writes (null otherwise).
  if (set.path == RenderPath::Gl) counted(json, "slot_writes", last.slot_writes);
  json.field("max_depth_complexity", s.max_depth_complexity).field("mean_depth_complexity", s.mean_depth_complexity);
  json.field("covered_pixels", s.covered_pixels);
  write_extent(json, "table", last.table);
  json.field("capacity", last.capacity).field("load_factor", last.load_factor).field("max_age", last.max_age);
  json.field("insert_order", to_string(last.insert_order));
  json.field("gather_ms", last.gather_ms).field("resolve_ms", last.resolve_ms).field("frame_ms", last.frame_ms);
  const std::uint64_t stored = last.counters.stored();
  json.field("memory_bytes", r.memory_bytes).field("memory_model_bytes", r.memory_model_bytes);
  json.field("bytes_per_fragment", stored > 0 ? static_cast<double>(r.memory_bytes) / static_cast<double>(stored) : 0.0);
  json.field("memory_paper_bytes",
             paper_memory_bytes(set.technique, set.config.screen.area(), stored,
                                last.load_factor > 0 ? last.load_factor : 1.0,
                                static_cast<std::uint32_t>(last.capacity / set.config.screen.area())));
  json.field("growth_limited", r.growth_limited);
  json.key("heatmaps").begin_array();
  for (const HeatmapOutput& h : s.outputs->heatmaps)
    json.begin_object().field("kind", h.kind).field("path", h.path).field("max", h.max).end_object();
  json.end_array();
  if (s.outputs->reference_difference) {
    const ImageDifference& d = *s.outputs->reference_difference;
    json.key("reference").begin_object().field("path", s.outputs->reference).field("psnr", d.psnr);
    json.field("rmse", d.rmse).field("max_error", d.max_error).end_object();
  }
  if (s.outputs->error) {
    // Against the exact reference (SPEC 7 in double precision over the
    // frame's own fragments), in float, before any 8-bit file.
    const ImageDifference& d = *s.outputs->error;
    json.field("psnr", d.psnr).field("rmse", d.rmse).field("max_error", d.max_error);
  }
  if (r.light && set.shadows) light(json, *set.shadows, *r.light, s.outputs->shadow_error);
  json.key("frames").begin_array();
  for (const FrameStats& f : r.frames) frame(json, f, set.path);
  json.end_array();
  json.end_object();
  json.save(path);
}

void print_render_summary(const RenderSummary& s, const RenderOutputs& outputs) {
  const FrameStats& last = s.result->frames.back();
  const RenderSettings& set = *s.settings;
  const std::string held = uses_table(set.technique)
                               ? "table " + last.table.str() + ", max age " + std::to_string(last.max_age)
                               : std::to_string(last.capacity) + " records of " + to_string(set.technique);
  std::printf("%s %s %s, %s: %.3g M fragments (max depth complexity %u), %.3g M stored, load %.2f of %s\n",
              s.scene.name.c_str(), set.config.screen.str().c_str(), to_string(set.config.layout).c_str(),
              s.result->device.c_str(), static_cast<double>(last.counters.fragments) * 1e-6, s.max_depth_complexity,
              static_cast<double>(last.counters.stored()) * 1e-6, last.load_factor, held.c_str());
  std::printf("gather %.1f ms, resolve %.1f ms, frame %.1f ms; %s memory %.1f MiB; culled %llu, failed %llu%s\n",
              last.gather_ms, last.resolve_ms, last.frame_ms, to_string(set.technique).c_str(),
              static_cast<double>(s.result->memory_bytes) / (1 << 20),
              static_cast<unsigned long long>(last.counters.culled),
              static_cast<unsigned long long>(last.counters.failures()),
              outputs.reference_difference
                  ? (", PSNR vs reference " + std::to_string(outputs.reference_difference->psnr) + " dB").c_str()
                  : "");
  if (const std::optional<LightStats>& l = s.result->light) {
    std::printf("light %s %s: %.3g M fragments, table %s, load %.2f, max age %u, %.1f MiB; built %u time%s in "
                "%.1f ms; lookups %.1f ms for %.3g M pixels\n",
                l->view.orthographic ? "directional" : "spot", l->size.str().c_str(),
                static_cast<double>(l->counters.fragments) * 1e-6, l->table.str().c_str(), l->load_factor, l->max_age,
                static_cast<double>(l->memory_bytes) / (1 << 20), l->builds, l->builds == 1 ? "" : "s", l->build_ms,
                l->lookup_ms, static_cast<double>(l->lookup_pixels) * 1e-6);
  }
  if (const std::optional<ShadowAccuracy>& a = outputs.shadow_error)
    std::printf("shadow T vs reference: %.4f%% of %llu receivers outside the bands within 1/255 (bands %.2f%%: "
                "silhouette %llu of which self-shadowed %llu, depth %llu); RMSE %.4f, max error %.4f\n",
                100.0 * a->within_fraction, static_cast<unsigned long long>(a->receivers - a->band),
                a->receivers > 0 ? 100.0 * static_cast<double>(a->band) / static_cast<double>(a->receivers) : 0.0,
                static_cast<unsigned long long>(a->silhouette_band), static_cast<unsigned long long>(a->self_shadow),
                static_cast<unsigned long long>(a->depth_band),
                a->rmse, a->max_error);
  std::string files;
  for (const std::string& f : {outputs.image, outputs.stats, outputs.reference})
    if (!f.empty()) files += (files.empty() ? "" : ", ") + f;
  for (const HeatmapOutput& h : outputs.heatmaps) files += (files.empty() ? "" : ", ") + h.path;
  std::printf("wrote %s\n", files.c_str());
}

}  // namespace habuffer::cli
