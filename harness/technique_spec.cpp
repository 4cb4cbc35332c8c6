#include "habuffer/harness/technique_spec.h"

#include "habuffer/technique_descriptor.h"

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include "habuffer/number_text.h"
#include "habuffer/option_rules.h"

namespace habuffer::harness {
namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string part;
  std::istringstream in(s);
  while (std::getline(in, part, sep)) out.push_back(part);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

// A knob's value by `parse` (one of the shared rules), its refusal naming
// the word and the knob.
template <class Parse>
auto knob(const std::string& word, const std::string& key, const std::string& text, Parse parse) {
  try {
    return parse(text);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("technique '" + word + "': " + key + "=" + text + ": " + e.what());
  }
}

std::uint32_t whole(const std::string& word, const std::string& key, const std::string& text, std::uint32_t lo,
                    std::uint32_t hi) {
  return static_cast<std::uint32_t>(knob(word, key, text, [&](const std::string& t) { return parse_unsigned(t, lo, hi); }));
}

std::string number_text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

void require(bool ok, const std::string& word, const std::string& what) {
  if (!ok) throw std::invalid_argument("technique '" + word + "': " + what);
}

}  // namespace

std::string TechniqueSpec::label() const {
  std::string s = to_string(technique);
  if (cull > 0.0f) s += ":cull=" + number_text(cull);
  if (saturation) s += ":sat";
  if (load) s += ":load=" + number_text(*load);
  if (age_bits) s += ":age=" + std::to_string(*age_bits);
  if (layers) s += ":k=" + std::to_string(*layers);
  if (occupancy) s += ":occ";
  if (occupancy_words) s += ":words=" + std::to_string(*occupancy_words);
  return s;
}

bool TechniqueSpec::exact() const { return exact_technique(technique) && cull == 0.0f; }

namespace {

// "ha, lists, sorted-lists": the techniques a load sizes.
std::string automatically_sized_techniques() {
  std::string s;
  for (const TechniqueDescriptor* d : technique_registry())
    if (d->sized_automatically()) s += (s.empty() ? "" : ", ") + std::string(d->name);
  return s;
}

}  // namespace

TechniqueSpec parse_technique_spec(const std::string& word) {
  const std::vector<std::string> parts = split(word, ':');
  TechniqueSpec t;
  const std::optional<Technique> technique = parse_technique(parts.empty() ? "" : parts[0]);
  if (!technique) throw std::invalid_argument("technique '" + word + "': unknown name '" + (parts.empty() ? "" : parts[0]) + "'");
  t.technique = *technique;
  std::set<std::string> given;
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const std::size_t eq = parts[i].find('=');
    const std::string key = parts[i].substr(0, eq), value = eq == std::string::npos ? "" : parts[i].substr(eq + 1);
    const bool flag = eq == std::string::npos;
    require(given.insert(key).second, word, key + " given twice");
    if (key == "cull" && !flag) {
      t.cull = knob(word, key, value, [](const std::string& v) { return parse_cull_threshold(v); });
    } else if (key == "sat" && flag) {
      t.saturation = true;
    } else if (key == "load" && !flag) {
      t.load = knob(word, key, value, [](const std::string& v) { return parse_load_factor(v); });
    } else if (key == "age" && !flag) {
      t.age_bits = whole(word, key, value, HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS);
    } else if (key == "k" && !flag) {
      t.layers = whole(word, key, value, 1, HABUFFER_MAX_LAYERS);
    } else if (key == "occ" && flag) {
      t.occupancy = true;
    } else if (key == "words" && !flag) {
      t.occupancy_words = whole(word, key, value, 1, HABUFFER_MAX_OCCUPANCY_WORDS);
    } else {
      throw std::invalid_argument("technique '" + word + "': unknown knob '" + parts[i] +
                                  "' (cull=TAU, sat, load=L, age=A, k=K, occ, words=D)");
    }
  }
  // Each knob is a CLI option of the technique's descriptor.
  const TechniqueDescriptor& d = descriptor(t.technique);
  require(t.cull == 0.0f || d.takes("early-cull"), word, "cull applies to " + techniques_taking("early-cull"));
  require(!t.saturation || t.cull > 0.0f, word, "sat needs cull=TAU");
  require(!t.load || d.sized_automatically(), word, "load applies to " + automatically_sized_techniques());
  require(!t.age_bits || d.capacity == CapacityKind::TableSlots, word, "age applies to " + techniques_taking("table"));
  require(!t.layers || d.takes("layers"), word, "k applies to " + techniques_taking("layers"));
  require(!t.occupancy || d.takes("occupancy"), word, "occ applies to " + techniques_taking("occupancy"));
  require(!t.occupancy_words || t.occupancy, word, "words needs occ");
  return t;
}

Extent table_for_load(Extent screen, std::uint64_t fragments, double load) {
  const double slots = std::ceil(static_cast<double>(fragments) / load);
  const double scale = std::sqrt(slots / static_cast<double>(screen.area()));
  const Extent table = table_of_sides(std::ceil(screen.x * scale), std::ceil(screen.y * scale), load, fragments);
  if (table.x < screen.x || table.y < screen.y)
    throw std::invalid_argument("load " + number_text(load) + " of " + std::to_string(fragments) +
                                " fragments needs a table smaller than the screen " + screen.str() +
                                " (SPEC 1's geometry rule): the largest load this scene allows is " +
                                number_text(static_cast<double>(fragments) / static_cast<double>(screen.area())));
  return table;
}

std::uint64_t capacity_for_load(std::uint64_t fragments, double load) {
  const double nodes = std::ceil(static_cast<double>(fragments) / load);
  if (!(nodes <= static_cast<double>(UINT32_MAX - 1)))
    throw std::invalid_argument("load " + number_text(load) + " of " + std::to_string(fragments) + " fragments needs " +
                                number_text(nodes) + " nodes or layers, more than 2^32 - 2: raise the load");
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(nodes));
}

void TechniqueSpec::apply(RenderSettings& s, std::uint64_t fragments) const {
  s.technique = technique;
  s.config.early_cull_tau = cull;
  s.config.saturation = saturation;
  if (age_bits) s.config.age_bits = *age_bits;
  if (layers) s.layers = *layers;
  s.occupancy = occupancy;
  if (occupancy_words) s.occupancy_words = *occupancy_words;
  s.config.table = {};
  s.pool_capacity = 0;
  if (load && uses_table(technique)) s.config.table = table_for_load(s.config.screen, fragments, *load);
  if (load && uses_pool(technique)) s.pool_capacity = capacity_for_load(fragments, *load);
}

}  // namespace habuffer::harness
