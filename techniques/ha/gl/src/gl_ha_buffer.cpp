#include "habuffer/gl/techniques/ha/gl_ha_buffer.h"

#include "gl_state_guard.h"

namespace habuffer::gl {

GlHaBuffer::GlHaBuffer(const BufferConfig& config, OffsetSource offsets, AtomicMode mode, const GlFrameOptions& options,
                       const GlBindings& bindings)
    : GlFrameDriver(std::make_unique<GlHaTable>(config, std::move(offsets), mode, bindings, options.clear_tile), options),
      table_(static_cast<GlHaTable&>(technique())) {}

void GlHaBuffer::resize(Extent table) {
  technique().check_context("resize");
  table_.resize(table);
  write_params();
  sized_by_host();  // an automatic table given a size by its host is not counted again
}

std::uint64_t GlHaBuffer::count_stored() {
  technique().check_context("count_stored");
  const GlStateGuard guard(bindings());
  write_params();
  bind();
  return table_.count_stored();
}

}  // namespace habuffer::gl
