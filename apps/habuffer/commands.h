/// @file
/// The subcommands of the habuffer CLI. Each returns the process exit code:
/// 0 success, 1 bad data, 2 bad usage (errors are thrown, main reports them).
/// `args` are the arguments after the subcommand's name; each prints its usage for a lone --help.
#pragma once

#include <string>
#include <vector>

namespace habuffer::cli {

int run_build_lists(const std::vector<std::string>& args);  ///< `habuffer build-lists`
int run_generate(const std::vector<std::string>& args);  ///< `habuffer generate`
int run_offsets(const std::vector<std::string>& args);  ///< `habuffer offsets`
int run_demo(const std::vector<std::string>& args);  ///< `habuffer demo`
int run_info(const std::vector<std::string>& args);  ///< `habuffer info`
int run_stats(const std::vector<std::string>& args);  ///< `habuffer stats`
int run_render(const std::vector<std::string>& args);  ///< `habuffer render`
int run_compare(const std::vector<std::string>& args);  ///< `habuffer compare`
int run_sweep(const std::vector<std::string>& args);  ///< `habuffer sweep`
int run_bench(const std::vector<std::string>& args);  ///< `habuffer bench`
int run_figure(const std::vector<std::string>& args);  ///< `habuffer figure`
int run_plan(const std::vector<std::string>& args);  ///< `habuffer plan`
int run_techniques(const std::vector<std::string>& args);  ///< `habuffer techniques`
int run_voxelize(const std::vector<std::string>& args);  ///< `habuffer voxelize`
int run_csg(const std::vector<std::string>& args);  ///< `habuffer csg`
int run_hash(const std::vector<std::string>& args);  ///< `habuffer hash`

}  // namespace habuffer::cli
