#include "file_values.h"

#include <utility>

#include "habuffer/harness/workload.h"
#include "habuffer/list_text.h"
#include "habuffer/scene_catalog.h"

namespace habuffer::cli {
namespace {

std::vector<std::string> split(const std::string& text, char separator) { return split_list(text, separator); }

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t"), last = s.find_last_not_of(" \t");
  return first == std::string::npos ? std::string() : s.substr(first, last - first + 1);
}

bool is_solid_name(const std::string& name) { return name == "sphere" || name == "torus" || name == "box"; }

}  // namespace

std::vector<std::string> listed_files(const std::string& value) {
  std::vector<std::string> out;
  for (const std::string& item : split(value, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::vector<std::string> scene_file(const std::string& value) {
  if (value.empty()) return {};
  if (std::string file = scene_input_file(value); !file.empty()) return {file};
  return {};
}

std::vector<std::string> mesh_file(const std::string& value) {
  if (value.empty() || is_solid_name(value)) return {};
  return scene_file(value);
}

std::vector<std::string> scene_word_file(const std::string& value) {
  try {
    if (std::string file = harness::parse_workload_spec(value).input_file(); !file.empty()) return {file};
  } catch (const std::invalid_argument&) {
    // the command's own parse refuses the word
  }
  return {};
}

std::vector<std::string> scene_word_files(const std::string& value) {
  std::vector<std::string> out;
  for (const std::string& word : listed_files(value))
    for (std::string& file : scene_word_file(word)) out.push_back(std::move(file));
  return out;
}

std::vector<std::string> mesh_files(const std::string& value) {
  std::vector<std::string> out;
  for (const std::string& m : listed_files(value))
    for (std::string& file : mesh_file(m)) out.push_back(std::move(file));
  return out;
}

std::vector<std::string> solid_files(const std::string& value) {
  std::vector<std::string> out;
  for (const std::string& raw : split(value, ';')) {
    const std::string item = trimmed(raw);
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq + 1 >= item.size()) continue;
    const std::string spec = item.substr(eq + 1);
    const std::string kind = spec.substr(0, spec.find(':'));
    if (spec.find(':') != std::string::npos && (kind == "box" || kind == "sphere" || kind == "cylinder" || kind == "torus"))
      continue;
    out.push_back(spec);
  }
  return out;
}

std::vector<std::string> offsets_file(const std::string& value) {
  if (value == "random" || value == "farthest" || value.empty()) return {};
  return {value};
}

std::vector<std::string> heatmap_files(const std::string& value) {
  std::vector<std::string> out;
  for (const std::string& item : listed_files(value)) {
    const auto colon = item.find(':');
    if (colon != std::string::npos && colon + 1 < item.size()) out.push_back(item.substr(colon + 1));
  }
  return out;
}

}  // namespace habuffer::cli
