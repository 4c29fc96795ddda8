// Monte Carlo of the cone-frustum test piece on the tilting-table example: 1000 samples of
// the Table 3.9 limits, each evaluated with the exact procedure of seed 000 §3.9 (720 points,
// FK with errors, LS plane and circle). Target: at least 3000 samples/s on one core. Side by
// side in the same run, the first-order shortcut (n . dP, harmonic removal) on the same
// samples; the two medians must agree within 1 % (the errors are small enough that first
// order holds; seed 000 Table 3.4 entries agree to that, tests/seed000_table3_4_test.cpp).
// There is no outside baseline: no other library computes this test piece.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "mtacc/io/limits_yaml.hpp"
#include "mtacc/io/bundled_data.hpp"
#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/procedures/monte_carlo.hpp"
#include "bench_support.hpp"

namespace {

using namespace mtacc;

struct Setup {
  std::shared_ptr<const Machine> machine = std::make_shared<const Machine>(loadMachine("tilting-table"));
  ErrorLimits limits = loadErrorLimits(*machine, bundledDataDir() + "/limits/seed000-table3.9.yaml");
  ConeSpec spec;
  KinematicModel nominal = compileNominal(machine);
  ConePath path = conePath(spec, 720);
  ConeMotion motion = coneMotion(nominal, spec, path);
};

Setup& setup() {
  static Setup s;
  return s;
}

int samples = 1000;  // 100 for the agreement check

double medianFormError[2] = {0, 0};  // first order, exact (mm)

double run(bool exact) {
  auto& s = setup();
  if (exact) return medianFormError[1] = coneMonteCarlo(s.machine, s.limits, s.spec, s.path, s.motion, samples, 7).statistics.median;
  std::vector<std::string> notes;
  const auto spans = monteCarloSpans(*s.machine, s.limits, s.motion, notes);
  std::mt19937_64 rng(7);
  std::vector<double> v;
  for (int i = 0; i < samples; ++i)
    v.push_back(coneFormErrorFirstOrder(compile(s.machine, sampleErrors(*s.machine, s.limits, spans, rng)), s.nominal, s.path,
                                        s.motion).formError);
  return medianFormError[0] = boxStatistics(v).median;
}

void MonteCarloExact(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(run(true));
  state.SetItemsProcessed(state.iterations() * samples);
}
void MonteCarloFirstOrder(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(run(false));
  state.SetItemsProcessed(state.iterations() * samples);
}
BENCHMARK(MonteCarloExact)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)->UseRealTime();
BENCHMARK(MonteCarloFirstOrder)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)->UseRealTime();

class Collect : public benchmark::ConsoleReporter {
 public:
  Collect() : ConsoleReporter(OO_Tabular) {}
  std::map<std::string, std::vector<double>> seconds;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& r : runs)
      if (r.run_type == Run::RT_Iteration) seconds[r.run_name.function_name].push_back(r.GetAdjustedRealTime() / 1e3);
    ConsoleReporter::ReportRuns(runs);
  }
  double median(const std::string& n) {
    auto v = seconds[n];
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  }
};

}  // namespace

int main(int argc, char** argv) {
  const bool check = bench::agreementCheckOnly(argc, argv);
  setup();
  if (check) {
    samples = 100;
    run(true);
    run(false);
  } else {
    benchmark::Initialize(&argc, argv);
    Collect reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    const double exact = reporter.median("MonteCarloExact"), first = reporter.median("MonteCarloFirstOrder");
    fmt::print("\ncone Monte Carlo, {} samples x 720 points, one core (medians of 3 runs):\n", samples);
    fmt::print("  exact evaluation       {:.3f} s = {:.0f} samples/s (target >= 3000 samples/s)\n", exact, samples / exact);
    fmt::print("  first-order shortcut   {:.3f} s = {:.0f} samples/s; exact / first-order time ratio {:.2f}\n", first,
               samples / first, exact / first);
    benchmark::Shutdown();
  }
  const double difference = std::abs(medianFormError[1] - medianFormError[0]) / medianFormError[1];
  fmt::print("  median form error: exact {:.3f} um, first order {:.3f} um (difference {:.2f} %, limit 1 %)\n",
             medianFormError[1] * 1e3, medianFormError[0] * 1e3, difference * 100);
  return difference <= 0.01 ? 0 : 1;
}
