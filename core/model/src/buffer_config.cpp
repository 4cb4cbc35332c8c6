#include "habuffer/buffer_config.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace habuffer {

void BufferConfig::validate() const {
  (void)record_layout();  // checks layout and age bits
  const Extent h = table_or_screen();
  if (screen.area() == 0) throw std::invalid_argument("screen size " + screen.str() + " is empty");
  if (table != Extent{} && table.area() == 0)
    throw std::invalid_argument("table " + table.str() + " has a zero side (0x0 means the screen's size)");
  if (screen.area() > UINT32_MAX)
    throw std::invalid_argument("screen " + screen.str() + " has more than 2^32 - 1 pixels");
  if (h.x < screen.x || h.y < screen.y)
    throw std::invalid_argument("table " + h.str() + " is smaller than screen " + screen.str() +
                                " (SPEC 1: each table side must be at least the screen side)");
  if (h.x > (1u << 31) || h.y > (1u << 31))
    throw std::invalid_argument("table " + h.str() + " has a side above 2^31 slots");
  if (block == 0) throw std::invalid_argument("max-age block size must be at least 1");
  if (iter_limit == 0 || iter_limit > HABUFFER_MAX_ITER_LIMIT)
    throw std::invalid_argument("iteration limit " + std::to_string(iter_limit) + " is not in [1, " +
                                std::to_string(HABUFFER_MAX_ITER_LIMIT) + "]");
  if (!(early_cull_tau >= 0.0f && early_cull_tau <= 1.0f))
    throw std::invalid_argument("early-cull threshold " + std::to_string(early_cull_tau) + " outside (0, 1]");
  if (early_cull_tau > 0.0f && layout != Layout::L64)
    throw std::invalid_argument("early cull needs the L64 layout (it reads opacity from the colour data)");
  if (saturation && early_cull_tau <= 0.0f)
    throw std::invalid_argument("saturation depth needs early cull (a threshold in (0, 1])");
  if (early_cull_tau > 0.0f && samples > 1)
    throw std::invalid_argument("early cull accumulates a whole pixel's opacity: it does not apply to " +
                                std::to_string(samples) + " samples per pixel (samples 1 only)");
}

}  // namespace habuffer
