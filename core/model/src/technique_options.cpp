#include "habuffer/technique_options.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "habuffer/number_text.h"
#include "habuffer/option_rules.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer {
namespace {

std::uint32_t u32(const OptionValue& v) { return static_cast<std::uint32_t>(std::get<std::uint64_t>(v)); }

// The table (technique_options.h). Its order is the order of help, of the
// technique words' labels and checks, and of the report fields.
constexpr TechniqueOption kOptions[] = {
    {.flag = "early-cull", .knob = "cull", .value_name = "TAU", .kind = OptionKind::Threshold,
     .help = "early cull: a pixel's list ends where its opacity reaches TAU",
     .buffer_field = true,
     .get = [](const TechniqueConfig& c) { return OptionValue{c.buffer.early_cull_tau}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.buffer.early_cull_tau = std::get<float>(v); },
     .knob_applies = [](const TechniqueDescriptor& d) { return d.takes("early-cull"); }},
    {.flag = "saturation", .knob = "sat", .value_name = "on|off", .kind = OptionKind::Switch,
     .help = "the saturation depth: fragments behind a culled one are rejected before insertion",
     .needs = "early-cull", .without_needed = "on needs --early-cull TAU (it records where culling began)",
     .buffer_field = true,
     .get = [](const TechniqueConfig& c) { return OptionValue{c.buffer.saturation}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.buffer.saturation = std::get<bool>(v); }},
    {.flag = "", .knob = "load", .value_name = "L", .kind = OptionKind::Load,
     .help = "a fixed table or pool for load L of the scene's fragments (else automatic)",
     .knob_applies = [](const TechniqueDescriptor& d) { return d.sized_automatically(); }},
    {.flag = "age-bits", .knob = "age", .value_name = "A", .kind = OptionKind::Count,
     .min = HABUFFER_MIN_AGE_BITS, .max = HABUFFER_MAX_AGE_BITS,
     .help = "bits of a record's age: the deepest probe is 2^A - 1 (fixes the depth code of every technique)",
     .buffer_field = true,
     .get = [](const TechniqueConfig& c) { return OptionValue{std::uint64_t{c.buffer.age_bits}}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.buffer.age_bits = u32(v); },
     .knob_applies = [](const TechniqueDescriptor& d) { return d.capacity == CapacityKind::TableSlots; }},
    {.flag = "samples", .knob = "", .value_name = "S", .kind = OptionKind::Count, .min = 1,
     .max = RecordLayout::kMaxSamples, .power_of_two = true,
     .help = "samples per pixel, 1, 2, 4 or 8: above 1 each record keeps its fragment's coverage mask in S low "
             "bits of its depth code (S depth bits fewer) and the image is resolved per sample",
     .buffer_field = true,
     .get = [](const TechniqueConfig& c) { return OptionValue{std::uint64_t{c.buffer.samples}}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.buffer.samples = u32(v); }},
    {.flag = "layers", .knob = "k", .value_name = "K", .kind = OptionKind::Count, .min = 1,
     .max = HABUFFER_MAX_LAYERS, .help = "layers per pixel", .json = "layers",
     .get = [](const TechniqueConfig& c) { return OptionValue{std::uint64_t{c.layers}}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.layers = u32(v); },
     .knob_applies = [](const TechniqueDescriptor& d) { return d.takes("layers"); },
     .reported = [](const TechniqueConfig& c, std::uint64_t capacity) {
       const std::uint64_t pixels = c.buffer.screen.area();
       return pixels > 0 ? capacity / pixels : 0;
     }},
    {.flag = "pool", .knob = "", .value_name = "N|auto", .kind = OptionKind::CountOrAuto, .min = 1,
     .max = UINT32_MAX - 1,
     .help = "nodes of the node pool; auto sizes it from the fragments, grows it at once on a drop",
     .json = "pool_nodes",
     .get = [](const TechniqueConfig& c) { return OptionValue{c.pool_capacity}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.pool_capacity = std::get<std::uint64_t>(v); },
     .reported = [](const TechniqueConfig&, std::uint64_t capacity) { return capacity; }},
    {.flag = "occupancy", .knob = "occ", .value_name = "on|off", .kind = OptionKind::Switch,
     .help = "the occupancy map: insertion rejects what lies beyond the K-th occupied depth bucket",
     .json = "occupancy",
     .get = [](const TechniqueConfig& c) { return OptionValue{c.occupancy}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.occupancy = std::get<bool>(v); },
     .knob_applies = [](const TechniqueDescriptor& d) { return d.takes("occupancy"); }},
    {.flag = "occupancy-words", .knob = "words", .value_name = "D", .kind = OptionKind::Count, .min = 1,
     .max = HABUFFER_MAX_OCCUPANCY_WORDS, .help = "32-bit words of a pixel's occupancy map (32 buckets each)",
     .json = "occupancy_words", .needs = "occupancy", .without_needed = "has no effect with --occupancy off",
     .get = [](const TechniqueConfig& c) { return OptionValue{std::uint64_t{c.occupancy_words}}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.occupancy_words = u32(v); }},
    {.flag = "depth-range", .knob = "", .value_name = "NEAR,FAR", .kind = OptionKind::Interval,
     .help = "the depths the scene's fragments lie in: the occupancy map's buckets, wboit's weights",
     .json = "depth_range",
     .get = [](const TechniqueConfig& c) { return OptionValue{c.depth_range}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.depth_range = std::get<DepthRange>(v); }},
    {.flag = "block", .knob = "", .value_name = "B", .kind = OptionKind::Count, .min = 1, .max = 1u << 16,
     .help = "the max-age table's block side in pixels", .buffer_field = true,
     .get = [](const TechniqueConfig& c) { return OptionValue{std::uint64_t{c.buffer.block}}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.buffer.block = u32(v); }},
    {.flag = "iter-limit", .knob = "", .value_name = "N", .kind = OptionKind::Count, .min = 1,
     .max = HABUFFER_MAX_ITER_LIMIT, .help = "iterations of one insert call before it gives up (failed_iter)",
     .buffer_field = true,
     .get = [](const TechniqueConfig& c) { return OptionValue{std::uint64_t{c.buffer.iter_limit}}; },
     .put = [](TechniqueConfig& c, const OptionValue& v) { c.buffer.iter_limit = u32(v); }},
};

DepthRange parse_interval(std::string_view text) {
  const std::string v(text);
  const std::size_t comma = v.find(',');
  float near_t = 0.0f, far_t = 0.0f;
  try {
    if (comma == std::string::npos) throw std::invalid_argument(v);
    std::size_t used_near = 0, used_far = 0;
    near_t = std::stof(v.substr(0, comma), &used_near);
    far_t = std::stof(v.substr(comma + 1), &used_far);
    if (used_near != comma || used_far != v.size() - comma - 1) throw std::invalid_argument(v);
  } catch (const std::exception&) {
    throw std::invalid_argument("'" + v + "' is not NEAR,FAR (two depths in [0, 1])");
  }
  if (!(near_t >= 0.0f && near_t < far_t && far_t <= 1.0f))
    throw std::invalid_argument(v + " is not an interval NEAR < FAR within [0, 1]");
  return {near_t, far_t};
}

}  // namespace

