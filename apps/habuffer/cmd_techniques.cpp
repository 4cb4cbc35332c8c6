// habuffer techniques: the registered techniques, from their descriptors.
#include <cstdio>
#include <string>

#include "cli_args.h"
#include "commands.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::cli {

const CommandSpec& techniques_spec() {
  static const CommandSpec spec{
      "techniques [--markdown]",
      {{"markdown", "", "", "print the README's property table instead"}},
      "  Lists every registered technique: its name, what it is, and the options only it\n"
      "  and some others take.\n"};
  return spec;
}

int run_techniques(const std::vector<std::string>& argv) {
  if (print_help(argv, techniques_spec())) return 0;
  const Args args(argv, techniques_spec());
  if (args.has("markdown")) {
    std::fputs(property_table_markdown().c_str(), stdout);
    return 0;
  }
  for (const TechniqueDescriptor* d : technique_registry()) {
    std::string options;
    for (std::string_view o : d->options) options += (options.empty() ? "--" : ", --") + std::string(o);
    std::printf("%-13s %s (%s)\n", std::string(d->name).c_str(), std::string(d->summary).c_str(),
                std::string(d->properties.source).c_str());
    std::printf("%-13s exact: %s; sorted: %s\n", "", d->exact ? "yes" : "no", std::string(d->properties.sorted).c_str());
    if (!options.empty()) std::printf("%-13s options: %s\n", "", options.c_str());
  }
  return 0;
}

}  // namespace habuffer::cli
