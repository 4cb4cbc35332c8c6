/// @file
/// The key-set options shared by `habuffer hash build` and `habuffer stats
/// --keys`: declared once here, parsed once.
#pragma once

#include <string>

#include "cli_args.h"
#include "habuffer/key_streams.h"

namespace habuffer::cli {

/// The option row --NAME (--key-set or --keys): which key set (help text once).
OptionSpec key_set_option(const std::string& name);
/// The option row --domain XxY[xZ]: the key domain.
OptionSpec domain_option();
/// The option row --coverage F: the sparse-image set's share of covered pixels.
OptionSpec coverage_option();
/// The option row --count N: the random set's number of keys.
OptionSpec count_option();
/// "XxY" or "XxYxZ" with positive sides below 2^32; UsageError naming --domain otherwise.
spatial::Domain parse_domain(const std::string& text);
/// The key set of --NAME (set name), --domain, --coverage, --count and `seed`;
/// UsageError naming the option that is wrong.
spatial::KeySetOptions parse_key_set(const Args& args, const std::string& name, std::uint64_t seed);

}  // namespace habuffer::cli
