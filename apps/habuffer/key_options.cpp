#include "key_options.h"

#include <cstdio>
#include <stdexcept>

namespace habuffer::cli {

OptionSpec key_set_option(const std::string& name) {
  return {name, "NAME", "", "sparse-image, voxel-shell or random (habuffer/key_streams.h), in --domain"};
}
OptionSpec domain_option() { return {"domain", "XxY[xZ]", "", "the key space (a voxel shell: a cube)"}; }
OptionSpec coverage_option() { return {"coverage", "F", "0.25", "(sparse-image) the share of pixels covered"}; }
OptionSpec count_option() { return {"count", "N", "100000", "(random) keys"}; }

spatial::Domain parse_domain(const std::string& text) {
  unsigned long long x = 0, y = 0, z = 1;
  char tail = 0;
  const int n = std::sscanf(text.c_str(), "%llux%llux%llu%c", &x, &y, &z, &tail);
  if ((n != 2 && n != 3) || x == 0 || y == 0 || z == 0 || x > 0xFFFFFFFFull || y > 0xFFFFFFFFull ||
      z > 0xFFFFFFFFull || text.find_first_not_of("0123456789x") != std::string::npos)
    throw UsageError("option --domain: '" + text + "' is not XxY or XxYxZ with positive sides below 2^32");
  return {static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), static_cast<std::uint32_t>(z)};
}

spatial::KeySetOptions parse_key_set(const Args& args, const std::string& name, std::uint64_t seed) {
  spatial::KeySetOptions o;
  const auto set = spatial::parse_key_set(args.str(name));
  if (!set)
    throw UsageError("option --" + name + ": '" + args.str(name) + "' is not sparse-image, voxel-shell or random");
  o.set = *set;
  if (!args.has("domain")) throw UsageError("option --" + name + " needs --domain");
  o.domain = parse_domain(args.str("domain"));
  args.refuse_unless(o.set == spatial::KeySet::SparseImage, {"coverage"}, "on a key set other than sparse-image");
  args.refuse_unless(o.set == spatial::KeySet::Random, {"count"}, "on a key set other than random");
  o.coverage = args.real("coverage");
  o.count = args.u64_in("count", 1);
  o.seed = seed;
  try {
    o.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("option --") + name + ": " + e.what());
  }
  return o;
}

}  // namespace habuffer::cli
