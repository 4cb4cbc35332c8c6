#include "technique_options.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "habuffer/technique_descriptor.h"

namespace habuffer::cli {

namespace {

// Refuses every option some technique takes (its descriptor's list) that
// the chosen technique does not, naming the techniques it applies to.
void refuse_other_techniques_options(const Args& args, const TechniqueDescriptor& chosen) {
  for (const TechniqueDescriptor* d : technique_registry())
    for (std::string_view option : d->options)
      if (!chosen.takes(option) && args.has(std::string(option)))
        throw UsageError("option --" + std::string(option) + " has no effect with --technique " +
                         std::string(chosen.name) + " (it applies to " + techniques_taking(option) + ")");
}

}  // namespace

std::string technique_help() {
  std::string s = "  --technique NAME (default ha), one of:\n";
  for (const TechniqueDescriptor* d : technique_registry()) {
    std::string name(d->name);
    name.resize(std::max<std::size_t>(name.size(), 13), ' ');
    s += "    " + name + " " + std::string(d->summary) + "\n";
  }
  s += "  The options only some techniques take are refused with the others; `habuffer techniques` lists\n"
       "  each technique's (--pool N|auto: nodes, auto by default; --layers K, default 16; --occupancy on,\n"
       "  --occupancy-words D, --depth-range NEAR,FAR: the k-buffer's occupancy map, wboit's weights).\n";
  return s;
}

TechniqueOptions parse_technique_options(const Args& args) {
  TechniqueOptions o;
  const std::string name = args.str("technique", "ha");
  const std::optional<Technique> t = parse_technique(name);
  if (!t) throw UsageError("option --technique: '" + name + "' is not one of " + technique_names());
  o.technique = *t;
  refuse_other_techniques_options(args, descriptor(o.technique));
  o.layers = args.u32("layers", HABUFFER_DEFAULT_LAYERS, 1, HABUFFER_MAX_LAYERS);
  const std::string pool = args.str("pool", "auto");
  o.pool_capacity = pool == "auto" ? 0 : args.u64("pool", 0, 1, UINT32_MAX - 1);
  const std::string occupancy = args.str("occupancy", "off");
  if (occupancy != "on" && occupancy != "off")
    throw UsageError("option --occupancy: '" + occupancy + "' is not on or off");
  o.occupancy = occupancy == "on";
  o.occupancy_words = args.u32("occupancy-words", HABUFFER_DEFAULT_OCCUPANCY_WORDS, 1, HABUFFER_MAX_OCCUPANCY_WORDS);
  args.refuse_unless(o.occupancy, {"occupancy-words"}, "with --occupancy off");
  if (args.has("depth-range")) {
    const std::string v = args.required("depth-range");
    const std::size_t comma = v.find(',');
    float near_t = 0.0f, far_t = 0.0f;
    try {
      if (comma == std::string::npos) throw std::invalid_argument(v);
      std::size_t used_near = 0, used_far = 0;
      near_t = std::stof(v.substr(0, comma), &used_near);
      far_t = std::stof(v.substr(comma + 1), &used_far);
      if (used_near != comma || used_far != v.size() - comma - 1) throw std::invalid_argument(v);
    } catch (const std::exception&) {
      throw UsageError("option --depth-range: '" + v + "' is not NEAR,FAR (two depths in [0, 1])");
    }
    if (!(near_t >= 0.0f && near_t < far_t && far_t <= 1.0f))
      throw UsageError("option --depth-range: " + v + " is not an interval NEAR < FAR within [0, 1]");
    o.depth_range = {near_t, far_t};
  }
  return o;
}

}  // namespace habuffer::cli
