#include "technique_flags.h"

#include <algorithm>
#include <stdexcept>
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

OptionSpec technique_option_spec(std::string_view flag) {
  const TechniqueOption* o = find_option_flag(flag);
  if (o == nullptr) throw std::logic_error("--" + std::string(flag) + " is no technique option");
  const std::string takers = techniques_taking(o->flag);
  return {std::string(o->flag), std::string(o->value_name), option_default_text(*o),
          std::string(o->help) + (takers.empty() ? std::string() : " [" + takers + "]")};
}

std::vector<OptionSpec> technique_option_specs(bool buffer_part) {
  std::vector<OptionSpec> specs;
  for (const TechniqueOption& o : technique_options())
    if (!o.flag.empty() && o.buffer_field == buffer_part) specs.push_back(technique_option_spec(o.flag));
  return specs;
}

std::string technique_help() {
  std::string s = "  The techniques (--technique NAME):\n";
  for (const TechniqueDescriptor* d : technique_registry()) {
    std::string name(d->name);
    name.resize(std::max<std::size_t>(name.size(), 13), ' ');
    s += "    " + name + " " + std::string(d->summary) + "\n";
  }
  return s + "  The options only some techniques take (the techniques in [...] above) are refused with the others;\n"
             "  `habuffer techniques` lists each technique's.\n";
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
  const std::string name = args.str("technique");
  const std::optional<Technique> t = parse_technique(name);
  if (!t) throw UsageError("option --technique: '" + name + "' is not one of " + technique_names());
  o.technique = *t;
  refuse_other_techniques_options(args, descriptor(o.technique));
  set_technique_options(args, o, false);
  return o;
}

}  // namespace habuffer::cli
