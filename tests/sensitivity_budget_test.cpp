// Sensitivity coefficients (seed 001 eq. 15) and the error budget against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "mtacc/kinematics/budget.hpp"
#include "mtacc/kinematics/jacobian.hpp"
#include "mtacc/workflows/budget.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

TEST(SensitivityBudget, ExactCoefficientTendsToTheJacobianProjection) {
  const auto machine = test::bundled("tilting-table");
  const auto errors = loadMachineErrors(*machine);
  const auto zero = compile(machine, ErrorModel::zero(*machine));
  const std::vector<double> q{40, -60, 120, -35 * kDeg, 70 * kDeg};
  const Vec3 n = Vec3(0.3, -0.5, 0.8).normalized();
  const auto params = parameterCatalogue(*machine, errors);
  // The coefficient is taken with all other errors zero, so compare with the Jacobian at zero
  // errors (same shapes of the component-error functions).
  ErrorModel shape = errors;
  for (const auto& p : params) setParameterValue(shape, p, 0.0);
  const auto jac = parameterJacobian(compile(machine, shape, params), zero, q.data());
  // E/eps is a one-sided difference: it differs from the derivative by the curvature term
  // (at most eps * |TCP| for a rotation) plus rounding (a few ulps of |TCP| divided by eps).
  const double arm = toolPoint(zero, q.data()).position.norm() + 1.0;
  for (size_t k = 0; k < params.size(); ++k) {
    const double eps = params[k].dimension == Dimension::Length ? 1e-5 : 1e-7;
    const double exact = sensitivityCoefficient(machine, errors, {params[k], eps}, {q.data(), n});
    const double first = n.dot(jac.col(static_cast<Eigen::Index>(k)).head<3>());
    const double bound = eps * arm + 8 * std::numeric_limits<double>::epsilon() * arm / eps;
    EXPECT_NEAR(exact, first, bound) << params[k].name;
  }
}

// The Maho machine's component errors are C1 piecewise quadratics (seed 003): each coefficient
// alone is no error of the machine (EXX.k2c2 alone moved the TCP by 4 mm while all errors
// together move it by 86 um). The budget has one line per error function, each bounded by the
// combined error's order of magnitude.
TEST(SensitivityBudget, BudgetOfAModelHasOneLinePerErrorFunction) {
  const auto setup = loadMachineSetup({"maho", "", "", std::nullopt, ""});
  BudgetOptions options;
  options.samplesPerAxis = 3;
  const auto r = errorBudget(setup, options);
  ASSERT_FALSE(r.entries.empty());
  std::set<std::string> names;
  for (const auto& e : r.entries) {
    EXPECT_TRUE(names.insert(e.name).second) << e.name << " twice";
    EXPECT_EQ(e.name.find('.'), std::string::npos) << e.name << ": a term of a function, not the function";
    EXPECT_LE(e.maxPositionError, 3 * r.combinedMaxPositionError) << e.name;
  }
  EXPECT_TRUE(names.count("EXX") == 1 && names.count("ECX") == 1);
}

// The step of k = E / epsilon on a coefficient per mm^2 is scaled to the function's value at the
// pose: the default 30 urad applied to the coefficient itself made the function 4 rad at
// X = 385 mm, and exact and first-order k then differed (17 with opposite signs).
TEST(SensitivityBudget, CoefficientStepsStayInTheLinearRange) {
  const auto setup = loadMachineSetup({"maho", "", "", std::nullopt, ""});
  SensitivityRequest request;
  request.q = {385, 275, 330, 45 * kDeg, -12 * kDeg};
  const auto r = sensitivities(setup, request);
  ASSERT_FALSE(r.rows.empty());
  for (const auto& row : r.rows) {
    // Both are per unit of the parameter; what one-sided differencing and rounding leave is
    // far below 1 % of the parameter's whole effect on the TCP.
    const double scale = row.position.norm();
    EXPECT_NEAR(row.kExact, row.kFirstOrder, 1e-3 * scale + 1e-9) << row.parameter.name;
  }
}

// Seed 001 §4.3 (seed lines 214-219): with the workpiece coordinate transformation M_WC,
// "the machined surface of ZONE I is not affected by the geometric errors of the rotary
// axes because no rotary axes are moving"; without it, it is (Fig. 10 vs Fig. 12).
TEST(SensitivityBudget, ZoneIUnaffectedByRotaryAxisErrorsWithMwc) {
  const char* names[] = {"δxBY", "δyBY", "δzBY", "αBY", "βBY", "γBY", "αCB", "δxCB"};
  for (const auto alignment : {WorkpieceAlignment::Machine, WorkpieceAlignment::Table}) {
    auto machine = std::make_shared<Machine>(loadMachine("tilting-table"));
    machine->alignment = alignment;
    const ErrorModel zero = ErrorModel::zero(*machine);
    double largest = 0;
    for (const std::string x : {"-16", "0", "16"})
      for (const std::string y : {"-16", "0", "16"}) {
        const std::vector<double> q{std::stod(x), std::stod(y), 50.0, 0.0, 0.0};  // ZONE I: B = C = 0, top face
        for (const char* name : names) {
          const auto p = findParameter(*machine, zero, name);
          const double eps = p.dimension == Dimension::Length ? 0.5 : 0.5 * kDeg;  // seed 001 §5.3: 0.5 mm, 0.5 deg
          largest = std::max(largest, std::abs(sensitivityCoefficient(machine, zero, {p, eps}, {q.data(), Vec3::UnitZ()})));
        }
      }
    if (alignment == WorkpieceAlignment::Machine)
      EXPECT_LT(largest, 1e-9);
    else
      EXPECT_GT(largest, 0.1);
  }
}

TEST(SensitivityBudget, ClosedFormsForSingleErrors) {
  const auto machine = test::bundled("tilting-table");
  const auto items = budgetItemsAtMagnitude(*machine, 0.010, 30e-6);
  const auto grid = workingVolumeGrid(*machine, 5);
  EXPECT_EQ(grid.rows(), 3125);
  const auto entries = errorBudget(machine, items, grid, 2);
  auto find = [&](const std::string& name) {
    for (const auto& e : entries)
      if (e.name == name) return e;
    ADD_FAILURE() << name;
    return entries.front();
  };
  // X0B translates the B-carried chain: 10 um everywhere.
  EXPECT_NEAR(find("X0B").maxPositionError, 0.010, 1e-12);
  // C0Y turns the Y direction by 30 urad: |dp| = |Y| * 2 sin(eps / 2), largest at |Y| = 300 mm.
  EXPECT_NEAR(find("C0Y").maxPositionError, 300 * 2 * std::sin(15e-6), 1e-12);
  // A constant EXX shifts the TCP by 10 um along the X carriage.
  EXPECT_NEAR(find("EXX").maxPositionError, 0.010, 1e-12);
  // The linear-axis tilt about its own direction is not a parameter.
  for (const auto& e : entries) EXPECT_NE(e.name, "A0X");
  for (size_t i = 1; i < entries.size(); ++i) EXPECT_GE(entries[i - 1].maxPositionError, entries[i].maxPositionError);
}

}  // namespace
}  // namespace mtacc
