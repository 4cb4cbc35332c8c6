#include "habuffer/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace habuffer {
namespace {

std::string duration_text(double s) {
  char buf[32];
  if (s < 100.0) {
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  } else if (s < 6000.0) {
    std::snprintf(buf, sizeof buf, "%.0f min", s / 60.0);
  } else {
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600.0);
  }
  return buf;
}

}  // namespace

std::string format_progress(const std::string& label, const std::string& unit, std::uint64_t done, std::uint64_t total,
                            double elapsed_s, int width) {
  const double fraction = total > 0 ? std::min(1.0, static_cast<double>(done) / static_cast<double>(total)) : 1.0;
  const int filled = static_cast<int>(std::floor(fraction * width));
  std::string line = label + " [" + std::string(static_cast<std::size_t>(filled), '#') +
                     std::string(static_cast<std::size_t>(width - filled), ' ') + "] ";
  char buf[160];
  std::snprintf(buf, sizeof buf, "%3.0f%% %llu/%llu %s", fraction * 100.0, static_cast<unsigned long long>(done),
                static_cast<unsigned long long>(total), unit.c_str());
  line += buf;
  if (done > 0 && elapsed_s > 0.0) {
    const double rate = static_cast<double>(done) / elapsed_s;
    std::snprintf(buf, sizeof buf, ", %.3g/s", rate);
    line += buf;
    if (done < total) line += ", " + duration_text(static_cast<double>(total - done) / rate) + " left";
  }
  return line;
}

ProgressBar::ProgressBar(std::string label, std::string unit, bool enabled, std::FILE* out)
    : label_(std::move(label)), unit_(std::move(unit)), enabled_(enabled), out_(out),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

ProgressBar ProgressBar::for_terminal(std::string label, std::string unit, bool quiet) {
  return ProgressBar(std::move(label), std::move(unit), !quiet && ::isatty(STDERR_FILENO) == 1);
}

ProgressBar::~ProgressBar() {
  if (enabled_ && drawn_) {
    std::fputs("\r\033[K", out_);
    std::fflush(out_);
  }
}

void ProgressBar::update(std::uint64_t done, std::uint64_t total) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && done < total && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  drawn_ = true;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::fprintf(out_, "\r\033[K%s", format_progress(label_, unit_, done, total, elapsed).c_str());
  std::fflush(out_);
}

ProgressCallback ProgressBar::callback() {
  return [this](std::uint64_t done, std::uint64_t total) { update(done, total); };
}

}  // namespace habuffer
