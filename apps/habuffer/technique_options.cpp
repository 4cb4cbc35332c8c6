#include "technique_options.h"

#include <algorithm>
#include <string>

#include "habuffer/technique_descriptor.h"
#include "habuffer/technique_options.h"

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

std::string technique_option_help(bool buffer_part) {
  std::string s;
  for (const TechniqueOption& o : technique_options()) {
    if (o.flag.empty() || o.buffer_field != buffer_part) continue;
    std::string usage = option_usage(o);
    usage.resize(std::max<std::size_t>(usage.size(), 26), ' ');
    const std::string fallback = option_default_text(o);
    const std::string takers = techniques_taking(o.flag);
    s += "    " + usage + " " + std::string(o.help) + (fallback.empty() ? "" : "; default " + fallback) + " (" +
         (takers.empty() ? std::string("every technique") : takers) + ")\n";
  }
  return s;
}

std::string technique_help() {
  std::string s = "  --technique NAME (default ha), one of:\n";
  for (const TechniqueDescriptor* d : technique_registry()) {
    std::string name(d->name);
    name.resize(std::max<std::size_t>(name.size(), 13), ' ');
    s += "    " + name + " " + std::string(d->summary) + "\n";
  }
  s += "  The options only some techniques take are refused with the others (`habuffer techniques` lists\n"
       "  each technique's); the technique's own options:\n";
  return s + technique_option_help(false);
}

void set_technique_options(const Args& args, TechniqueConfig& config, bool buffer_part) {
  for (const TechniqueOption& o : technique_options()) {
    const std::string flag(o.flag);
    if (!flag.empty() && o.buffer_field == buffer_part && args.has(flag))
      usage_errors(flag, [&] { set_option(o, config, args.required(flag)); });
  }
  for (const TechniqueOption& o : technique_options()) {
    const TechniqueOption* needed = o.needs.empty() ? nullptr : find_option_flag(o.needs);
    if (needed != nullptr && o.buffer_field == buffer_part && args.has(std::string(o.flag)) &&
        option_on(o, config) && !option_on(*needed, config))
      throw UsageError("option --" + std::string(o.flag) + " " + std::string(o.without_needed));
  }
}

TechniqueOptions parse_technique_options(const Args& args) {
  TechniqueOptions o;
  const std::string name = args.str("technique", "ha");
  const std::optional<Technique> t = parse_technique(name);
  if (!t) throw UsageError("option --technique: '" + name + "' is not one of " + technique_names());
  o.technique = *t;
  refuse_other_techniques_options(args, descriptor(o.technique));
  set_technique_options(args, o, false);
  return o;
}

}  // namespace habuffer::cli
