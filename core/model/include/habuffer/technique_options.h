/// @file
/// The technique options, declared once: one row per option (the k-buffer's
/// K, a pool's nodes, early cull's threshold, ...) with its command-line
/// flag, its knob in the harness' technique words ("kbuffer:k=8:occ"), its
/// value's kind and range, its help line, its JSON report key, the option it
/// needs, and how it reads and writes its TechniqueConfig field. The CLI's
/// parsing, refusals and help, the technique words and the report fields
/// are written from this table; defaults are the TechniqueConfig's own
/// member initializers (read back for the help, never restated).
///
/// Which techniques take an option is their descriptors' `options` list
/// (technique_descriptor.h): that list is the per-technique view of this table.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "habuffer/technique.h"

namespace habuffer {

struct TechniqueDescriptor;

/// How an option's value is written and read.
enum class OptionKind {
  Count,        ///< an unsigned integer in [min, max]
  CountOrAuto,  ///< "auto" (stored as 0) or a count in [min, max]
  Switch,       ///< on|off on the command line; a flag knob ("occ") in technique words
  Threshold,    ///< early cull's threshold, a float32 in (0, 1] (parse_cull_threshold); absent: off
  Load,         ///< a target load factor in (0, 1] (parse_load_factor); technique words only
  Interval,     ///< NEAR,FAR: two depths, NEAR < FAR within [0, 1]
};

/// One option's value, by kind: Count and CountOrAuto a std::uint64_t,
/// Switch a bool, Threshold a float, Load a double, Interval a DepthRange.
using OptionValue = std::variant<std::uint64_t, bool, float, double, DepthRange>;

/// One technique option (see the file comment). Rows are constants.
struct TechniqueOption {
  std::string_view flag;        ///< the CLI's --flag; "" for a technique-word knob alone (load)
  std::string_view knob = {};        ///< its technique-word knob ("k", "occ"); "" where words have none
  std::string_view value_name = {};  ///< "K", "TAU", "N|auto", "NEAR,FAR"; "on|off" for a switch
  OptionKind kind;              ///< how the value is read
  std::uint64_t min = 0;        ///< Count, CountOrAuto: the smallest count
  std::uint64_t max = 0;        ///< Count, CountOrAuto: the largest count
  bool power_of_two = false;    ///< Count: only powers of two in [min, max] (samples per pixel)
  std::string_view help = {};        ///< what it sets, one phrase (the default is added from TechniqueConfig)
  std::string_view json = {};        ///< its key in the technique's report fields; "" for none
  /// The option (flag) that must be on for this one to be given ("" for
  /// none): --occupancy-words needs --occupancy on, --saturation on needs
  /// --early-cull TAU.
  std::string_view needs = {};
  /// The CLI's refusal when `needs` is not on, after "option --FLAG ".
  std::string_view without_needed = {};
  bool buffer_field = false;  ///< it writes the BufferConfig part (else the TechniqueChoice part)
  /// Its value in `config` (nullptr for Load: a load sizes the table or pool, it is no field).
  OptionValue (*get)(const TechniqueConfig& config) = nullptr;
  /// Stores `value` (of its kind) in `config`.
  void (*put)(TechniqueConfig& config, const OptionValue& value) = nullptr;
  /// Technique words: the techniques whose words take the knob (nullptr: any
  /// word; `needs` still applies).
  bool (*knob_applies)(const TechniqueDescriptor& d) = nullptr;
  /// The reported value where it is the built capacity rather than the
  /// configured one (K and pool nodes after lossless growth); nullptr: get().
  std::uint64_t (*reported)(const TechniqueConfig& config, std::uint64_t capacity) = nullptr;
};

/// Every technique option, in the order help, words' labels and reports list them.
std::span<const TechniqueOption> technique_options();
/// The row of CLI option `flag`; nullptr for any other name.
const TechniqueOption* find_option_flag(std::string_view flag);
/// The row of technique-word knob `knob`; nullptr for any other name.
const TechniqueOption* find_option_knob(std::string_view knob);

/// `text` read as `option`'s kind. Throws std::invalid_argument whose message
/// is the reason alone ("0 outside 1..65536"), for the caller to prefix with
/// the option or knob.
OptionValue parse_option_value(const TechniqueOption& option, std::string_view text);
/// parse_option_value, stored in `config`.
void set_option(const TechniqueOption& option, TechniqueConfig& config, std::string_view text);
/// Whether the option is in effect in `config`: a switch on, a threshold
/// above 0; every other kind whenever given (true).
bool option_on(const TechniqueOption& option, const TechniqueConfig& config);
/// `value` as the command line writes it ("auto" for a CountOrAuto 0, "off"
/// for a Threshold 0, "on"/"off", "NEAR,FAR").
std::string option_value_text(const TechniqueOption& option, const OptionValue& value);
/// Its default, a default TechniqueConfig's value as text; "" for Load.
std::string option_default_text(const TechniqueOption& option);
/// "k=K", "occ": the knob as a technique word writes it.
std::string knob_usage(const TechniqueOption& option);
/// "arrays, kbuffer": the techniques whose words take the knob (by
/// knob_applies; without one, those whose descriptors take the flag).
std::string techniques_taking_knob(const TechniqueOption& option);

}  // namespace habuffer
