#include "technique_edit.h"

#include <stdexcept>

#include "habuffer/technique_descriptor.h"

namespace habuffer::view {
namespace {

bool shown_for(const TechniqueOption& o, Technique t) {
  return !o.flag.empty() && o.get != nullptr && (techniques_taking(o.flag).empty() || descriptor(t).takes(o.flag));
}

}  // namespace

TechniqueConfig with_technique(const TechniqueConfig& config, Technique t) {
  TechniqueConfig c = config;
  c.technique = t;
  const TechniqueConfig defaults;
  for (const TechniqueOption& o : technique_options())
    if (o.get != nullptr && o.put != nullptr && !shown_for(o, t)) o.put(c, o.get(defaults));
  return c;
}

std::vector<const TechniqueOption*> editable_options(Technique t) {
  std::vector<const TechniqueOption*> out;
  for (const TechniqueOption& o : technique_options())
    if (shown_for(o, t)) out.push_back(&o);
  return out;
}

TechniqueConfig with_option(const TechniqueConfig& config, const TechniqueOption& o, const std::string& text) {
  TechniqueConfig c = config;
  try {
    set_option(o, c, text);  // the value's own rule; the configuration's are make_gl_technique's
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("--" + std::string(o.flag) + " " + text + ": " + e.what());
  }
  return c;
}

std::string option_text(const TechniqueOption& o, const TechniqueConfig& config) {
  return o.get == nullptr ? std::string() : option_value_text(o, o.get(config));
}

}  // namespace habuffer::view
