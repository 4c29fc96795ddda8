#include "reference_values.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace mtacc::test {
namespace {

// Fields separated by tabs: seed, where, quantity, printed, mtacc, difference, unit, verdict.
void record(const Printed& p, const std::string& mtacc, const std::string& difference, const std::string& verdict) {
  static std::set<std::string> seen;
  const std::string key = "reference " + p.where + " " + p.quantity;
  EXPECT_TRUE(seen.insert(key).second) << key << " is recorded twice";
  ::testing::Test::RecordProperty(key, fmt::format("{}\t{}\t{}\t{:.{}f}\t{}\t{}\t{}\t{}", p.seed, p.where, p.quantity, p.value,
                                                   p.decimals, mtacc, difference, p.unit, verdict));
}

std::string shown(const Printed& p, double v) {
  const std::string text = fmt::format("{:.{}f}", v, p.decimals + 2);
  return text.find_first_of("123456789") == std::string::npos ? text.substr(text[0] == '-') : text;  // no "-0.00"
}

double halfDigit(const Printed& p) { return 0.5 * std::pow(10.0, -p.decimals); }

}  // namespace

void expectReproduced(const Printed& p, double mtacc, double tolerance, const std::string& why) {
  EXPECT_NEAR(mtacc, p.value, tolerance) << p.where << ", " << p.quantity << " [" << p.unit << "]";
  record(p, shown(p, mtacc), shown(p, mtacc - p.value), fmt::format("reproduced within {:g} ({})", tolerance, why));
}

void expectInputEchoed(const Printed& p, double mtacc, double tolerance, const std::string& why) {
  EXPECT_NEAR(mtacc, p.value, tolerance) << p.where << ", " << p.quantity << " [" << p.unit << "]";
  record(p, shown(p, mtacc), shown(p, mtacc - p.value), fmt::format("input echoed within {:g} ({})", tolerance, why));
}

void expectSelfConsistent(const Printed& injected, double recovered, double tolerance, const std::string& why) {
  EXPECT_NEAR(recovered, injected.value, tolerance) << injected.where << ", " << injected.quantity << " [" << injected.unit << "]";
  record(injected, shown(injected, recovered), shown(injected, recovered - injected.value),
         fmt::format("self-consistent within {:g} ({})", tolerance, why));
}

void expectKnownDifference(const Printed& p, double mtacc, double today, double pin, const std::string& reason) {
  EXPECT_NEAR(mtacc, today, pin) << p.where << ", " << p.quantity << ": today's value changed";
  EXPECT_GT(std::abs(mtacc - p.value), halfDigit(p))
      << p.where << ", " << p.quantity << " now reproduces the printed value: move it to expectReproduced";
  record(p, shown(p, mtacc), shown(p, mtacc - p.value), "known difference: " + reason);
}

void recordNotComputed(const Printed& p, const std::string& reason) { record(p, "", "", "not computed: " + reason); }

}  // namespace mtacc::test
