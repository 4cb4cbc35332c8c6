// habuffer info: what this build is and which paths it offers.
#include <cstdio>

#include <tbb/info.h>
#include <tbb/version.h>

#include "cli_args.h"
#include "commands.h"

namespace habuffer::cli {

int run_info(const std::vector<std::string>& argv) {
  const Args args(argv, {}, {"help"});
  if (args.has("help")) {
    std::puts("usage: habuffer info");
    return 0;
  }
  std::printf("habuffer %s\n", HABUFFER_VERSION);
  std::printf("build type: %s%s%s\n", HABUFFER_BUILD_TYPE, *HABUFFER_SANITIZE_NAME ? ", sanitizers: " : "",
              HABUFFER_SANITIZE_NAME);
  std::printf("compiler: %s\n", __VERSION__);
  std::printf("paths:\n");
  std::printf("  cpu: available (oneTBB %d.%d, %d hardware threads; layouts L64 and L32; age bits 4..12)\n",
              TBB_VERSION_MAJOR, TBB_VERSION_MINOR, tbb::info::default_concurrency());
  std::printf("  gl: not in this build (the GPU path is a later issue)\n");
  return 0;
}

}  // namespace habuffer::cli
