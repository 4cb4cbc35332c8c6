/// @file
/// A technique and its knobs as one word, for lists on the command line:
/// NAME[:KEY=VALUE|:FLAG]... with NAME a technique of technique.h and
///   cull=TAU    early cull / early termination (ha, sorted-lists)
///   sat         saturation depth (with cull)
///   load=L      fixed size for load L of the scene's fragments: the
///               HA-buffer's table, the lists' pool (else automatic)
///   age=A       the HA-buffer's age bits
///   k=K         layers (arrays, kbuffer)
///   occ         the k-buffer's occupancy map; words=D its 32-bit words per pixel
/// e.g. "ha:cull=0.99:sat", "kbuffer:k=8:occ", "lists:load=0.8". One word per
/// configuration lets bench, sweep and frontier take lists of them. The knobs
/// are rows of the technique option table (habuffer/technique_options.h):
/// their names, ranges, rules (where each applies, what each needs) and
/// refusals are the CLI options' own.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "habuffer/extent.h"
#include "habuffer/render/render_job.h"
#include "habuffer/technique.h"

namespace habuffer::harness {

/// One technique word, parsed (see the file comment); unset knobs keep RenderSettings' defaults.
struct TechniqueSpec {
  Technique technique = Technique::Ha;  ///< NAME
  float cull = 0.0f;                    ///< cull=TAU: early cull's tau, 0 for off (BufferConfig::early_cull_tau)
  bool saturation = false;              ///< sat: the saturation depth (with cull)
  std::optional<double> load;           ///< load=L in (0, 1]: a fixed table or pool; none: automatic
  std::optional<std::uint32_t> age_bits;  ///< age=A: the HA-buffer's age bits
  std::optional<std::uint32_t> layers;    ///< k=K: layers of arrays and the k-buffer
  bool occupancy = false;                 ///< occ: the k-buffer's occupancy map
  std::optional<std::uint32_t> occupancy_words;  ///< words=D: the occupancy map's 32-bit words per pixel

  /// The canonical word ("ha:cull=0.99:sat"), parsed back to the same spec.
  [[nodiscard]] std::string label() const;
  /// Whether the technique keeps every fragment (no cull, no layers to overflow).
  [[nodiscard]] bool exact() const;
  /// The technique's fields of `s` set from the spec; `fragments` (those
  /// reaching insertion) sizes a table or pool given by load. Throws
  /// std::invalid_argument for a load no table can give on this screen.
  void apply(RenderSettings& s, std::uint64_t fragments) const;
};

/// Parses one technique word (see the file comment). Throws std::invalid_argument naming the word and the key.
TechniqueSpec parse_technique_spec(const std::string& word);

/// The table of about fragments / load slots with the screen's aspect ratio
/// (sides rounded up). Throws std::invalid_argument when it would be smaller
/// than the screen (SPEC 1's geometry rule), naming the largest load possible.
Extent table_for_load(Extent screen, std::uint64_t fragments, double load);
/// Nodes (or per-pixel layers) for `load`: ceil(fragments / load), at least 1.
std::uint64_t capacity_for_load(std::uint64_t fragments, double load);

}  // namespace habuffer::harness
