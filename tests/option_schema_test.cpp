// The option schema's reader: every value checked against its key's kind and range, defaults
// stated once, and each refusal naming the key.
#include <gtest/gtest.h>

#include <functional>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/option_schema.hpp"

namespace mtacc {
namespace {

const OptionSchema& schema() {
  static const OptionSchema s{"test",
                              {{"files", OptionKind::List, "files"},
                               {"name", OptionKind::Text, "a name"},
                               {"fast", OptionKind::Flag, "go fast"},
                               {.key = "step", .kind = OptionKind::Quantity, .help = "step", .defaultText = "2 um", .low = 1e-6,
                                .high = 1.0, .outOfRange = "must be from 1 nm to 1 mm"},
                               {.key = "share", .kind = OptionKind::Number, .help = "share", .defaultText = "0.1", .low = 0, .high = 1,
                                .lowExcluded = true, .outOfRange = "must be above 0 and at most 1"},
                               {.key = "threads", .kind = OptionKind::Count, .help = "threads", .defaultText = "0", .low = 0,
                                .high = 1024, .outOfRange = "must be from 0 to 1024"},
                               {"repeat", OptionKind::Count, "a count without a range"}}};
  return s;
}

std::string refusal(const OptionValues& values, const std::function<void(const OptionReader&)>& read) {
  try {
    read(OptionReader(schema(), values));
  } catch (const InputError& e) {
    return e.where().key + ": " + e.reason();
  }
  return "accepted";
}

TEST(OptionSchema, DefaultsApplyWhereNothingIsGiven) {
  const OptionValues none;
  const OptionReader read(schema(), none);
  EXPECT_TRUE(read.list("files").empty());
  EXPECT_FALSE(read.text("name"));
  EXPECT_FALSE(read.flag("fast"));
  EXPECT_DOUBLE_EQ(*read.quantity("step"), 2e-3);
  EXPECT_DOUBLE_EQ(*read.number("share"), 0.1);
  EXPECT_EQ(*read.count("threads"), 0);
}

TEST(OptionSchema, ValuesAreReadInTheirKindAndUnit) {
  const OptionValues given{{"files", {"a.csv,b.csv", "c.csv"}}, {"fast", {"true"}}, {"step", {"5 nm"}}, {"share", {"1"}}, {"threads", {"3"}}};
  const OptionReader read(schema(), given);
  EXPECT_EQ(read.list("files"), (std::vector<std::string>{"a.csv", "b.csv", "c.csv"}));
  EXPECT_TRUE(read.flag("fast"));
  EXPECT_DOUBLE_EQ(*read.quantity("step"), 5e-6);
  EXPECT_DOUBLE_EQ(*read.number("share"), 1.0);
  EXPECT_EQ(*read.count("threads"), 3);
}

TEST(OptionSchema, EachRefusalNamesItsKey) {
  EXPECT_EQ(refusal({{"speed", {"1"}}}, [](const OptionReader&) {}),
            "speed: not an option of test; its options are: files, name, fast, step, share, threads, repeat");
  EXPECT_EQ(refusal({{"name", {"a", "b"}}}, [](const OptionReader&) {}), "name: given more than once");
  EXPECT_EQ(refusal({{"fast", {"yes"}}}, [](const OptionReader& r) { r.flag("fast"); }), "fast: expected true or false, not 'yes'");
  EXPECT_EQ(refusal({{"step", {"0.5 nm"}}}, [](const OptionReader& r) { r.quantity("step"); }), "step: must be from 1 nm to 1 mm");
  EXPECT_EQ(refusal({{"step", {"1 deg"}}}, [](const OptionReader& r) { r.quantity("step"); }), "step: expected a length");
  EXPECT_EQ(refusal({{"share", {"0"}}}, [](const OptionReader& r) { r.number("share"); }), "share: must be above 0 and at most 1");
  EXPECT_EQ(refusal({{"share", {"nan"}}}, [](const OptionReader& r) { r.number("share"); }), "share: not a finite number: 'nan'");
  EXPECT_EQ(refusal({{"threads", {"1.5"}}}, [](const OptionReader& r) { r.count("threads"); }), "threads: expected a whole number, not '1.5'");
  EXPECT_EQ(refusal({{"threads", {"1025"}}}, [](const OptionReader& r) { r.count("threads"); }), "threads: must be from 0 to 1024");
  // A whole number beyond an int, where no range is declared: refused, not converted with overflow.
  EXPECT_EQ(refusal({{"repeat", {"1e12"}}}, [](const OptionReader& r) { r.count("repeat"); }),
            "repeat: '1e12' is out of range: at most 2147483647 in size");
}

TEST(OptionSchema, APositionalKeyMustBeGiven) {
  const OptionSchema withFile{"file", {{.key = "test", .kind = OptionKind::Text, .help = "the file", .positional = true}}};
  try {
    OptionReader(withFile, {});
    ADD_FAILURE() << "a missing positional key was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "test: is required");
  }
  const OptionValues given{{"test", {"a.csv"}}};
  EXPECT_EQ(*OptionReader(withFile, given).text("test"), "a.csv");
}

TEST(OptionSchema, BothEndsOfARangeAsDeclared) {
  const OptionField& share = *schema().find("share");
  EXPECT_THROW(requireInRange(share, 0.0), InputError);
  EXPECT_NO_THROW(requireInRange(share, 1.0));
  EXPECT_THROW(requireInRange(share, 1.0 + 1e-12), InputError);
  const OptionField& threads = *schema().find("threads");
  EXPECT_NO_THROW(requireInRange(threads, 0.0));
}

TEST(OptionSchema, ASubsetKeepsTheFieldsItNames) {
  const OptionSchema small = schema().subset("small", {"threads", "files"});
  EXPECT_EQ(small.keys(), (std::vector<std::string>{"threads", "files"}));
  EXPECT_EQ(small.at("threads").outOfRange, "must be from 0 to 1024");
}

TEST(OptionSchema, HelpStatesTheUnitAndTheDefault) {
  EXPECT_EQ(optionHelp(schema().at("step")), "step (a length with its unit, e.g. 0.5um); default 2 um");
}

}  // namespace
}  // namespace mtacc
