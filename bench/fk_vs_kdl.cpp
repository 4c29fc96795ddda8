// Batch forward kinematics of the tilting-table example, side by side with orocos KDL's
// recursive chain FK of the same nominal chain (workpiece -> C -> B -> X -> Y -> Z -> tool).
// KDL computes the full tool frame, so the fair comparison is mtacc computing the same output
// (toolInWorkpiece: rotation and TCP):
//   nominal, (a) with location errors only, (b) with all six component errors of every axis
//   as cubic-spline tables,
// on one core each. Beside them, labelled as a different output, mtacc's batch of tool points
// and directions (toolPoints, what the simulations use), on one core and (b) on two threads.
// Prints poses/s per core and the ratios; exits non-zero when the nominal frames disagree.
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
#include "bench_support.hpp"

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

void MtaccFrames(benchmark::State& state, const KinematicModel& model) {
  auto& f = fixture();
  for (auto _ : state) {
    for (long i = 0; i < kPoses; ++i) {
      Pose frame = toolInWorkpiece(model, f.q.row(i).data());
      benchmark::DoNotOptimize(frame);
    }
  }
  state.SetItemsProcessed(state.iterations() * kPoses);
}

void FrameNominal(benchmark::State& s) { MtaccFrames(s, fixture().nominal); }
void FrameLocationErrors(benchmark::State& s) { MtaccFrames(s, fixture().locationOnly); }
void FrameSplineErrors(benchmark::State& s) { MtaccFrames(s, fixture().splines); }
void PointNominal(benchmark::State& s) { Mtacc(s, fixture().nominal, 1); }
void PointLocationErrors(benchmark::State& s) { Mtacc(s, fixture().locationOnly, 1); }
void PointSplineErrors(benchmark::State& s) { Mtacc(s, fixture().splines, 1); }
void PointSplineErrorsTwoThreads(benchmark::State& s) { Mtacc(s, fixture().splines, 2); }

BENCHMARK(KdlNominal)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(FrameNominal)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(FrameLocationErrors)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(FrameSplineErrors)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(PointNominal)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(PointLocationErrors)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(PointSplineErrors)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(PointSplineErrorsTwoThreads)->Unit(benchmark::kMillisecond)->UseRealTime();

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
  const bool check = bench::agreementCheckOnly(argc, argv);
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
  double worst = 0, worstRotation = 0;
  for (long i = 0; i < 1000; ++i) {
    f.toKdl(i, j);
    solver.JntToCart(j, frame);
    const Pose ours = toolInWorkpiece(f.nominal, f.q.row(i).data());
    const auto tp = toolPoint(f.nominal, f.q.row(i).data());
    worst = std::max({worst, (ours.translation() - Vec3(frame.p.x(), frame.p.y(), frame.p.z())).norm(),
                      (tp.position - ours.translation()).norm()});
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) worstRotation = std::max(worstRotation, std::abs(ours.linear()(r, c) - frame.M(r, c)));
  }
  fmt::print("nominal mtacc vs KDL over 1000 poses: largest TCP difference {:.2e} mm, rotation entry {:.2e}\n", worst,
             worstRotation);
  if (worst > 1e-9 || worstRotation > 1e-12) {
    fmt::print(stderr, "bench_fk_vs_kdl: the frames disagree (limits 1e-9 mm, 1e-12)\n");
    return 1;
  }
  if (check) return 0;

  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const double kdl = reporter.median("KdlNominal");
  auto rate = [&](const char* name) { return reporter.median(name); };
  fmt::print("\nmedians of the repetitions, poses/s at 1 thread\nKDL full frame, nominal: {:.3g}\n", kdl);
  fmt::print("mtacc full frame (same output as KDL): nominal {:.3g} ({:.2f}x KDL), (a) location errors {:.3g} ({:.2f}x, "
             "target >= 3), (b) spline errors {:.3g} ({:.2f}x)\n",
             rate("FrameNominal"), rate("FrameNominal") / kdl, rate("FrameLocationErrors"), rate("FrameLocationErrors") / kdl,
             rate("FrameSplineErrors"), rate("FrameSplineErrors") / kdl);
  fmt::print("mtacc tool point and direction only (less output than KDL, not a like-for-like ratio): nominal {:.3g}, "
             "(a) {:.3g}, (b) {:.3g}; (b) on 2 threads {:.3g} ({:.2f}x its 1-thread rate)\n",
             rate("PointNominal"), rate("PointLocationErrors"), rate("PointSplineErrors"), rate("PointSplineErrorsTwoThreads"),
             rate("PointSplineErrorsTwoThreads") / rate("PointSplineErrors"));
  benchmark::Shutdown();
  return 0;
}
