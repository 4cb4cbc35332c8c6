#include "technique_options.h"

namespace habuffer::cli {

TechniqueOptions parse_technique_options(const Args& args, std::initializer_list<const char*> more) {
  TechniqueOptions o;
  const std::string name = args.str("technique", "ha");
  const std::optional<Technique> t = parse_technique(name);
  if (!t) throw UsageError("option --technique: '" + name + "' is not one of " + technique_names());
  o.technique = *t;
  const std::string on = "with --technique " + to_string(o.technique);
  args.refuse_unless(o.technique == Technique::Arrays, {"layers"}, on + " (it sets fixed arrays' K)");
  args.refuse_unless(o.technique == Technique::Lists, {"pool"}, on + " (it sets linked lists' node pool)");
  args.refuse_unless(o.technique == Technique::Ha, {"table", "block", "iter-limit", "early-cull", "offsets", "seed"},
                     on + " (the HA-buffer's own)");
  for (const char* m : more) args.refuse_unless(o.technique == Technique::Ha, {m}, on + " (the HA-buffer's own)");
  o.layers = args.u32("layers", HA_DEFAULT_LAYERS, 1, 1u << 16);
  const std::string pool = args.str("pool", "auto");
  o.pool = pool == "auto" ? 0 : args.u64("pool", 0, 1, UINT32_MAX - 1);
  return o;
}

}  // namespace habuffer::cli
