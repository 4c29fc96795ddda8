#include "reference_values.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace mtacc::test {
namespace {

// Fields separated by tabs: seed, where, quantity, printed, mtacc, difference, unit, verdict.
void recordRow(const std::string& seed, const std::string& where, const std::string& quantity, const std::string& printed,
               const std::string& mtacc, const std::string& difference, const std::string& unit, const std::string& verdict) {
  static std::set<std::string> seen;
  const std::string key = "reference " + where + " " + quantity;
  EXPECT_TRUE(seen.insert(key).second) << key << " is recorded twice";
  ::testing::Test::RecordProperty(key, fmt::format("{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}", seed, where, quantity, printed, mtacc, difference, unit, verdict));
}

void record(const Printed& p, const std::string& mtacc, const std::string& difference, const std::string& verdict) {
  recordRow(p.seed, p.where, p.quantity, fmt::format("{:.{}f}", p.value, p.decimals), mtacc, difference, p.unit, verdict);
}

std::string shown(const Printed& p, double v) {
  const std::string text = fmt::format("{:.{}f}", v, p.decimals + 2);
  return text.find_first_of("123456789") == std::string::npos ? text.substr(text[0] == '-') : text;  // no "-0.00"
}

double halfDigit(const Printed& p) { return 0.5 * std::pow(10.0, -p.decimals); }

}  // namespace

namespace {

// The three categories judged by a tolerance around the printed (or injected) value.
void expectWithin(const char* category, const Printed& p, double mtacc, double tolerance, const std::string& why) {
  EXPECT_NEAR(mtacc, p.value, tolerance) << p.where << ", " << p.quantity << " [" << p.unit << "]";
  record(p, shown(p, mtacc), shown(p, mtacc - p.value), fmt::format("{} within {:.3g} ({})", category, tolerance, why));
}

}  // namespace

void expectReproduced(const Printed& p, double mtacc, double tolerance, const std::string& why) {
  expectWithin("reproduced", p, mtacc, tolerance, why);
}

void expectInputEchoed(const Printed& p, double mtacc, double tolerance, const std::string& why) {
  expectWithin("input echoed", p, mtacc, tolerance, why);
}

void expectSelfConsistent(const Printed& injected, double recovered, double tolerance, const std::string& why) {
  expectWithin("self-consistent", injected, recovered, tolerance, why);
}

void expectKnownDifference(const Printed& p, double mtacc, double today, double pin, const std::string& reason) {
  EXPECT_NEAR(mtacc, today, pin) << p.where << ", " << p.quantity << ": today's value changed";
  EXPECT_GT(std::abs(mtacc - p.value), halfDigit(p))
      << p.where << ", " << p.quantity << " now reproduces the printed value: move it to expectReproduced";
  record(p, shown(p, mtacc), shown(p, mtacc - p.value), "known difference: " + reason);
}

void expectStatementHolds(const Statement& st, bool holds, const std::string& mtacc, const std::string& why) {
  EXPECT_TRUE(holds) << st.where << ", " << st.quantity << ": " << st.printed << " does not hold for mtacc's " << mtacc;
  recordRow(st.seed, st.where, st.quantity, st.printed, mtacc, "", "", "reproduced: " + why);
}

void expectStatementFails(const Statement& st, bool holds, const std::string& mtacc, const std::string& reason) {
  EXPECT_FALSE(holds) << st.where << ", " << st.quantity << " now holds for mtacc's " << mtacc << ": move it to expectStatementHolds";
  recordRow(st.seed, st.where, st.quantity, st.printed, mtacc, "", "", "known difference: " + reason);
}

void recordNotComputed(const Printed& p, const std::string& reason) { record(p, "", "", "not computed: " + reason); }

}  // namespace mtacc::test
