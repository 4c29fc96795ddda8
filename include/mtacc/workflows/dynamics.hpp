#pragma once
// Workflows `dynamics modes | frf | accel | map`: the rigid-body structural dynamics of a
// structure model (seed 000 part II) at given axis positions, or over a grid of two axes.
// Units at this boundary: positions in mm, frequencies in Hz, compliances in um/N,
// acceleration responses in um/g_n.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mtacc/dynamics/rigid_body_dynamics.hpp"
#include "mtacc/workflows/machine_setup.hpp"

namespace mtacc {

// The model's axes (travel in mm) and bodies (mass, centre and bounding box in mm, the axes
// that move each), for drawing.
// A structure model file (docs/file-formats.md "Structure models") or a bundled model's name.
StructureModel loadStructureModel(const std::string& pathOrName);
nlohmann::json structureJson(const StructureModel& model);

// "Y=400,Z=-300" (mm); the other axes at 0. Throws InputError naming `key`.
std::vector<double> structurePositions(const StructureModel& model, const std::string& text, const std::string& key = "at");

struct ModesResult {
  std::string model;
  StructureMatrices matrices;
  Modes undamped;
  std::vector<DampedMode> damped;
  std::vector<std::string> bodies;  // per mode: the body of the largest kinetic energy
  std::vector<std::string> dofs;    // and its DOF (x y z rx ry rz)
};
ModesResult structureModes(const StructureModel& model, const std::vector<double>& positions);
// The first `count` modes, each with its mass-normalised shape (6 per body: m and rad).
nlohmann::json toJson(const ModesResult& result, int count);

struct FrfRequest {
  std::vector<double> positions;  // m
  std::vector<double> frequencies;  // Hz
  // "auto": the modal sum where the damping is proportional (it is exact there), else the
  // direct solve; "modal" or "direct" to force one (a forced modal sum on a non-proportional
  // damping is flagged in the result's warnings).
  std::string method = "auto";
};
struct FrfResult {
  std::string model;
  std::string method;            // the one that computed the FRF: "modal" or "direct"
  double dampingCoupling = 0;    // modalDampingCoupling: 0 for proportional damping
  std::vector<std::string> warnings;
  std::vector<double> frequencies;
  Frf frf;                       // m/N
  Eigen::Matrix3d staticCompliance;  // m/N
};
// Frequencies from `from` to `to` in `step`s (Hz): at most 1,000,000 of them.
std::vector<double> frequencyGrid(double from, double to, double step);
FrfResult structureFrf(const StructureModel& model, const FrfRequest& request);
nlohmann::json toJson(const FrfResult& result);

struct AccelerationResult {
  std::string model;
  std::vector<std::string> axes;
  Eigen::MatrixXd response;  // 3 x axes, um / g_n
};
AccelerationResult structureAcceleration(const StructureModel& model, const std::vector<double>& positions);
nlohmann::json toJson(const AccelerationResult& result);

struct MapRequest {
  std::string quantity = "Hx/X";
  MapGrid grid;
};
struct MapResult {
  std::string model;
  DynamicsQuantity quantity;
  DynamicsMap map;
};
MapResult structureMap(const StructureModel& model, const MapRequest& request);
nlohmann::json toJson(const MapResult& result);

}  // namespace mtacc
