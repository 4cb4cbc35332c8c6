// habuffer: command-line front end of the HA-buffer library.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli_args.h"
#include "commands.h"
#include "habuffer/atomic_file.h"
#include "habuffer/csv.h"
#include "habuffer/printable.h"

namespace {

constexpr const char* kUsage =
    "usage: habuffer COMMAND [OPTIONS]\n"
    "commands:\n"
    "  render       render a scene headless through the HA-buffer: image, stats, heat maps, reference\n"
    "  compare      RMSE, PSNR and largest channel error of two images\n"
    "  build-lists  build per-pixel sorted lists from a fragment CSV (SPEC 10)\n"
    "  generate     write a synthetic fragment stream CSV\n"
    "  offsets      write an offsets CSV (random or farthest) and its quality\n"
    "  stats        experiments on age vs load (probing, policy, offsets) with confidence intervals\n"
    "  demo         build lists for a generated stream and print its stats\n"
    "  sweep        throughput, probes and ages of one view against the load factor\n"
    "  bench        techniques x scenes x sizes, interleaved, with floors and error vs the exact reference\n"
    "  figure       seed 000's Fig. 2, Fig. 8, Table 1, seed 001's Fig. 10, the speed-accuracy frontier\n"
    "  plan         predict memory, max age, overflow and error per technique from one counting pass\n"
    "  info         version, build type and available paths\n"
    "  techniques   the registered techniques and their properties (--markdown: the README table)\n"
    "  voxelize     a mesh's solid voxels from lossless sorted depth lists (grid file, stats, slices)\n"
    "  csg          a CSG expression over named solids rendered from lossless sorted depth lists\n"
    "  hash         the coherent hash as a spatial hash table: build from keys, query, stats, image\n"
    "Run 'habuffer COMMAND --help' for a command's options.\n";

void report(const std::string& name, const char* what) {
  std::fprintf(stderr, "habuffer %s: %s\n", name.c_str(), habuffer::error_line(what).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  using namespace habuffer;
  const auto& commands = cli::command_runners();
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::fputs(kUsage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  const auto it = commands.find(name);
  if (it == commands.end()) {
    std::fprintf(stderr, "habuffer: unknown command %s (run 'habuffer --help' for the list)\n",
                 excerpt(name).c_str());
    return 2;
  }
  // An interrupted run removes its partial outputs; earlier files of the
  // same names stay as they were.
  remove_partial_outputs_on_signals();
  try {
    return it->second(std::vector<std::string>(argv + 2, argv + argc));
  } catch (const cli::UsageError& e) {
    report(name, e.what());
    return 2;
  } catch (const DataError& e) {
    report(name, e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "habuffer %s: out of memory\n", name.c_str());
    return 1;
  } catch (const std::filesystem::filesystem_error& e) {
    report(name, habuffer::filesystem_message(e).c_str());
    return 1;
  } catch (const std::exception& e) {
    report(name, e.what());
    return 1;
  }
}
