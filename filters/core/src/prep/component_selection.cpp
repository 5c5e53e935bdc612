// SPDX-License-Identifier: BSD-3-Clause
#include "prep/component_selection.h"

#include "prep/report_text.h"

#include "tc/common/errors.h"

#include <string>
#include <utility>

namespace tc
{
namespace detail
{
namespace
{
/// The error when the options dropped every component: how many each rule dropped, and which
/// option to relax.
InputError nothingLeftError(const PreparationOptions& options, const PreparationReport& report)
{
  std::string why;
  if (report.droppedNonOrientable > 0)
  {
    why = "DropNonOrientable dropped " +
      counted(report.droppedNonOrientable, kNonOrientableComponent) + " (" +
      counted(report.droppedNonOrientableTriangles, kTriangle) + ")";
  }
  if (report.droppedSmallComponents > 0)
  {
    why += (why.empty() ? "" : " and ") + std::string("MinComponentTriangles = ") +
      std::to_string(options.minComponentTriangles) + " dropped " +
      counted(report.droppedSmallComponents, kComponent) + " (" +
      counted(report.droppedSmallTriangles, kTriangle) + ")";
  }
  return InputError("mesh preparation: no component is left: " + why +
    "; lower MinComponentTriangles (--min-component-triangles) or leave DropNonOrientable "
    "(--drop-non-orientable) off");
}
} // namespace

std::vector<int64_t> componentTriangles(
  const std::vector<int32_t>& componentId, int64_t numComponents)
{
  std::vector<int64_t> triangles(static_cast<size_t>(numComponents), 0);
  for (const int32_t k : componentId)
  {
    ++triangles[k];
  }
  return triangles;
}

int32_t largestComponent(const std::vector<int64_t>& triangles)
{
  int32_t largest = -1;
  for (int32_t k = 0; k < static_cast<int32_t>(triangles.size()); ++k)
  {
    largest = (largest < 0 || triangles[k] > triangles[largest]) ? k : largest;
  }
  return largest;
}

void describeComponents(
  const std::vector<int32_t>& componentId, const ComponentKinds& kinds, PreparationReport& report)
{
  const std::vector<int64_t> triangles =
    componentTriangles(componentId, static_cast<int64_t>(kinds.closed.size()));
  report.nonOrientableTriangles = 0;
  for (size_t k = 0; k < triangles.size(); ++k)
  {
    report.nonOrientableTriangles += kinds.nonOrientable[k] ? triangles[k] : 0;
  }
  const int32_t largest = largestComponent(triangles);
  report.largestComponentTriangles = largest < 0 ? 0 : triangles[largest];
  report.largestComponentClosed =
    largest >= 0 && kinds.closed[largest] && !kinds.nonOrientable[largest];
}

std::vector<uint8_t> selectComponents(const std::vector<int32_t>& componentId,
  const ComponentKinds& kinds, const PreparationOptions& options, PreparationReport& report)
{
  const std::vector<int64_t> triangles =
    componentTriangles(componentId, static_cast<int64_t>(kinds.closed.size()));
  std::vector<uint8_t> keep(triangles.size(), 1);
  for (size_t k = 0; k < triangles.size(); ++k)
  {
    if (options.dropNonOrientable && kinds.nonOrientable[k])
    {
      keep[k] = 0;
      ++report.droppedNonOrientable;
      report.droppedNonOrientableTriangles += triangles[k];
    }
    else if (triangles[k] < options.minComponentTriangles)
    {
      keep[k] = 0;
      ++report.droppedSmallComponents;
      report.droppedSmallTriangles += triangles[k];
    }
  }
  // The largest of the components the first two rules left.
  std::vector<int64_t> left(triangles.size(), -1);
  for (size_t k = 0; k < triangles.size(); ++k)
  {
    left[k] = keep[k] ? triangles[k] : -1;
  }
  const int32_t largest = largestComponent(left);
  if (largest < 0 || left[largest] < 0)
  {
    throw nothingLeftError(options, report);
  }
  for (size_t k = 0; options.keepLargestComponent && k < triangles.size(); ++k)
  {
    if (keep[k] && static_cast<int32_t>(k) != largest)
    {
      keep[k] = 0;
      ++report.droppedMinorComponents;
      report.droppedMinorTriangles += triangles[k];
    }
  }
  return keep;
}

ComponentRemoval keepComponents(
  TriMesh& mesh, const std::vector<int32_t>& componentId, const std::vector<uint8_t>& keep)
{
  ComponentRemoval out;
  const int64_t nf = mesh.numTriangles();
  std::vector<int32_t> newId(static_cast<size_t>(mesh.numPoints()), -1);
  for (int64_t f = 0; f < nf; ++f)
  {
    if (keep[componentId[f]])
    {
      out.keptTriangles.push_back(static_cast<int32_t>(f));
      for (int c = 0; c < 3; ++c)
      {
        newId[mesh.triangles[3 * f + c]] = 0;
      }
    }
  }
  TriMesh kept;
  for (int32_t v = 0; v < static_cast<int32_t>(newId.size()); ++v)
  {
    if (newId[v] == 0)
    {
      newId[v] = static_cast<int32_t>(out.keptPoints.size());
      out.keptPoints.push_back(v);
      kept.points.insert(kept.points.end(), &mesh.points[3 * static_cast<size_t>(v)],
        &mesh.points[3 * static_cast<size_t>(v)] + 3);
    }
  }
  for (const int32_t f : out.keptTriangles)
  {
    for (int c = 0; c < 3; ++c)
    {
      kept.triangles.push_back(newId[mesh.triangles[3 * static_cast<size_t>(f) + c]]);
    }
  }
  out.droppedPoints = mesh.numPoints() - kept.numPoints();
  mesh = std::move(kept);
  return out;
}
} // namespace detail
} // namespace tc
