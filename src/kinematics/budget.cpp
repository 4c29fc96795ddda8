#include "mtacc/kinematics/budget.hpp"

#include <algorithm>
#include <cmath>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
double sensitivityCoefficient(std::shared_ptr<const Machine> machine, const ErrorModel& shape, const ErrorStep& step,
                              const SurfacePoint& at) {
  const auto nominal = compileNominal(machine);
  const auto actual = compile(machine, singleError(*machine, shape, step.parameter, step.epsilon));
  const Vec3 e = toolPosition(actual, at.q) - toolPosition(nominal, at.q);
  return at.normal.normalized().dot(e) / step.epsilon;
}

std::vector<BudgetItem> budgetItemsAtMagnitude(const Machine& machine, double length, double angle) {
  std::vector<BudgetItem> items;
  const ErrorModel zero = ErrorModel::zero(machine);
  for (const auto& p : parameterCatalogue(machine, zero)) {
    const double m = p.dimension == Dimension::Length ? length : angle;
    items.push_back({p.name, p.dimension, m, singleError(machine, zero, p, m)});
  }
  for (int a = 0; a < static_cast<int>(machine.axes.size()); ++a) {
    for (int c = 0; c < 6; ++c) {
      ErrorModel e = ErrorModel::zero(machine);
      const double m = c < 3 ? length : angle;
      e.axes[static_cast<size_t>(a)].motion[static_cast<size_t>(c)].add(PolynomialTerm{0.0, 1.0, {m}});
      items.push_back({motionErrorName(machine, a, c), c < 3 ? Dimension::Length : Dimension::Angle, m, std::move(e)});
    }
  }
  return items;
}

namespace {

// The largest |value| of an error function over the axis's travel (one turn for a continuous
// axis), both directions of motion: the magnitude a budget line states for it.
double largestValue(const ErrorFunction& f, const Axis& axis) {
  const AxisSpan span = harmonicSpan(axis);
  constexpr int kSamples = 400;
  double largest = 0;
  for (int i = 0; i <= kSamples; ++i)
    for (int direction : {-1, 1})
      largest = std::max(largest, std::abs(f.value(span.min + span.range * i / kSamples, direction)));
  return largest;
}

}  // namespace

std::vector<BudgetItem> budgetItemsOfModel(const Machine& machine, const ErrorModel& errors) {
  std::vector<BudgetItem> items;
  std::vector<std::pair<int, int>> functionsDone;
  for (const auto& p : nonZeroParameters(machine, errors)) {
    if (p.kind != ParameterKind::Motion) {
      const double v = parameterValue(errors, p);
      items.push_back({p.name, p.dimension, v, singleError(machine, errors, p, v)});
      continue;
    }
    // A component error is one line however many terms or coefficients describe it: the
    // coefficients of a piecewise or polynomial function alone are not errors of the machine.
    const std::pair<int, int> function{p.axis, p.component};
    if (std::find(functionsDone.begin(), functionsDone.end(), function) != functionsDone.end()) continue;
    functionsDone.push_back(function);
    const auto& f = errors.axes[static_cast<size_t>(p.axis)].motion[static_cast<size_t>(p.component)];
    ErrorModel alone = ErrorModel::zero(machine);
    alone.axes[static_cast<size_t>(p.axis)].motion[static_cast<size_t>(p.component)] = f;
    items.push_back({motionErrorName(machine, p.axis, p.component), p.component < 3 ? Dimension::Length : Dimension::Angle,
                     largestValue(f, machine.axes[static_cast<size_t>(p.axis)]), std::move(alone)});
  }
  return items;
}

JointMatrix workingVolumeGrid(const Machine& machine, int samples) {
  const int n = machine.commandedCount();
  long total = 1;
  for (int i = 0; i < n; ++i) total *= samples;
  JointMatrix q(total, n);
  for (long row = 0; row < total; ++row) {
    long rest = row;
    for (int i = 0; i < n; ++i) {
      const Axis& a = machine.axes[static_cast<size_t>(i)];
      const long k = rest % samples;
      rest /= samples;
      if (a.travel) {
        q(row, i) = samples == 1 ? 0.5 * (a.travel->min + a.travel->max)
                                 : a.travel->min + (a.travel->max - a.travel->min) * static_cast<double>(k) / (samples - 1);
      } else {
        q(row, i) = -kPi + 2.0 * kPi * static_cast<double>(k) / samples;
      }
    }
  }
  return q;
}

std::vector<BudgetEntry> errorBudget(std::shared_ptr<const Machine> machine, const std::vector<BudgetItem>& items,
                                     const JointMatrix& poses, int threads,
                                     const std::function<void(size_t, size_t)>& progress) {
  if (poses.rows() == 0) throw InvalidInput("error budget needs at least one pose");
  const auto nominal = compileNominal(machine);
  std::vector<Pose> nominalPoses(static_cast<size_t>(poses.rows()));
  for (long i = 0; i < poses.rows(); ++i) nominalPoses[static_cast<size_t>(i)] = toolInWorkpiece(nominal, poses.row(i).data());
  std::vector<BudgetEntry> out;
  for (size_t k = 0; k < items.size(); ++k) {
    const auto model = compile(machine, items[k].errors);
    std::vector<double> pos(static_cast<size_t>(poses.rows())), rot(pos.size());
    parallelFor(poses.rows(), threads, [&](long begin, long end) {
      for (long i = begin; i < end; ++i) {
        const Vec6 e = poseError(toolInWorkpiece(model, poses.row(i).data()), nominalPoses[static_cast<size_t>(i)]);
        pos[static_cast<size_t>(i)] = e.head<3>().norm();
        rot[static_cast<size_t>(i)] = e.tail<3>().norm();
      }
    });
    const auto worst = std::max_element(pos.begin(), pos.end());
    BudgetEntry entry{items[k].name, items[k].dimension, items[k].magnitude, *worst,
                      *std::max_element(rot.begin(), rot.end()), {}};
    const long w = worst - pos.begin();
    entry.worstPose.assign(poses.row(w).data(), poses.row(w).data() + poses.cols());
    out.push_back(std::move(entry));
    if (progress) progress(k + 1, items.size());
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const BudgetEntry& a, const BudgetEntry& b) { return a.maxPositionError > b.maxPositionError; });
  return out;
}

}  // namespace mtacc
