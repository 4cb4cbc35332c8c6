#include "habuffer/techniques/ha/ha_param_block.h"

namespace habuffer {

std::uint64_t ha_max_age_cells(const BufferConfig& c) {
  return std::uint64_t{(c.screen.x - 1) / c.block + 1} * std::uint64_t{(c.screen.y - 1) / c.block + 1};
}

void write_ha_params(const BufferConfig& c, ParamBlock& p) {
  p.ha_table_size[0] = c.table.x;
  p.ha_table_size[1] = c.table.y;
  p.habuffer_age_bits = c.age_bits;
  p.habuffer_coverage_bits = c.record_layout().coverage_bits();
  p.ha_block = c.block;
  p.ha_max_age_cells_x = (c.screen.x - 1) / c.block + 1;
  p.habuffer_iter_limit = c.iter_limit;
  p.habuffer_cull_tau = c.early_cull_tau;
  p.habuffer_saturation = c.saturation ? 1u : 0u;
}

}  // namespace habuffer
