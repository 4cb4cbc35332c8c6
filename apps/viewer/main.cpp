// habuffer-view: the windowed explorer. Parses the command line (the CLI's
// declarations and rules) and runs the viewer; every error is one line.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_args.h"
#include "habuffer/atomic_file.h"
#include "habuffer/printable.h"
#include "view_command.h"
#include "view_run.h"

int main(int argc, char** argv) {
  using namespace habuffer;
  const std::vector<std::string> args(argv + 1, argv + argc);
  // The CLI's output machinery: SIGINT, SIGTERM and SIGHUP remove the
  // screenshot's or report's temporary file; a file-size limit is a write error.
  remove_partial_outputs_on_signals();
  try {
    if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h")) {
      std::fputs(view::view_help().c_str(), stdout);
      return 0;
    }
    if (args.empty()) {
      std::fputs(view::view_help().c_str(), stderr);
      return 2;
    }
    const cli::Args parsed(args, view::view_spec());
    const view::ViewSettings settings = view::parse_view_settings(parsed);
    return view::run_view(settings);
  } catch (const cli::UsageError& e) {
    std::fprintf(stderr, "habuffer-view: %s\n", error_line(e.what()).c_str());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    std::fprintf(stderr, "habuffer-view: %s\n", filesystem_message(e).c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "habuffer-view: %s\n", error_line(e.what()).c_str());
    return 1;
  }
}
