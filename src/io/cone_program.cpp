#include "mtacc/io/cone_program.hpp"

#include <fmt/format.h>

#include "mtacc/core/units.hpp"

namespace mtacc {

std::string coneNcProgram(const Machine& m, const ConeSpec& s, const JointMatrix& q, double feed) {
  std::string g = fmt::format("; mtacc cone-frustum test piece (seed 000): alpha {:g} deg, beta {:g} deg, r {:g} mm\n",
                              s.alpha / kDeg, s.beta / kDeg, s.radius);
  g += fmt::format("; machine {}; axis positions in mm and deg; TCP feed {:g} mm/min\nG90 G94\n", m.name, feed);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    std::string line = fmt::format("N{} G01", 10 * (i + 1));
    for (int k = 0; k < m.commandedCount(); ++k) {
      const Axis& a = m.axes[static_cast<size_t>(k)];
      line += fmt::format(" {}{:.4f}", a.name, a.isRotary() ? q(i, k) / kDeg : q(i, k));
    }
    if (i == 0) line += fmt::format(" F{:g}", feed);
    g += line + "\n";
  }
  return g + "M30\n";
}

std::string coneClData(const ConePath& path) {
  std::string cl = "phi_deg,x,y,z,i,j,k,nx,ny,nz\n";
  for (size_t i = 0; i < path.phi.size(); ++i) {
    const auto &p = path.points[i], &t = path.tools[i], &n = path.normals[i];
    cl += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", path.phi[i] / kDeg, p.x(), p.y(), p.z(), t.x(), t.y(), t.z(), n.x(), n.y(),
                      n.z());
  }
  return cl;
}

}  // namespace mtacc
