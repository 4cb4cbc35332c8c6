#include "habuffer/gl/gl_context.h"
#include "habuffer/gl/technique_registry.h"

#include <array>

#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_technique.h"
#include "habuffer/technique_list.h"

// Each technique's gl folder defines its descriptor(); the list names them.
#define HABUFFER_DECLARE_GL_DESCRIPTOR(Enumerator, ns) \
  namespace habuffer::gl::techniques::ns {             \
  const GlTechniqueDescriptor& descriptor();           \
  }
HABUFFER_TECHNIQUES(HABUFFER_DECLARE_GL_DESCRIPTOR)
#undef HABUFFER_DECLARE_GL_DESCRIPTOR

namespace habuffer::gl {
namespace {

const std::array<const GlTechniqueDescriptor*, kTechniqueCount>& registry() {
#define HABUFFER_LIST_GL_DESCRIPTOR(Enumerator, ns) &techniques::ns::descriptor(),
  static const std::array<const GlTechniqueDescriptor*, kTechniqueCount> list = {
      HABUFFER_TECHNIQUES(HABUFFER_LIST_GL_DESCRIPTOR)};
#undef HABUFFER_LIST_GL_DESCRIPTOR
  static const bool checked = (check_registry_order<GlTechniqueDescriptor>(list, "GL technique registry"), true);
  (void)checked;
  return list;
}

}  // namespace

const GlTechniqueDescriptor& gl_descriptor(Technique t) {
  const auto i = static_cast<std::size_t>(t);
  if (i >= kTechniqueCount) throw GlError("technique " + std::to_string(i) + " is not registered");
  return *registry()[i];
}

std::unique_ptr<GlTechnique> make_gl_technique(const TechniqueConfig& c, const OffsetSource& offsets, AtomicMode mode,
                                               const GlBindings& bindings, std::uint32_t clear_tile) {
  require_context("make_gl_technique");  // before any GL call: one line, not an abort in libepoxy
  return gl_descriptor(c.technique).make(c, offsets, mode, bindings, clear_tile);
}

}  // namespace habuffer::gl