std::span<const TechniqueOption> technique_options() { return kOptions; }

const TechniqueOption* find_option_flag(std::string_view flag) {
  for (const TechniqueOption& o : kOptions)
    if (!o.flag.empty() && o.flag == flag) return &o;
  return nullptr;
}

const TechniqueOption* find_option_knob(std::string_view knob) {
  for (const TechniqueOption& o : kOptions)
    if (!o.knob.empty() && o.knob == knob) return &o;
  return nullptr;
}

OptionValue parse_option_value(const TechniqueOption& o, std::string_view text) {
  switch (o.kind) {
    case OptionKind::Count: {
      const std::uint64_t n = parse_unsigned(text, o.min, o.max);
      if (o.power_of_two && (n & (n - 1)) != 0)
        throw std::invalid_argument(std::to_string(n) + " is not a power of two in " + std::to_string(o.min) + ".." +
                                    std::to_string(o.max));
      return n;
    }
    case OptionKind::CountOrAuto:
      return text == "auto" ? std::uint64_t{0} : parse_unsigned(text, o.min, o.max);
    case OptionKind::Switch:
      if (text != "on" && text != "off") throw std::invalid_argument("'" + std::string(text) + "' is not on or off");
      return text == "on";
    case OptionKind::Threshold:
      return parse_cull_threshold(text);
    case OptionKind::Load:
      return parse_load_factor(text);
    case OptionKind::Interval:
      return parse_interval(text);
  }
  throw std::logic_error("technique option --" + std::string(o.flag) + ": unknown kind");
}

void set_option(const TechniqueOption& o, TechniqueConfig& config, std::string_view text) {
  if (o.put == nullptr) throw std::logic_error("technique option '" + std::string(o.knob) + "' has no field");
  o.put(config, parse_option_value(o, text));
}

bool option_on(const TechniqueOption& o, const TechniqueConfig& config) {
  if (o.get == nullptr) return true;
  const OptionValue v = o.get(config);
  if (o.kind == OptionKind::Switch) return std::get<bool>(v);
  if (o.kind == OptionKind::Threshold) return std::get<float>(v) > 0.0f;
  return true;
}

std::string option_value_text(const TechniqueOption& o, const OptionValue& v) {
  switch (o.kind) {
    case OptionKind::Count:
      return std::to_string(std::get<std::uint64_t>(v));
    case OptionKind::CountOrAuto:
      return std::get<std::uint64_t>(v) == 0 ? "auto" : std::to_string(std::get<std::uint64_t>(v));
    case OptionKind::Switch:
      return std::get<bool>(v) ? "on" : "off";
    case OptionKind::Threshold:
      return std::get<float>(v) > 0.0f ? shortest_text(std::get<float>(v)) : "off";
    case OptionKind::Load:
      return shortest_text(std::get<double>(v));
    case OptionKind::Interval:
      return shortest_text(std::get<DepthRange>(v).near_t) + "," + shortest_text(std::get<DepthRange>(v).far_t);
  }
  return "";
}

std::string option_default_text(const TechniqueOption& o) {
  return o.get == nullptr ? std::string() : option_value_text(o, o.get(TechniqueConfig{}));
}

std::string knob_usage(const TechniqueOption& o) {
  return o.kind == OptionKind::Switch ? std::string(o.knob) : std::string(o.knob) + "=" + std::string(o.value_name);
}

std::string techniques_taking_knob(const TechniqueOption& o) {
  std::string s;
  for (const TechniqueDescriptor* d : technique_registry())
    if (o.knob_applies != nullptr ? o.knob_applies(*d) : o.flag.empty() || d->takes(o.flag))
      s += (s.empty() ? "" : ", ") + std::string(d->name);
  return s;
}

}  // namespace habuffer
