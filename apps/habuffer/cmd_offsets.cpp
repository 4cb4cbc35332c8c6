// habuffer offsets: write an offsets CSV and measure its spread.
#include <chrono>
#include <cstdio>

#include "cli_args.h"
#include "commands.h"
#include "habuffer/interchange.h"
#include "habuffer/buffer_config.h"

namespace habuffer::cli {

int run_offsets(const std::vector<std::string>& argv) {
  if (print_help(argv,
        "usage: habuffer offsets --table WxH [--generator random|farthest] [--seed N] [--age-bits N | --count N]\n"
        "         [--out OFFSETS.csv] [--quality QUALITY.csv]\n"
        "  Prints the generation time. --quality writes k,min_distance for the first k offsets, k = 2..count.\n"))
    return 0;
  const Args args(argv, {"table", "generator", "seed", "age-bits", "count", "out", "quality"}, {});
  const auto table = args.extent("table");
  if (!table) throw UsageError("option --table is required");
  if (args.has("age-bits") && args.has("count")) throw UsageError("give at most one of --age-bits and --count");
  const std::uint32_t age_bits = args.u32("age-bits", HABUFFER_DEFAULT_AGE_BITS, HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS);
  const std::uint32_t count = args.u32("count", (1u << age_bits) - 1, 1, 1u << 20);
  FileRoles files;
  for (const char* o : {"out", "quality"})
    if (args.has(o)) files.output(std::string("--") + o, args.required(o));
  check_files(files);
  const std::string gen = args.str("generator", "random");
  if (gen != "random" && gen != "farthest") throw UsageError("option --generator: '" + gen + "' is not random or farthest");
  if (gen == "farthest" && table->area() > kFarthestMaxSlots)
    throw UsageError("--generator farthest: table " + table->str() + " has more than 2^28 slots");
  const auto t0 = std::chrono::steady_clock::now();
  const OffsetSequence offsets = OffsetSequence::make(
      gen == "farthest" ? OffsetGenerator::Farthest : OffsetGenerator::Random, *table, count, args.u64("seed", 1));
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
