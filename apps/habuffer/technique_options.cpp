#include "technique_options.h"

#include <stdexcept>
#include <string>

namespace habuffer::cli {

TechniqueOptions parse_technique_options(const Args& args, std::initializer_list<const char*> more) {
  TechniqueOptions o;
  const std::string name = args.str("technique", "ha");
  const std::optional<Technique> t = parse_technique(name);
  if (!t) throw UsageError("option --technique: '" + name + "' is not one of " + technique_names());
  o.technique = *t;
  const Technique tech = o.technique;
  const std::string on = "with --technique " + to_string(tech);
  args.refuse_unless(uses_layers(tech), {"layers"}, on + " (it sets fixed arrays' and the k-buffer's K)");
  args.refuse_unless(uses_pool(tech), {"pool"}, on + " (it sets linked lists' node pool)");
  args.refuse_unless(tech == Technique::KBuffer, {"occupancy", "occupancy-words"}, on + " (the k-buffer's occupancy map)");
  args.refuse_unless(tech == Technique::KBuffer || tech == Technique::Wboit, {"depth-range"},
                     on + " (it sets the k-buffer's occupancy buckets and wboit's weights)");
  args.refuse_unless(has_early_cull(tech), {"early-cull", "iter-limit", "saturation"},
                     on + " (early cull is the HA-buffer's and sorted lists')");
  args.refuse_unless(tech == Technique::Ha, {"table", "block", "offsets", "seed"}, on + " (the HA-buffer's own)");
  args.refuse_unless(stores_lists(tech), {"lossless", "max-attempts"},
                     on + " (it blends every fragment into the image: nothing is dropped, nothing grows)");
  for (const char* m : more) args.refuse_unless(tech == Technique::Ha, {m}, on + " (the HA-buffer's own)");
  o.layers = args.u32("layers", HABUFFER_DEFAULT_LAYERS, 1, HABUFFER_MAX_LAYERS);
  const std::string pool = args.str("pool", "auto");
  o.pool = pool == "auto" ? 0 : args.u64("pool", 0, 1, UINT32_MAX - 1);
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
