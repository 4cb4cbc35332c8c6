#include "habuffer/atomic_mode.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "habuffer/shared/ha_constants.h"

namespace habuffer {

std::string to_string(AtomicMode mode) {
  switch (mode) {
    case AtomicMode::Native32: return "native32";
    case AtomicMode::Native64: return "native64";
    case AtomicMode::Emulated64: return "emulated64";
  }
  return "?";
}

std::vector<AtomicMode> runnable_atomic_modes(const AtomicSupport& support) {
  std::vector<AtomicMode> modes{AtomicMode::Native32};
  if (support.int64_types && support.atomic_int64) modes.push_back(AtomicMode::Native64);
  if (support.int64_types) modes.push_back(AtomicMode::Emulated64);
  return modes;
}

std::optional<AtomicMode> atomic_mode_override() {
  const char* env = std::getenv("HABUFFER_ATOMIC_MODE");
  if (env == nullptr || *env == '\0') return std::nullopt;
  for (AtomicMode m : {AtomicMode::Native32, AtomicMode::Native64, AtomicMode::Emulated64})
    if (to_string(m) == env) return m;
  throw std::invalid_argument("HABUFFER_ATOMIC_MODE='" + std::string(env) +
                              "' is not native32, native64 or emulated64");
}

std::optional<AtomicMode> chosen_atomic_mode(const AtomicSupport& support, Layout layout,
                                             const std::function<void(const std::string&)>& warn) {
  const auto forced = atomic_mode_override();
  if (forced && (*forced == AtomicMode::Native32) != (layout == Layout::L32)) {
    // A mode the layout cannot run is never replaced quietly: 32-bit atomics
    // cannot hold a 64-bit record (refused); a 64-bit mode forced beside a
    // 32-bit layout leaves it its one mode (said once).
    if (layout == Layout::L64)
      throw std::invalid_argument("HABUFFER_ATOMIC_MODE=" + to_string(*forced) + " does not fit layout " +
                                  to_string(layout) +
                                  ": 64-bit records run native64 or emulated64 (unset the variable, force one of "
                                  "those, or use 32-bit records)");
    if (warn)
      warn("warning: HABUFFER_ATOMIC_MODE=" + to_string(*forced) + " does not apply to layout " + to_string(layout) +
           ": 32-bit records run native32, their only mode");
  } else if (forced) {
    const auto runnable = runnable_atomic_modes(support);
    if (std::find(runnable.begin(), runnable.end(), *forced) == runnable.end())
      throw std::invalid_argument("HABUFFER_ATOMIC_MODE=" + to_string(*forced) + " cannot run on this " +
                                  support.api + " (" + support.device + "): no " +
                                  (*forced == AtomicMode::Native64 && support.int64_types ? support.atomic_name
                                                                                          : support.int64_name));
    return forced;
  }
  if (layout == Layout::L32) return AtomicMode::Native32;
  if (support.int64_types && support.atomic_int64) return AtomicMode::Native64;
  if (support.int64_types) return AtomicMode::Emulated64;
  return std::nullopt;
}

std::uint64_t emulated64_lock_words(std::uint64_t slots) {
  return (slots + (std::uint64_t{1} << HABUFFER_LOCK_SHIFT) - 1) >> HABUFFER_LOCK_SHIFT;
}

}  // namespace habuffer
