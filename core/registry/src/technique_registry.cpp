#include "habuffer/technique_descriptor.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <type_traits>

#include "habuffer/technique_list.h"
#include "habuffer/technique_options.h"

// Each technique's folder defines its descriptor(); the list names them.
#define HABUFFER_DECLARE_DESCRIPTOR(Enumerator, ns) \
  namespace habuffer::techniques::ns {              \
  const TechniqueDescriptor& descriptor();          \
  }
HABUFFER_TECHNIQUES(HABUFFER_DECLARE_DESCRIPTOR)
#undef HABUFFER_DECLARE_DESCRIPTOR

namespace habuffer {
namespace {

// Built on first use, so no descriptor is read before its folder's constant
// is initialised (they live in other translation units).
const std::array<const TechniqueDescriptor*, kTechniqueCount>& registry() {
#define HABUFFER_LIST_DESCRIPTOR(Enumerator, ns) &techniques::ns::descriptor(),
  static const std::array<const TechniqueDescriptor*, kTechniqueCount> list = {
      HABUFFER_TECHNIQUES(HABUFFER_LIST_DESCRIPTOR)};
#undef HABUFFER_LIST_DESCRIPTOR
  static const bool checked = (check_registry_order<TechniqueDescriptor>(list, "technique registry"), true);
  (void)checked;
  return list;
}

std::string cell(std::string_view text) {
  std::string s(text);
  for (char& c : s)
    if (c == '|') c = '/';
  return s;
}

}  // namespace

bool TechniqueDescriptor::takes(std::string_view option) const {
  return std::find(options.begin(), options.end(), option) != options.end();
}

std::string loss_hint(Technique t) {
  const TechniqueDescriptor& d = descriptor(t);
  std::string hint(d.lossless_hint);
  if (!hint.empty() && d.stores_lists && !d.overflow_keeps_nearest)
    hint += "; which fragments drop depends on their arrival order, so lossy lists differ between paths, thread "
            "counts and insert orders";
  return hint;
}

const TechniqueDescriptor& descriptor(Technique t) {
  const auto i = static_cast<std::size_t>(t);
  if (i >= kTechniqueCount) throw std::invalid_argument("technique " + std::to_string(i) + " is not registered");
  return *registry()[i];
}

std::span<const TechniqueDescriptor* const> technique_registry() { return registry(); }

const TechniqueDescriptor* find_technique(std::string_view name) {
  for (const TechniqueDescriptor* d : registry())
    if (d->name == name) return d;
  return nullptr;
}

std::string techniques_taking(std::string_view option) {
  std::string s;
  for (const TechniqueDescriptor* d : registry())
    if (d->takes(option)) s += (s.empty() ? "" : ", ") + std::string(d->name);
  return s;
}

std::vector<ReportField> technique_report_fields(const TechniqueConfig& c, std::uint64_t capacity) {
  const TechniqueDescriptor& d = descriptor(c.technique);
  std::vector<ReportField> fields;
  for (const TechniqueOption& o : technique_options()) {
    if (o.json.empty() || !d.takes(o.flag)) continue;
    const TechniqueOption* needed = o.needs.empty() ? nullptr : find_option_flag(o.needs);
    if (needed != nullptr && !option_on(*needed, c)) continue;
    if (o.reported != nullptr) {
      fields.push_back({o.json, o.reported(c, capacity)});
      continue;
    }
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, std::uint64_t> || std::is_same_v<V, bool> || std::is_same_v<V, DepthRange>)
            fields.push_back({o.json, v});
          else
            throw std::logic_error("technique option --" + std::string(o.flag) + ": no report type for its value");
        },
        o.get(c));
  }
  return fields;
}

std::string property_table_markdown(std::size_t per_table) {
  using Row = std::pair<const char*, std::string_view TechniqueProperties::*>;
  static constexpr Row rows[] = {
      {"storage", &TechniqueProperties::storage},
      {"bytes per stored fragment (model)", &TechniqueProperties::bytes_per_fragment},
      {"passes", &TechniqueProperties::passes},
      {"atomics per fragment", &TechniqueProperties::atomics_per_fragment},
      {"sorted", &TechniqueProperties::sorted},
      {"exact when", &TechniqueProperties::exact_when},
      {"overflow", &TechniqueProperties::overflow},
      {"early cull", &TechniqueProperties::early_cull},
      {"host shaders", &TechniqueProperties::host_shaders},
  };
  if (per_table == 0) per_table = 1;
  const auto all = registry();
  std::string md;
  for (std::size_t first = 0; first < all.size(); first += per_table) {
    const std::size_t last = std::min(all.size(), first + per_table);
    if (!md.empty()) md += "\n";
    md += "|";
    for (std::size_t i = first; i < last; ++i)
      md += " | `" + std::string(all[i]->name) + "` (" + std::string(all[i]->properties.source) + ")";
    md += " |\n|---|";
    for (std::size_t i = first; i < last; ++i) md += "---|";
    md += "\n";
    for (const Row& row : rows) {
      md += std::string("| ") + row.first;
      for (std::size_t i = first; i < last; ++i) md += " | " + cell(all[i]->properties.*row.second);
      md += " |\n";
    }
  }
  return md;
}

}  // namespace habuffer
