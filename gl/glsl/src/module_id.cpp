#include "habuffer/gl/module_id.h"

#include <cstdio>

namespace habuffer::gl {

std::uint32_t module_fingerprint(std::string_view module_text) {
  std::uint32_t h = 2166136261u;
  for (const char c : module_text) h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
  return h == 0 ? 1u : h;
}

std::string module_id_define(std::uint32_t id) {
  char line[48];
  std::snprintf(line, sizeof line, "#define HABUFFER_MODULE_ID 0x%08xu\n", id);
  return line;
}

}  // namespace habuffer::gl
