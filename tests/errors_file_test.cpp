// Errors files written by mtacc (identify --errors-out) read back to the model they were written
// from, and the terms identify names (EXX.c1, ECC.h2c) mean in an errors file what they mean there.
#include <gtest/gtest.h>

#include <cmath>

#include "mtacc/core/input_error.hpp"
#include "mtacc/io/bundled_data.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "test_helpers.hpp"

namespace mtacc {
namespace {

// Every parameter and every function value (both directions of motion, across the travel) and
// every stiffness change the same.
void expectSameErrors(const Machine& m, const ErrorModel& a, const ErrorModel& b) {
  const auto pa = parameterCatalogue(m, a), pb = parameterCatalogue(m, b);
  ASSERT_EQ(pa.size(), pb.size());
  for (size_t k = 0; k < pa.size(); ++k) {
    EXPECT_EQ(pa[k].name, pb[k].name);
    const double va = parameterValue(a, pa[k]);
    EXPECT_NEAR(parameterValue(b, pb[k]), va, 1e-13 * std::max(1.0, std::abs(va))) << pa[k].name;
  }
  for (size_t axis = 0; axis < m.axes.size(); ++axis) {
    const auto span = harmonicSpan(m.axes[axis]);
    for (int c = 0; c < 6; ++c)
      for (int i = 0; i <= 40; ++i)
        for (int direction : {-1, 1}) {
          const double q = span.min + span.range * i / 40.0;
          const double va = a.axes[axis].motion[static_cast<size_t>(c)].value(q, direction);
          EXPECT_NEAR(b.axes[axis].motion[static_cast<size_t>(c)].value(q, direction), va, 1e-12 * std::max(1e-3, std::abs(va)))
              << motionErrorName(m, static_cast<int>(axis), c) << " at " << q;
        }
  }
  ASSERT_EQ(a.stiffness.size(), b.stiffness.size());
  for (size_t k = 0; k < a.stiffness.size(); ++k) {
    EXPECT_EQ(a.stiffness[k].otherAxis, b.stiffness[k].otherAxis);
    EXPECT_NEAR(a.stiffness[k].referenceLoad, b.stiffness[k].referenceLoad, 1e-12);
    EXPECT_LT((a.stiffness[k].values - b.stiffness[k].values).cwiseAbs().maxCoeff(), 1e-15);
  }
  EXPECT_EQ(a.workpieceLoad, b.workpieceLoad);
}

TEST(ErrorsFile, WrittenErrorsReadBackToTheSameModel) {
  // Polynomials, linear terms, reversals, cyclic errors, harmonics, spline tables (tilting
  // table), seed 003's piecewise functions (maho) and stiffness changes (maho at 260 kg).
  for (const std::string name : {"tilting-table", "maho", "double-pivot-head", "multitasking-b-c", "swivel-head-table"}) {
    const auto m = test::bundled(name);
    const ErrorModel errors = loadMachineErrors(*m);
    SCOPED_TRACE(name);
    expectSameErrors(*m, errors, parseErrors(*m, errorsYaml(*m, errors), "written.yaml", ErrorsKey::Required));
  }
  // Terms about a point other than 0: Z's travel from -300 to 700 mm, B's from -105 deg.
  const auto head = test::bundled("double-pivot-head");
  const ErrorModel named = parseErrors(*head, "errors:\n  EZZ.c2: 3 um\n  ECB.h1c: 2 urad\n  EXB.h2s: 1 um\n", "t.yaml", ErrorsKey::Required);
  expectSameErrors(*head, named, parseErrors(*head, errorsYaml(*head, named), "written.yaml", ErrorsKey::Required));
  const auto maho = test::bundled("maho");
  const ErrorModel loaded = loadErrors(*maho, bundledDataDir() + "/stiffness/maho-260kg.yaml");
  ASSERT_FALSE(loaded.stiffness.empty());
  expectSameErrors(*maho, loaded, parseErrors(*maho, errorsYaml(*maho, loaded), "written.yaml", ErrorsKey::Required));
}

TEST(ErrorsFile, NamedTermsMeanWhatIdentifyMeans) {
  const auto m = test::bundled("three-axis-vertical");
  const auto& x = m->axes[static_cast<size_t>(m->axisIndex("X"))];
  // A term the errors do not define: the power over half the travel about its middle, so c1 is
  // the error at the end of travel (as a test plan's EXX.c1).
  const ErrorModel named = parseErrors(*m, "errors:\n  EXX.c1: 3 um\n  EZX.c2: 2 um\n", "t.yaml", ErrorsKey::Required);
  const auto& exx = named.axes[static_cast<size_t>(m->axisIndex("X"))].motion[0];
  EXPECT_NEAR(exx.value(x.travel->max, 0), 3e-3, 1e-15);
  EXPECT_NEAR(exx.value(x.travel->min, 0), -3e-3, 1e-15);
  EXPECT_NEAR(named.axes[static_cast<size_t>(m->axisIndex("X"))].motion[2].value(x.travel->min, 0), 2e-3, 1e-15);
  // The same names find the same parameters in the model a test plan's names define.
  ErrorModel planned = ErrorModel::zero(*m);
  const auto names = defineNamedTerms(*m, planned, {"EXX.c1", "EZX.c2"});
  for (const auto& n : names) EXPECT_NO_THROW(findParameter(*m, named, n)) << n;
  EXPECT_EQ(parameterValue(named, findParameter(*m, named, "EXX.c1")), 3e-3);

  // One form per function: its terms named alone or its function given, not both.
  EXPECT_THROW(parseErrors(*m, "errors:\n  EXX.c1: 3 um\n  EXX: {reversal: 2 um}\n", "t.yaml", ErrorsKey::Required), InputError);
  EXPECT_THROW(parseErrors(*m, "errors:\n  EXX: {reversal: 2 um}\n  EXX.c1: 3 um\n", "t.yaml", ErrorsKey::Required), InputError);
  // A harmonic without its part is two parameters.
  EXPECT_THROW(parseErrors(*m, "errors:\n  EXX.h1: 3 um\n", "t.yaml", ErrorsKey::Required), InputError);
  EXPECT_THROW(parseErrors(*m, "errors:\n  EXX:\n    harmonics: {terms: [{order: 1, amplitude: 1 um, part: sine, phase: 3 deg}]}\n",
                           "t.yaml", ErrorsKey::Required),
               InputError);
  // The sine part named in a file and written as a part: the same function.
  const ErrorModel sine = parseErrors(*m, "errors:\n  EXX.h2s: 1 um\n", "t.yaml", ErrorsKey::Required);
  expectSameErrors(*m, sine, parseErrors(*m, errorsYaml(*m, sine), "written.yaml", ErrorsKey::Required));
  EXPECT_EQ(findParameter(*m, parseErrors(*m, errorsYaml(*m, sine), "w.yaml", ErrorsKey::Required), "EXX.h2s").name, "EXX.h2s");
}

TEST(ErrorsFile, TopLevelKeysOfAnErrorsFile) {
  const auto m = test::bundled("three-axis-vertical");
  EXPECT_NO_THROW(parseErrors(*m, "errors:\n  C0Y: 1 urad\nidentification:\n  by: mtacc\n", "t.yaml", ErrorsKey::Required));
  EXPECT_THROW(parseErrors(*m, "errors:\n  C0Y: 1 urad\nidentifcation: {}\n", "t.yaml", ErrorsKey::Required), InputError);
  EXPECT_THROW(parseErrors(*m, "errors:\n  C0Y: 1 urad\nidentification: [1]\n", "t.yaml", ErrorsKey::Required), InputError);
}

}  // namespace
}  // namespace mtacc
