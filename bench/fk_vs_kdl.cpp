// Batch forward kinematics of the tilting-table example, side by side with orocos KDL's
// recursive chain FK of the same nominal chain (workpiece -> C -> B -> X -> Y -> Z -> tool):
//   (a) mtacc with location errors only,
//   (b) mtacc with all six component errors of every axis as cubic-spline tables,
// on one core each, then (b) on two threads. Prints poses/s per core and the ratios.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <algorithm>
#include <map>
#include <random>

#include "mtacc/io/errors_yaml.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/io/machine_yaml.hpp"

namespace {

using namespace mtacc;

constexpr long kPoses = 20000;

struct Fixture {
  std::shared_ptr<const Machine> machine = std::make_shared<const Machine>(loadMachine("tilting-table"));
  JointMatrix q{kPoses, 5};
  KinematicModel nominal = compileNominal(machine);
  KinematicModel locationOnly;
  KinematicModel splines;
  KDL::Chain chain;

  Fixture() {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    for (long i = 0; i < kPoses; ++i)
      for (int k = 0; k < 5; ++k) {
        const Axis& a = machine->axes[static_cast<size_t>(k)];
        const double lo = a.travel ? a.travel->min : -kPi, hi = a.travel ? a.travel->max : kPi;
        q(i, k) = lo + (hi - lo) * u(rng);
      }
    ErrorModel location = ErrorModel::zero(*machine);
    for (const auto& p : parameterCatalogue(*machine, location))
      setParameterValue(location, p, p.dimension == Dimension::Length ? 5e-3 * (u(rng) - 0.5) : 30e-6 * (u(rng) - 0.5));
    locationOnly = compile(machine, location);

    ErrorModel all = location;
    for (int a = 0; a < 5; ++a) {
      const Axis& axis = machine->axes[static_cast<size_t>(a)];
      const double lo = axis.travel ? axis.travel->min : 0.0, hi = axis.travel ? axis.travel->max : 2 * kPi;
      for (int c = 0; c < 6; ++c) {
        std::vector<double> pos, val;
        for (int k = 0; k <= 20; ++k) {
          pos.push_back(lo + (hi - lo) * k / 20.0);
          val.push_back((c < 3 ? 5e-3 : 20e-6) * (u(rng) - 0.5));
        }
        all.axes[static_cast<size_t>(a)].motion[static_cast<size_t>(c)].add(TableTerm(pos, val, Interpolation::CubicSpline));
      }
    }
    splines = compile(machine, all);

    chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::RotZ)));
    chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::RotY)));
    chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::TransX)));
    chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::TransY)));
    chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::TransZ)));
  }
  // KDL joint order C, B, X, Y, Z; mtacc order X, Y, Z, B, C.
  void toKdl(long i, KDL::JntArray& j) const {
    j(0) = q(i, 4);
    j(1) = q(i, 3);
    j(2) = q(i, 0);
    j(3) = q(i, 1);
    j(4) = q(i, 2);
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void KdlNominal(benchmark::State& state) {
  auto& f = fixture();
  KDL::ChainFkSolverPos_recursive solver(f.chain);
  KDL::JntArray j(5);
  KDL::Frame frame;
  for (auto _ : state) {
    for (long i = 0; i < kPoses; ++i) {
      f.toKdl(i, j);
      solver.JntToCart(j, frame);
      benchmark::DoNotOptimize(frame);
    }
  }
  state.SetItemsProcessed(state.iterations() * kPoses);
}

void Mtacc(benchmark::State& state, const KinematicModel& model, int threads) {
  auto& f = fixture();
  ToolPointBatch out;
  for (auto _ : state) {
    toolPoints(model, {f.q, {}}, out, threads);
    benchmark::DoNotOptimize(out.positions.data());
  }
  state.SetItemsProcessed(state.iterations() * kPoses);
}

void MtaccNominal(benchmark::State& s) { Mtacc(s, fixture().nominal, 1); }
void MtaccLocationErrors(benchmark::State& s) { Mtacc(s, fixture().locationOnly, 1); }
void MtaccSplineErrors(benchmark::State& s) { Mtacc(s, fixture().splines, 1); }
void MtaccSplineErrorsTwoThreads(benchmark::State& s) { Mtacc(s, fixture().splines, 2); }

BENCHMARK(KdlNominal)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(MtaccNominal)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(MtaccLocationErrors)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(MtaccSplineErrors)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(MtaccSplineErrorsTwoThreads)->Unit(benchmark::kMillisecond)->UseRealTime();

// Collects the rate of every repetition; the ratios use the median of each benchmark.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  RatioReporter() : ConsoleReporter(OO_Tabular) {}
  std::map<std::string, std::vector<double>> rates;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& r : runs)
      if (r.run_type == Run::RT_Iteration) rates[r.run_name.function_name].push_back(r.counters.at("items_per_second"));
    ConsoleReporter::ReportRuns(runs);
  }
  double median(const std::string& name) {
    auto v = rates[name];
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  }
};

}  // namespace

int main(int argc, char** argv) {
  // Eleven interleaved repetitions by default: the machines are shared and noisy, so KDL and
  // mtacc take turns and the ratios use medians.
  std::vector<char*> args(argv, argv + argc);
  std::string reps = "--benchmark_repetitions=11", interleave = "--benchmark_enable_random_interleaving=true";
  auto given = [&](const char* flag) {
    return std::any_of(args.begin(), args.end(), [&](const char* a) { return std::string(a).rfind(flag, 0) == 0; });
  };
  if (!given("--benchmark_repetitions")) args.push_back(reps.data());
  if (!given("--benchmark_enable_random_interleaving")) args.push_back(interleave.data());
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  // Same chain, same poses: the nominal mtacc and KDL results must agree before timing.
  auto& f = fixture();
  KDL::ChainFkSolverPos_recursive solver(f.chain);
  KDL::JntArray j(5);
  KDL::Frame frame;
  double worst = 0;
  for (long i = 0; i < 1000; ++i) {
    f.toKdl(i, j);
    solver.JntToCart(j, frame);
    const auto tp = toolPoint(f.nominal, f.q.row(i).data());
    worst = std::max(worst, (tp.position - Vec3(frame.p.x(), frame.p.y(), frame.p.z())).norm());
  }
  fmt::print("nominal mtacc vs KDL, largest TCP difference over 1000 poses: {:.2e} mm\n", worst);
  if (worst > 1e-9) return 1;

  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const double kdl = reporter.median("KdlNominal"), nominal = reporter.median("MtaccNominal"),
               loc = reporter.median("MtaccLocationErrors"), spl = reporter.median("MtaccSplineErrors"),
               spl2 = reporter.median("MtaccSplineErrorsTwoThreads");
  fmt::print("\nmedians of the repetitions\nposes/s per core: KDL nominal {:.3g}; mtacc nominal {:.3g}; (a) location errors {:.3g}; (b) spline errors {:.3g}\n",
             kdl, nominal, loc, spl);
  fmt::print("ratio to KDL nominal: mtacc nominal {:.2f}x, (a) location errors {:.2f}x (target >= 3), "
             "(b) all component errors as splines {:.2f}x (target >= 1)\n",
             nominal / kdl, loc / kdl, spl / kdl);
  fmt::print("(b) on 2 threads: {:.3g} poses/s, {:.2f}x the single-thread rate\n", spl2, spl2 / spl);
  benchmark::Shutdown();
  return 0;
}
