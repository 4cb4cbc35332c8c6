// The key-set options shared by `habuffer hash build` and `habuffer stats
// --keys`: declared once here, parsed once.
#pragma once

#include <string>

#include "cli_args.h"
#include "habuffer/key_streams.h"

namespace habuffer::cli {

/// The option rows --key-set/--keys NAME, --domain, --coverage, --count (help text once).
OptionSpec key_set_option(const std::string& name);
OptionSpec domain_option();
OptionSpec coverage_option();
OptionSpec count_option();
/// "XxY" or "XxYxZ" with positive sides below 2^32; UsageError naming --domain otherwise.
spatial::Domain parse_domain(const std::string& text);
/// The key set of --NAME (set name), --domain, --coverage, --count and `seed`;
/// UsageError naming the option that is wrong.
spatial::KeySetOptions parse_key_set(const Args& args, const std::string& name, std::uint64_t seed);

}  // namespace habuffer::cli
