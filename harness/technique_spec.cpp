#include "habuffer/harness/technique_spec.h"

#include "habuffer/technique_descriptor.h"

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include "habuffer/number_text.h"
#include "habuffer/option_rules.h"
#include "habuffer/technique_options.h"

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

std::string number_text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

void require(bool ok, const std::string& word, const std::string& what) {
  if (!ok) throw std::invalid_argument("technique '" + word + "': " + what);
}

// Where each knob of the option table (habuffer/technique_options.h) is kept
// in a TechniqueSpec: its value stored, whether it was given, its text in a
// label. The knobs' names, kinds, ranges, rules and refusals are the table's.
struct KnobField {
  std::string_view knob;
  void (*store)(TechniqueSpec& t, const OptionValue& v);
  bool (*given)(const TechniqueSpec& t);
  std::string (*text)(const TechniqueSpec& t);  ///< the value in a label (a switch has none)
};

std::uint32_t whole(const OptionValue& v) { return static_cast<std::uint32_t>(std::get<std::uint64_t>(v)); }

constexpr KnobField kKnobFields[] = {
    {"cull", [](TechniqueSpec& t, const OptionValue& v) { t.cull = std::get<float>(v); },
     [](const TechniqueSpec& t) { return t.cull > 0.0f; }, [](const TechniqueSpec& t) { return number_text(t.cull); }},
    {"sat", [](TechniqueSpec& t, const OptionValue&) { t.saturation = true; },
     [](const TechniqueSpec& t) { return t.saturation; }, nullptr},
    {"load", [](TechniqueSpec& t, const OptionValue& v) { t.load = std::get<double>(v); },
     [](const TechniqueSpec& t) { return t.load.has_value(); },
     [](const TechniqueSpec& t) { return number_text(*t.load); }},
    {"age", [](TechniqueSpec& t, const OptionValue& v) { t.age_bits = whole(v); },
     [](const TechniqueSpec& t) { return t.age_bits.has_value(); },
     [](const TechniqueSpec& t) { return std::to_string(*t.age_bits); }},
    {"k", [](TechniqueSpec& t, const OptionValue& v) { t.layers = whole(v); },
     [](const TechniqueSpec& t) { return t.layers.has_value(); },
     [](const TechniqueSpec& t) { return std::to_string(*t.layers); }},
    {"occ", [](TechniqueSpec& t, const OptionValue&) { t.occupancy = true; },
     [](const TechniqueSpec& t) { return t.occupancy; }, nullptr},
    {"words", [](TechniqueSpec& t, const OptionValue& v) { t.occupancy_words = whole(v); },
     [](const TechniqueSpec& t) { return t.occupancy_words.has_value(); },
     [](const TechniqueSpec& t) { return std::to_string(*t.occupancy_words); }},
};

const KnobField& knob_field(const TechniqueOption& o) {
  for (const KnobField& f : kKnobFields)
    if (f.knob == o.knob) return f;
  throw std::logic_error("technique words: knob '" + std::string(o.knob) + "' has no TechniqueSpec field");
}

// "(cull=TAU, sat, load=L, ...)": every knob, for the refusal of an unknown one.
std::string knob_list() {
  std::string s;
  for (const TechniqueOption& o : technique_options())
    if (!o.knob.empty()) s += (s.empty() ? "" : ", ") + knob_usage(o);
  return "(" + s + ")";
}

}  // namespace

std::string TechniqueSpec::label() const {
  std::string s = to_string(technique);
  for (const TechniqueOption& o : technique_options()) {
    if (o.knob.empty()) continue;
    const KnobField& f = knob_field(o);
    if (!f.given(*this)) continue;
    s.append(":").append(o.knob);
    if (f.text != nullptr) s.append("=").append(f.text(*this));
  }
  return s;
}

bool TechniqueSpec::exact() const { return exact_technique(technique) && cull == 0.0f; }

namespace {

// The knob `part` ("k=8", "occ") of `word`, parsed by its table row and stored.
void parse_knob(const std::string& word, const std::string& part, TechniqueSpec& t, std::set<std::string>& given) {
  const std::size_t eq = part.find('=');
  const std::string key = part.substr(0, eq), value = eq == std::string::npos ? "" : part.substr(eq + 1);
  const bool flag = eq == std::string::npos;
  require(given.insert(key).second, word, key + " given twice");
  const TechniqueOption* o = find_option_knob(key);
  if (o == nullptr || flag != (o->kind == OptionKind::Switch))
    throw std::invalid_argument("technique '" + word + "': unknown knob '" + part + "' " + knob_list());
  knob_field(*o).store(t, flag ? OptionValue{true} : knob(word, key, value, [&](const std::string& v) {
    return parse_option_value(*o, v);
  }));
}

// Each knob where its row says it applies, and with the knob it needs.
void check_knobs(const std::string& word, const TechniqueSpec& t) {
  const TechniqueDescriptor& d = descriptor(t.technique);
  for (const TechniqueOption& o : technique_options()) {
    if (o.knob.empty() || !knob_field(o).given(t)) continue;
    require(o.knob_applies == nullptr || o.knob_applies(d), word,
            std::string(o.knob) + " applies to " + techniques_taking_knob(o));
    const TechniqueOption* needed = o.needs.empty() ? nullptr : find_option_flag(o.needs);
    require(needed == nullptr || knob_field(*needed).given(t), word,
            std::string(o.knob) + " needs " + (needed != nullptr ? knob_usage(*needed) : ""));
  }
}

}  // namespace

TechniqueSpec parse_technique_spec(const std::string& word) {
  const std::vector<std::string> parts = split(word, ':');
  TechniqueSpec t;
  const std::optional<Technique> technique = parse_technique(parts.empty() ? "" : parts[0]);
  if (!technique) throw std::invalid_argument("technique '" + word + "': unknown name '" + (parts.empty() ? "" : parts[0]) + "'");
  t.technique = *technique;
  std::set<std::string> given;
  for (std::size_t i = 1; i < parts.size(); ++i) parse_knob(word, parts[i], t, given);
  check_knobs(word, t);
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
  if (load && uses_table(technique)) s.config.table = harness::table_for_load(s.config.screen, fragments, *load);
  if (load && uses_pool(technique)) s.pool_capacity = capacity_for_load(fragments, *load);
}

}  // namespace habuffer::harness
