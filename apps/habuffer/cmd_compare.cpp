// habuffer compare: two images through OpenImageIO's comparison.
#include <cstdio>

#include "cli_args.h"
#include "commands.h"
#include "habuffer/csv.h"
#include "habuffer/render/image.h"

namespace habuffer::cli {

// Two positional image files and no option.
const CommandSpec& compare_spec() {
  static const CommandSpec spec{
      "compare A B", {}, "  Prints RMSE, PSNR and the largest channel error over RGB (values in [0, 1]).\n"};
  return spec;
}

int run_compare(const std::vector<std::string>& argv) {
  if (print_help(argv, compare_spec())) return 0;
  if (argv.size() != 2 || argv[0].rfind("--", 0) == 0 || argv[1].rfind("--", 0) == 0)
    throw UsageError("give exactly two image files");
  try {
    const ImageDifference d = compare_images(argv[0], argv[1]);
    std::printf("rmse %.6g\npsnr %.4g\nmax_error %.6g at (%d, %d) channel %d\n", d.rmse, d.psnr, d.max_error, d.max_x,
                d.max_y, d.max_channel);
  } catch (const ImageError& e) {
    throw DataError(e.what());
  }
  return 0;
}

}  // namespace habuffer::cli
