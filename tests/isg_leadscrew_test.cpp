// TwinCAT/ISG bilateral leadscrew error compensation lists (issue 46): the reversal beside the
// volumetric compensation, in the documentation's sign and units, read back and applied as the
// controller applies them.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <regex>
#include <sstream>

#include "mtacc/compensation/isg_leadscrew.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

struct LeadscrewList {
  std::map<std::string, std::string> fields;
  std::vector<long long> setpoint, pos, neg;
};

LeadscrewList readList(const std::string& text) {
  LeadscrewList list;
  std::istringstream file(text);
  std::string line;
  const std::regex entry(R"(kw\.ssfk\.table\[(\d+)\]\.(setpoint|pos|neg) (-?\d+))"), field(R"((\S+) (\S+))");
  while (std::getline(file, line)) {
    std::smatch m;
    if (line.starts_with("#")) continue;
    if (std::regex_match(line, m, entry)) {
      auto& column = m[2] == "setpoint" ? list.setpoint : m[2] == "pos" ? list.pos : list.neg;
      EXPECT_EQ(static_cast<size_t>(std::stoi(m[1])), column.size()) << line;
      column.push_back(std::stoll(m[3]));
    } else if (std::regex_match(line, m, field)) {
      list.fields[m[1]] = m[2];
    } else {
      ADD_FAILURE() << "not a list line: " << line;
    }
  }
  return list;
}

// The kernel documentation's example (FCT-C5, "Example - non-equidistant bilateral LSEC"): at
// 19866.7 um programmed on the Y axis, 19856.5 um reached moving positive and 19874.7 um moving
// negative; the list holds -102 and 80 (0.1 um), actual less programmed. The corrections that
// put the axis at 19866.7 each way are +10.2 um and -8.0 um.
TEST(IsgLeadscrew, TheDocumentationsExampleInItsSignAndUnits) {
  const auto machine = test::bundled("three-axis-vertical");
  const AxisReversalTable y{"Y", 1, false, false, {19.8667}, {0.0102}, {-0.0080}};
  LeadscrewList list = readList(isgLeadscrewList(*machine, y));
  EXPECT_EQ(list.setpoint, std::vector<long long>{198667});
  EXPECT_EQ(list.pos, std::vector<long long>{-102});
  EXPECT_EQ(list.neg, std::vector<long long>{80});
  EXPECT_EQ(list.fields["kopf.log_achs_name"], "Y");
  EXPECT_EQ(list.fields["kw.ssfk.bilateral"], "1");
  EXPECT_EQ(list.fields["kw.ssfk.unit"], "1");
  EXPECT_EQ(list.fields["kw.ssfk.interval"], "0");
  EXPECT_EQ(list.fields["kw.ssfk.kw_nr_max"], "1");
  EXPECT_EQ(list.fields["kw.ssfk.kw_startpos"], "198667");
}

// A machine whose only errors are the axes' reversals: the lists of the trims rounded to 0.1 um,
// read back, the setpoint changed by the negated value of the direction the axis moves in
// (linear between the points), leave at most the rounding, 0.05 um on each axis.
TEST(IsgLeadscrew, BilateralListsCarryTheReversalToTheListsUnit) {
  const auto machine = test::bundled("three-axis-vertical");
  const ErrorModel errors = parseErrors(*machine, "errors:\n  EXX: {reversal: 3 um}\n  EYY: {reversal: 2 um}\n  EZZ: {reversal: 1.5 um}\n",
                                        "reversals.yaml", ErrorsKey::Required);
  const CorrectionGrid grid = correctionGrid(machine, errors, {{7, 5, 6}, {}});
  std::array<ReversalTrims, 3> trims;
  for (int a = 0; a < 3; ++a) trims[static_cast<size_t>(a)] = reversalTrims(machine, errors, grid, a);
  const auto tables = axisReversalTables(*machine, grid, roundedTrims(trims, kIsgLeadscrewUnit), {});
  ASSERT_EQ(tables.size(), 3u);
  std::array<LeadscrewList, 3> lists;
  for (const auto& t : tables) {
    lists[static_cast<size_t>(t.index)] = readList(isgLeadscrewList(*machine, t));
    EXPECT_EQ(lists[static_cast<size_t>(t.index)].fields["kopf.achs_nr"], std::to_string(t.index + 1));
  }
  EXPECT_EQ(lists[0].pos.front() - lists[0].neg.front(), -30);  // X's 3 um reversal, in 0.1 um
  const auto value = [&](int axis, double p, int motion) {
    const LeadscrewList& l = lists[static_cast<size_t>(axis)];
    const auto& column = motion > 0 ? l.pos : l.neg;
    const double x = p / kIsgLeadscrewUnit;
    size_t k = 0;
    while (k + 2 < l.setpoint.size() && x > static_cast<double>(l.setpoint[k + 1])) ++k;
    const double t = std::clamp((x - static_cast<double>(l.setpoint[k])) / static_cast<double>(l.setpoint[k + 1] - l.setpoint[k]), 0.0, 1.0);
    return ((1.0 - t) * static_cast<double>(column[k]) + t * static_cast<double>(column[k + 1])) * kIsgLeadscrewUnit;
  };
  const KinematicModel actual = compile(machine, errors), nominal = compileNominal(machine);
  std::mt19937 rng(11);
  double largest = 0.0;
  for (int s = 0; s < 300; ++s) {
    std::vector<double> q(3), commanded(3);
    std::vector<int> motion(3);
    for (int a = 0; a < 3; ++a) {
      const auto ua = static_cast<size_t>(a);
      q[ua] = std::uniform_real_distribution<double>(grid.node(a, 0), grid.node(a, grid.counts[ua] - 1))(rng);
      motion[ua] = rng() % 2 ? 1 : -1;
      commanded[ua] = q[ua] - value(a, q[ua], motion[ua]);
    }
    largest = std::max(largest, (toolPoint(actual, commanded.data(), motion.data()).position - toolPoint(nominal, q.data()).position).norm());
  }
  RecordProperty("largest_um", std::to_string(largest * 1e3));
  EXPECT_LE(largest, std::sqrt(3.0) * 0.5 * kIsgLeadscrewUnit + 1e-9);
}

}  // namespace
}  // namespace mtacc
