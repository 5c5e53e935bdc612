// SPDX-License-Identifier: BSD-3-Clause
/// @file level_rule.h
/// Private to buildGeometryImages: how each chart's d_max spends the sample budget (Feng et al.
/// 2010, section 5.2), by curvature-weighted area (LevelRule::Area) or by measured levelError
/// (LevelRule::Error); see tc/gim/geometry_images.h for the rules.
#pragma once

#include "gim/geometry_images_input.h"

#include <cstdint>
#include <vector>

namespace tc::detail::geometry_images
{
/// Whether the error rule stops on options.errorTarget (the Error rule with a target > 0).
inline bool stopsOnTarget(const GeometryImageOptions& o)
{
  return o.levelRule == LevelRule::Error && o.errorTarget > 0.0;
}

/// The sample counts of the level rules (see GeometryImageOptions::sampleBudget).
struct SampleBudgets
{
  int64_t area = 0; ///< the area rule's: sampleBudget, or 0 -> the input's points
  /// what the error rule's grids may hold: 4^kErrorRuleLevelsAbove x area
  int64_t measured = 0;
  int64_t finest = 0; ///< the finest levels' total: sampleBudget, or 0 -> area or measured
};

/// The budgets of `options` for numCharts charts and inputPoints points (each at least what
/// minLevel needs).
/// @throws InputError for a sampleBudget below numCharts samples at minLevel
SampleBudgets sampleBudgets(
  const GeometryImageOptions& options, int32_t numCharts, int64_t inputPoints);

/// The area rule: d_max per chart, the largest alpha with floor(log4(alpha A_c)) clamped to
/// [minLevel, maxLevel] whose total of samples fits the budget. Charts whose thresholds tie
/// (symmetric patches) rise together or not at all.
std::vector<int32_t> areaRuleLevels(
  const std::vector<double>& weightedArea, const GeometryImageOptions& o, int64_t budget);

/// The level each chart's grid is sampled at: the area rule's d_max, raised by
/// kErrorRuleLevelsAbove (up to maxLevel) for the error rule, which measures every level up to
/// it.
std::vector<int32_t> sampledLevels(
  const std::vector<double>& weightedArea, const GeometryImageOptions& o, int64_t budget);

/// The error rule: from minLevel everywhere, the charts whose levelError at their current level
/// is largest rise one level while the rise fits the budget and that error is above
/// `target` (in input units; 0: none); errors within `tolerance` of the largest tie. A chart
/// at its cap (its last measured level) drops out, and so does a group whose rise does not fit.
std::vector<int32_t> allocateByError(const std::vector<std::vector<double>>& levelError,
  const GeometryImageOptions& o, int64_t budget, double tolerance, double target);

/// The charts to measure one level higher, `sampled` raised for them: those whose levelError at
/// their sampled level is above `target` (input units, > 0), below maxLevel, largest error
/// first while the total of sampled grids stays within `measured`.
std::vector<uint8_t> raiseMeasured(const std::vector<AtlasChart>& charts,
  std::vector<int32_t>& sampled, const GeometryImageOptions& o, int64_t measured, double target);

/// d_max of every chart: `sampled` under the area rule, else allocateByError over the charts'
/// levelError with the finest budget, the target errorTarget * diagonal and the tolerance of
/// float samples of `mesh`.
std::vector<int32_t> chartLevels(const std::vector<AtlasChart>& charts,
  const std::vector<int32_t>& sampled, const TriMesh& mesh, double diagonal,
  const GeometryImageOptions& o, const SampleBudgets& budgets);
} // namespace tc::detail::geometry_images
