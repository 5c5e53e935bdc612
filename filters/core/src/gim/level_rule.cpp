// SPDX-License-Identifier: BSD-3-Clause
#include "gim/level_rule.h"

#include "tc/common/errors.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace tc::detail::geometry_images
{
SampleBudgets sampleBudgets(
  const GeometryImageOptions& options, int32_t numCharts, int64_t inputPoints)
{
  const int64_t minimum = numCharts * gridVertexCount(options.minLevel);
  if (options.sampleBudget > 0 && options.sampleBudget < minimum)
  {
    throw InputError(kWhere + "sampleBudget " + num(options.sampleBudget) + " is below " +
      num(minimum) + ", what " + num(numCharts) + " charts need at minLevel " +
      num(options.minLevel) + "; raise sampleBudget or lower minLevel");
  }
  SampleBudgets b;
  b.area = options.sampleBudget > 0 ? options.sampleBudget : std::max(minimum, inputPoints);
  b.measured = b.area << (2 * kErrorRuleLevelsAbove);
  b.finest = options.sampleBudget > 0 ? options.sampleBudget
    : stopsOnTarget(options)          ? b.measured
                                      : b.area;
  return b;
}

std::vector<int32_t> areaRuleLevels(
  const std::vector<double>& weightedArea, const GeometryImageOptions& o, int64_t budget)
{
  const int32_t n = static_cast<int32_t>(weightedArea.size());
  std::vector<int32_t> level(n, o.minLevel);
  int64_t total = n * gridVertexCount(o.minLevel);
  struct Event
  {
    double logAlpha;
    int32_t chart;
  };
  std::vector<Event> events;
  for (int32_t c = 0; c < n; ++c)
  {
    if (weightedArea[c] > 0.0 && std::isfinite(weightedArea[c]))
    {
      for (int32_t d = o.minLevel + 1; d <= o.maxLevel; ++d)
      {
        events.push_back({ d * std::log(4.0) - std::log(weightedArea[c]), c });
      }
    }
  }
  std::sort(events.begin(), events.end(),
    [](const Event& a, const Event& b)
    { return a.logAlpha < b.logAlpha || (a.logAlpha == b.logAlpha && a.chart < b.chart); });
  for (size_t i = 0; i < events.size();)
  {
    const double tol = 1e-9 * std::max(1.0, std::abs(events[i].logAlpha));
    size_t j = i;
    int64_t delta = 0;
    while (j < events.size() && events[j].logAlpha <= events[i].logAlpha + tol)
    {
      const int32_t d = level[events[j].chart];
      delta += gridVertexCount(d + 1) - gridVertexCount(d);
      ++j;
    }
    if (total + delta > budget)
    {
      break;
    }
    for (size_t k = i; k < j; ++k)
    {
      ++level[events[k].chart];
    }
    total += delta;
    i = j;
  }
  return level;
}

std::vector<int32_t> sampledLevels(
  const std::vector<double>& weightedArea, const GeometryImageOptions& o, int64_t budget)
{
  std::vector<int32_t> sampled = areaRuleLevels(weightedArea, o, budget);
  // With a target the measuring starts at the area rule's levels and rises where the error
  // is (raiseMeasured), so the measured budget is not spent on charts already below it.
  if (o.levelRule == LevelRule::Error && !stopsOnTarget(o))
  {
    for (int32_t& d : sampled)
    {
      d = std::min(d + kErrorRuleLevelsAbove, o.maxLevel);
    }
  }
  return sampled;
}

// Errors within the tolerance tie and rise together or not at all (as areaRuleLevels does for
// tied areas): congruent charts keep one d_max, and flat charts, whose errors are only float
// rounding, share the budget evenly instead of in the order of their noise. A group whose rise
// does not fit drops out and the next largest errors are tried, so what is left of the budget
// still goes to the worst charts that fit. With errors that fall with the level, every chart
// raised while the largest error is above the area rule's was below its area level, so its rise
// fitted: the largest error ends no higher than with the area rule (a feasible allocation below
// the caps).
std::vector<int32_t> allocateByError(const std::vector<std::vector<double>>& levelError,
  const GeometryImageOptions& o, int64_t budget, double tolerance, double target)
{
  const int32_t n = static_cast<int32_t>(levelError.size());
  std::vector<int32_t> level(n, o.minLevel);
  int64_t total = n * gridVertexCount(o.minLevel);
  using Entry = std::pair<double, int32_t>;
  // Largest error on top; the lower id first on a tie, so the group is gathered in one order.
  auto below = [](const Entry& a, const Entry& b)
  { return a.first < b.first || (a.first == b.first && a.second > b.second); };
  std::vector<Entry> heap;
  heap.reserve(n);
  for (int32_t c = 0; c < n; ++c)
  {
    heap.emplace_back(levelError[c][o.minLevel], c);
  }
  std::make_heap(heap.begin(), heap.end(), below);
  std::vector<int32_t> group;
  while (!heap.empty())
  {
    const double largest = heap.front().first;
    if (target > 0.0 && largest <= target)
    {
      break;
    }
    group.clear();
    int64_t cost = 0;
    while (!heap.empty() && heap.front().first >= largest - tolerance)
    {
      std::pop_heap(heap.begin(), heap.end(), below);
      const int32_t c = heap.back().second;
      heap.pop_back();
      const int32_t d = level[c];
      if (d + 1 < static_cast<int32_t>(levelError[c].size()))
      {
        group.push_back(c);
        cost += gridVertexCount(d + 1) - gridVertexCount(d);
      }
    }
    if (total + cost > budget)
    {
      continue;
    }
    total += cost;
    for (int32_t c : group)
    {
      ++level[c];
      heap.emplace_back(levelError[c][level[c]], c);
      std::push_heap(heap.begin(), heap.end(), below);
    }
  }
  return level;
}

std::vector<uint8_t> raiseMeasured(const std::vector<AtlasChart>& charts,
  std::vector<int32_t>& sampled, const GeometryImageOptions& o, int64_t measured, double target)
{
  const int32_t n = static_cast<int32_t>(charts.size());
  int64_t total = 0;
  std::vector<std::pair<double, int32_t>> above;
  for (int32_t c = 0; c < n; ++c)
  {
    total += gridVertexCount(sampled[c]);
    const double e = charts[c].levelError[static_cast<size_t>(sampled[c])];
    if (e > target && sampled[c] < o.maxLevel)
    {
      above.emplace_back(-e, c);
    }
  }
  std::sort(above.begin(), above.end());
  std::vector<uint8_t> raised(n, 0);
  for (const auto& [minusError, c] : above)
  {
    const int64_t cost = gridVertexCount(sampled[c] + 1) - gridVertexCount(sampled[c]);
    if (total + cost <= measured)
    {
      total += cost;
      ++sampled[c];
      raised[c] = 1;
    }
  }
  return raised;
}

std::vector<int32_t> chartLevels(const std::vector<AtlasChart>& charts,
  const std::vector<int32_t>& sampled, const TriMesh& mesh, double diagonal,
  const GeometryImageOptions& o, const SampleBudgets& budgets)
{
  if (o.levelRule != LevelRule::Error)
  {
    return sampled;
  }
  std::vector<std::vector<double>> errors(charts.size());
  for (size_t c = 0; c < charts.size(); ++c)
  {
    errors[c] = charts[c].levelError;
  }
  // Float samples round each coordinate by up to 6e-8 of its magnitude: errors closer than
  // 1e-6 of the model's size (and of its distance from the origin) are not told apart.
  double extent = 0.0;
  for (double x : mesh.points)
  {
    extent = std::max(extent, std::abs(x));
  }
  return allocateByError(
    errors, o, budgets.finest, 1e-6 * (diagonal + extent), o.errorTarget * diagonal);
}
} // namespace tc::detail::geometry_images
