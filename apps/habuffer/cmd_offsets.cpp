// habuffer offsets: write an offsets CSV and measure its spread.
#include <chrono>
#include <cstdio>

#include "cli_args.h"
#include "commands.h"
#include "file_values.h"
#include "habuffer/interchange.h"
#include "habuffer/buffer_config.h"
#include "technique_flags.h"

namespace habuffer::cli {

const CommandSpec& offsets_spec() {
  static const CommandSpec spec{
      "offsets --table WxH [OPTIONS]",
      {{"table", "WxH", "", "the table the offsets are for (required)"},
       {"generator", "random|farthest", "random", "how the offsets are chosen"},
       {"seed", "N", "1", "the random generator's seed"},
       technique_option_spec("age-bits"),
       {"count", "N", "", "this many offsets instead of 2^A - 1, one per age (not with --age-bits)"},
       {"out", "OFFSETS.csv", "", "the offsets", writes()},
       {"quality", "QUALITY.csv", "", "k,min_distance for the first k offsets, k = 2..count", writes()}},
      "  Prints the generation time.\n"};
  return spec;
}

int run_offsets(const std::vector<std::string>& argv) {
  if (print_help(argv, offsets_spec())) return 0;
  const Args args(argv, offsets_spec());
  const auto table = args.extent("table");
  if (!table) throw UsageError("option --table is required");
  if (args.has("age-bits") && args.has("count")) throw UsageError("give at most one of --age-bits and --count");
  const std::uint32_t age_bits = args.u32_in("age-bits", HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS);
  const std::uint32_t count = args.u32("count", (1u << age_bits) - 1, 1, 1u << 20);
  const std::string gen = args.str("generator");
  if (gen != "random" && gen != "farthest") throw UsageError("option --generator: '" + gen + "' is not random or farthest");
  if (gen == "farthest" && table->area() > kFarthestMaxSlots)
    throw UsageError("--generator farthest: table " + table->str() + " has more than 2^28 slots");
  const auto t0 = std::chrono::steady_clock::now();
  const OffsetSequence offsets = OffsetSequence::make(
      gen == "farthest" ? OffsetGenerator::Farthest : OffsetGenerator::Random, *table, count, args.u64_in("seed"));
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("generated %u %s offsets for table %s in %.1f ms\n", count, gen.c_str(), table->str().c_str(), ms);
  if (args.has("out")) write_offsets(args.required("out"), offsets);
  if (args.has("quality")) {
    CsvWriter q(args.required("quality"));
    q.text("k,min_distance\n");
    const auto d = min_pairwise_distances(offsets.values(), *table);
    char buf[32];
    for (std::size_t i = 0; i < d.size(); ++i) {
      std::snprintf(buf, sizeof buf, "%.3f", d[i]);
      q.u64(i + 2).comma().text(buf).endl();
    }
    q.close();
  }
  return 0;
}

}  // namespace habuffer::cli
