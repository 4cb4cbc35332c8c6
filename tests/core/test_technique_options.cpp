// The technique option table (issue 24, item 2): each option declared once,
// with one flag and one knob; its default is TechniqueConfig's own (what the
// help prints reads back as the default configuration); every option a
// descriptor lists and that sets a field is a row; the report fields are the
// rows' JSON keys where the technique takes the option.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "habuffer/technique_descriptor.h"
#include "habuffer/technique_options.h"
#include "test_support.h"

namespace habuffer {
namespace {

TEST(TechniqueOptions, FlagsKnobsAndJsonKeysAreEachDeclaredOnce) {
  std::set<std::string_view> flags, knobs, keys;
  for (const TechniqueOption& o : technique_options()) {
    EXPECT_FALSE(o.flag.empty() && o.knob.empty()) << "a row neither the CLI nor the words read";
    if (!o.flag.empty()) { EXPECT_TRUE(flags.insert(o.flag).second) << o.flag; }
    if (!o.knob.empty()) { EXPECT_TRUE(knobs.insert(o.knob).second) << o.knob; }
    if (!o.json.empty()) { EXPECT_TRUE(keys.insert(o.json).second) << o.json; }
    if (!o.flag.empty()) { EXPECT_EQ(find_option_flag(o.flag), &o); }
    if (!o.knob.empty()) { EXPECT_EQ(find_option_knob(o.knob), &o); }
    if (!o.needs.empty()) { EXPECT_NE(find_option_flag(o.needs), nullptr) << o.flag << " needs " << o.needs; }
    EXPECT_EQ(o.get == nullptr, o.put == nullptr) << o.flag;
  }
}

TEST(TechniqueOptions, TheDefaultTheHelpPrintsReadsBackAsTheDefaultConfiguration) {
  for (const TechniqueOption& o : technique_options()) {
    if (o.get == nullptr || o.kind == OptionKind::Threshold) continue;  // a threshold's default is "absent: off"
    TechniqueConfig c;
    set_option(o, c, option_default_text(o));
    EXPECT_EQ(c, TechniqueConfig{}) << o.flag << " " << option_default_text(o);
  }
  EXPECT_EQ(option_default_text(*find_option_flag("layers")), std::to_string(HABUFFER_DEFAULT_LAYERS));
  EXPECT_EQ(option_default_text(*find_option_flag("pool")), "auto");
  EXPECT_EQ(option_default_text(*find_option_flag("early-cull")), "off");
  EXPECT_EQ(option_default_text(*find_option_flag("depth-range")), "0,1");
}

TEST(TechniqueOptions, ValuesReadBackThroughTheirTextAndBadOnesGiveTheReasonAlone) {
  for (const TechniqueOption& o : technique_options()) {
    if (o.get == nullptr) continue;
    TechniqueConfig c;
    const std::string text = o.kind == OptionKind::Threshold ? "0.5" : option_default_text(o);
    set_option(o, c, text);
    EXPECT_EQ(option_value_text(o, o.get(c)), text) << o.flag;
  }
  const auto reason = [](const char* flag, const char* text) {
    try {
      (void)parse_option_value(*find_option_flag(flag), text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(reason("layers", "0"), "0 outside 1..65536");
  EXPECT_EQ(reason("occupancy", "yes"), "'yes' is not on or off");
  EXPECT_EQ(reason("depth-range", "0.5"), "'0.5' is not NEAR,FAR (two depths in [0, 1])");
  EXPECT_EQ(reason("depth-range", "0.5,0.25"), "0.5,0.25 is not an interval NEAR < FAR within [0, 1]");
  EXPECT_EQ(reason("pool", "auto"), "accepted");
}

TEST(TechniqueOptions, EveryDescriptorOptionThatSetsATechniqueFieldIsARowAndReportsFollowTheRows) {
  for (const TechniqueDescriptor* d : technique_registry()) {
    // The options that set no TechniqueConfig field: the table's size and
    // offsets (the command's), lossless mode, the CPU order, the dumps.
    static const std::set<std::string_view> not_fields = {"table", "offsets", "seed", "lossless", "max-attempts",
                                                          "insert-order", "dump-table", "dump-max-age"};
    for (std::string_view option : d->options)
      EXPECT_TRUE(find_option_flag(option) != nullptr || not_fields.count(option) != 0) << d->name << " " << option;
    TechniqueConfig c = test::technique_config(d->technique, {4, 4});
    c.occupancy = d->takes("occupancy");
    std::set<std::string_view> reported;
    for (const ReportField& f : technique_report_fields(c, 32)) reported.insert(f.name);
    for (const TechniqueOption& o : technique_options())
      if (!o.json.empty()) { EXPECT_EQ(reported.count(o.json) != 0, d->takes(o.flag)) << d->name << " " << o.json; }
  }
}

}  // namespace
}  // namespace habuffer
