#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include <memory>
#include <optional>
#include <random>
#include <vector>
#include <string>

#include "mtacc/core/units.hpp"
#include "mtacc/errors/aliases.hpp"
#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"
#include "mtacc/io/machine_yaml.hpp"

namespace mtacc::test {

// The exception of type E that `f` throws, for a test to inspect its message; a test failure
// and nothing when `f` throws none. Any other exception propagates and fails the test. The one
// catch in the tests: each EXPECT_THROW that needs the message goes through here.
template <class E, class F>
std::optional<E> thrown(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e;
  }
  ADD_FAILURE() << "no exception thrown";
  return std::nullopt;
}

// A folder of the running test's own (its name and the process's in the folder's name), removed
// with everything in it when the test ends.
class TestFolder {
 public:
  explicit TestFolder(const std::string& prefix)
      : dir_(std::filesystem::temp_directory_path() /
             (prefix + "-" + std::to_string(::getpid()) + "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    std::filesystem::create_directories(dir_);
  }
  ~TestFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  TestFolder(const TestFolder&) = delete;
  TestFolder& operator=(const TestFolder&) = delete;
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

inline std::shared_ptr<const Machine> bundled(const std::string& name) {
  return std::make_shared<const Machine>(loadMachine(name));
}

// A uniformly random pose within travel (one turn for a continuous rotary axis).
template <class Rng>
std::vector<double> randomPose(const Machine& m, Rng& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> q(static_cast<size_t>(m.commandedCount()));
  for (size_t i = 0; i < q.size(); ++i) {
    const Axis& a = m.axes[i];
    const double lo = a.travel ? a.travel->min : -kPi, hi = a.travel ? a.travel->max : kPi;
    q[i] = lo + (hi - lo) * u(rng);
  }
  return q;
}

// gtest parameter names from machine names ("tilting-table" -> "tilting_table").
struct MachineName {
  template <class Info>
  std::string operator()(const Info& info) const {
    std::string n = info.param;
    for (auto& ch : n) ch = ch == '-' ? '_' : ch;
    return n;
  }
};

inline const char* kFiveAxisMachines[] = {"tilting-table", "swivel-head-table", "double-pivot-head",
                                          "inclined-a-table", "multitasking-b-c", "maho"};

// The error function of a component named in seed 003's notation (xrx, ztz, ...) in `errors`.
inline const ErrorFunction& seed003Component(const Machine& machine, const ErrorModel& errors, const std::string& name) {
  const auto p = findParameter(machine, errors, findAlias(name)->terms[0].isoName + ".k0c0");
  return errors.axes[static_cast<size_t>(p.axis)].motion[static_cast<size_t>(p.component)];
}

}  // namespace mtacc::test
