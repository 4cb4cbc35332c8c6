#include "habuffer/gl/gl_technique.h"

#include <epoxy/gl.h>

#include "habuffer/gl/gl_error.h"

namespace habuffer::gl {

GlTechnique::GlTechnique(Technique technique, AtomicMode mode, const GlBindings& bindings, Extent screen)
    : technique_(technique), mode_(mode), bindings_(bindings), screen_(screen) {}

GlTechnique::~GlTechnique() = default;

std::string GlTechnique::module_source(ShaderStage stage, std::string_view header) const {
  return technique_module(technique_, mode_, bindings_, stage, header);
}

PassTiming GlTechnique::after_gather(bool) { return {}; }

void GlTechnique::gathered(const FrameReport&) {}

std::uint64_t max_storage_bytes() {
  GLint64 bytes = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &bytes);
  return static_cast<std::uint64_t>(bytes);
}

void check_storage_fits(std::uint64_t bytes, const std::string& what) {
  if (bytes > max_storage_bytes())
    throw GlError(what + " needs " + std::to_string(bytes) + " bytes, this OpenGL allows " +
                  std::to_string(max_storage_bytes()) + " per shader-storage buffer");
}

}  // namespace habuffer::gl
