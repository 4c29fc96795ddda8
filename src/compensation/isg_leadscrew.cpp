#include "mtacc/compensation/isg_leadscrew.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

namespace mtacc {

std::string isgLeadscrewList(const Machine& machine, const AxisReversalTable& r) {
  const auto units = [](double v) { return static_cast<long long>(std::llround(v / kIsgLeadscrewUnit)); };
  std::string out = fmt::format(
      "# mtacc: the reversal of {} on {} as bilateral leadscrew error compensation, beside the volumetric compensation\n"
      "# values: the error corrected (actual less programmed) moving positive (pos) and negative (neg), in 0.1 um (0.0001 deg)\n"
      "# activate with lr_param.ssfk 1 (P-AXIS-00175) in the axis's machine data; {} entries{}\n"
      "kopf.achs_nr {}\nkopf.log_achs_name {}\nkw.ssfk.interval 0\nkw.ssfk.kw_startpos {}\nkw.ssfk.kw_nr_max {}\nkw.ssfk.unit 1\n"
      "kw.ssfk.bilateral 1\nkw.ssfk.modulo {}\n",
      r.axis, machine.name, r.positions.size(), r.positions.size() > 1500 ? ": set P-COMP-00059 to at least that" : "", r.index + 1, r.axis,
      units(r.positions.front()), r.positions.size(), r.modulo ? 1 : 0);
  auto it = std::back_inserter(out);
  for (size_t n = 0; n < r.positions.size(); ++n) fmt::format_to(it, "kw.ssfk.table[{}].setpoint {}\n", n, units(r.positions[n]));
  for (size_t n = 0; n < r.forward.size(); ++n) fmt::format_to(it, "kw.ssfk.table[{}].pos {}\n", n, -units(r.forward[n]));
  for (size_t n = 0; n < r.reverse.size(); ++n) fmt::format_to(it, "kw.ssfk.table[{}].neg {}\n", n, -units(r.reverse[n]));
  return out;
}

}  // namespace mtacc
