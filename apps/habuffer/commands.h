// The subcommands of the habuffer CLI. Each returns the process exit code:
// 0 success, 1 bad data, 2 bad usage (errors are thrown, main reports them).
#pragma once

#include <string>
#include <vector>

namespace habuffer::cli {

int run_build_lists(const std::vector<std::string>& args);
int run_generate(const std::vector<std::string>& args);
int run_offsets(const std::vector<std::string>& args);
int run_demo(const std::vector<std::string>& args);
int run_info(const std::vector<std::string>& args);
int run_stats(const std::vector<std::string>& args);
int run_render(const std::vector<std::string>& args);
int run_compare(const std::vector<std::string>& args);
int run_sweep(const std::vector<std::string>& args);
int run_bench(const std::vector<std::string>& args);
int run_figure(const std::vector<std::string>& args);
int run_plan(const std::vector<std::string>& args);
int run_techniques(const std::vector<std::string>& args);

}  // namespace habuffer::cli
