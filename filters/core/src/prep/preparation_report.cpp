// SPDX-License-Identifier: BSD-3-Clause
// What tcMeshPreparation says: the report's text, the repair hints, the repair errors.
#include "prep/report_text.h"

#include <utility>
#include <vector>

namespace tc
{
namespace detail
{
std::string counted(int64_t n, const Noun& noun)
{
  return std::to_string(n) + " " + (n == 1 ? noun.one : noun.many);
}

InputError notManifoldError(const PreparationReport& report, const PreparationOptions& options,
  const std::string& repair, const char* option)
{
  std::string why;
  if (!options.splitNonManifold && report.nonManifoldEdges + report.nonManifoldVertices > 0)
  {
    why = counted(report.nonManifoldEdges, kNonManifoldEdge) + " and " +
      counted(report.nonManifoldVertices, kNonManifoldVertex) +
      "; split them first (SplitNonManifold, --split-non-manifold)";
  }
  else
  {
    why = counted(report.nonOrientableComponents, kNonOrientableComponent) +
      " (Moebius-like), which no patch closes consistently; drop " +
      (report.nonOrientableComponents == 1 ? "it" : "them") +
      " (DropNonOrientable, --drop-non-orientable), repair the mesh in a mesh editor, or "
      "leave " +
      option + " off";
  }
  return InputError(
    "mesh preparation: cannot " + repair + ": the mesh is not an oriented manifold: " + why);
}
} // namespace detail

namespace
{
using detail::counted;

/// The unsplit non-manifold edges and vertices, and the option that splits them.
std::string nonManifoldRepair(const PreparationReport& report)
{
  std::string found;
  if (report.nonManifoldEdges > 0)
  {
    found = counted(report.nonManifoldEdges, detail::kNonManifoldEdge);
  }
  if (report.nonManifoldVertices > 0)
  {
    found += (found.empty() ? "" : " and ") +
      counted(report.nonManifoldVertices, detail::kNonManifoldVertex);
  }
  return found + " (split them: SplitNonManifold, trichart build --split-non-manifold)";
}

/// The boundary edges, and the option that closes them (or why it left them open).
std::string boundaryRepair(const PreparationReport& report, const PreparationOptions& options)
{
  const std::string edges = counted(report.boundaryEdges, detail::kBoundaryEdge);
  if (!options.fillHoles)
  {
    return edges + " (close the holes: FillHoles, trichart build --fill-holes)";
  }
  return counted(report.openHoles, detail::kHole) + " left open, " + edges +
    " in all (FillHoles closes holes of up to MaxHoleEdges = " +
    std::to_string(options.maxHoleEdges) +
    " edges with a manifold patch: raise it, 0 for any size, trichart build --max-hole-edges)";
}
/// The non-orientable components, their share of the triangles, and the option that drops them
/// (unless they are most of the mesh, which dropping would not repair but remove).
std::string nonOrientableRepair(const PreparationReport& report)
{
  const int64_t n = report.nonOrientableComponents;
  const std::string found =
    counted(n,
      { "non-orientable (Moebius-like) component", "non-orientable (Moebius-like) components" }) +
    " (" + std::to_string(report.nonOrientableTriangles) + " of the " +
    std::to_string(report.outputTriangles) + " triangles), which no orientation fixes ";
  if (2 * report.nonOrientableTriangles > report.outputTriangles)
  {
    return found +
      "(most of the mesh, which DropNonOrientable would drop: repair the mesh in a "
      "mesh editor)";
  }
  return found + "(drop " + (n == 1 ? "it" : "them") +
    ": DropNonOrientable, trichart build --drop-non-orientable; or repair the mesh in a mesh "
    "editor)";
}

/// When the largest component is closed and oriented and only other components hold the
/// defects (but for non-manifold vertices, which nonManifoldRepair names): keeping it alone
/// repairs the mesh, often better than filling the holes of a scan's debris.
std::string largestComponentRepair(
  const PreparationReport& report, const PreparationOptions& options)
{
  if (options.keepLargestComponent || report.components < 2 || !report.largestComponentClosed)
  {
    return {};
  }
  return "or keep only the largest component, which is closed and oriented (" +
    std::to_string(report.largestComponentTriangles) + " of the " +
    std::to_string(report.outputTriangles) +
    " triangles): KeepLargestComponent, trichart build --keep-largest-component";
}
} // namespace

bool PreparationReport::changed() const
{
  return polygonsTriangulated > 0 || mergedPoints > 0 || degenerateFaces > 0 ||
    duplicateFaces > 0 || flippedFaces > 0 || unusedPoints > 0 || splitVertices > 0 ||
    droppedNonOrientable > 0 || droppedSmallComponents > 0 || droppedMinorComponents > 0 ||
    filledHoles > 0 || droppedFragments > 0 || sliverPoints > 0 || reshapedTriangles > 0;
}

bool closedManifold(const PreparationReport& report, const PreparationOptions& options)
{
  return options.orient && report.closedComponents == report.components &&
    report.nonOrientableComponents == 0 &&
    (options.splitNonManifold || report.nonManifoldEdges + report.nonManifoldVertices == 0);
}

std::string closedManifoldRepairs(
  const PreparationReport& report, const PreparationOptions& options)
{
  if (closedManifold(report, options))
  {
    return {};
  }
  std::vector<std::string> problems;
  if (!options.splitNonManifold && report.nonManifoldEdges + report.nonManifoldVertices > 0)
  {
    problems.push_back(nonManifoldRepair(report));
  }
  if (report.nonOrientableComponents > 0)
  {
    problems.push_back(nonOrientableRepair(report));
  }
  if (report.boundaryEdges > 0)
  {
    problems.push_back(boundaryRepair(report, options));
  }
  if (!options.orient)
  {
    problems.push_back("orientation unchecked (turn Orient on)");
  }
  const std::string largest = largestComponentRepair(report, options);
  if (!largest.empty() && options.orient)
  {
    problems.push_back(largest);
  }
  std::string text;
  for (const std::string& p : problems)
  {
    text += (text.empty() ? "" : "; ") + p;
  }
  return text.empty() ? "unknown" : text;
}

std::string PreparationReport::text() const
{
  using namespace detail;
  // One line per count, in this order; a count of 0 gives no line.
  const std::pair<int64_t, std::string> lines[] = {
    { inputPoints, counted(inputPoints, { "input point", "input points" }) },
    { inputPolygons, counted(inputPolygons, { "input polygon", "input polygons" }) },
    { polygonsTriangulated,
      "triangulated " + counted(polygonsTriangulated, { "polygon", "polygons" }) +
        " with more than 3 corners" },
    { mergedPoints, "merged " + counted(mergedPoints, { "duplicate point", "duplicate points" }) },
    { degenerateFaces,
      "dropped " + counted(degenerateFaces, kDegenerateFace) + " (repeated corner or zero area)" },
    { duplicateFaces,
      "dropped " + counted(duplicateFaces, { "duplicate face", "duplicate faces" }) },
    { flippedFaces,
      "flipped " + counted(flippedFaces, { "face", "faces" }) + " for a consistent orientation" },
    { unusedPoints, "dropped " + counted(unusedPoints, { "unused point", "unused points" }) },
    { nonManifoldEdges,
      "found " + counted(nonManifoldEdges, kNonManifoldEdge) + " (more than 2 faces)" },
    { nonManifoldVertices,
      "found " + counted(nonManifoldVertices, kNonManifoldVertex) +
        " (more than one fan of faces)" },
    { splitVertices,
      "added " + counted(splitVertices, { "vertex copy", "vertex copies" }) +
        " to split non-manifold edges and vertices" },
    { droppedNonOrientable,
      "dropped " + counted(droppedNonOrientable, kNonOrientableComponent) + " with " +
        counted(droppedNonOrientableTriangles, kTriangle) + " (DropNonOrientable)" },
    { droppedSmallComponents,
      "dropped " + counted(droppedSmallComponents, kComponent) + " of fewer triangles than " +
        "MinComponentTriangles, with " + counted(droppedSmallTriangles, kTriangle) + " in all" },
    { droppedMinorComponents,
      "dropped " + counted(droppedMinorComponents, kComponent) + " other than the largest, with " +
        counted(droppedMinorTriangles, kTriangle) + " in all (KeepLargestComponent)" },
    { filledHoles,
      "filled " + counted(filledHoles, kHole) + " with " + counted(holeTriangles, kTriangle) +
        " and " + counted(holePoints, kPoint) },
    { droppedFragments,
      "dropped " + counted(droppedFragments, { "fragment", "fragments" }) +
        " of fewer than 4 triangles, which no hole filling closes into a surface" },
    { droppedComponentPoints,
      "dropped " + counted(droppedComponentPoints, kPoint) + " with the dropped components" },
    { unfairedHoles,
      counted(unfairedHoles, { "filled hole", "filled holes" }) + " left unfaired (flat patch)" },
    { openHoles,
      "left " + counted(openHoles, kHole) +
        " open (more boundary edges than MaxHoleEdges, or no manifold patch)" },
    { slivers,
      "found " + counted(slivers, kSliver) + " (caps and needles): collapsed " +
        counted(sliverPoints, kPoint) + " and reshaped " + counted(reshapedTriangles, kTriangle) },
    { remainingSlivers,
      "left " + counted(remainingSlivers, kSliver) +
        " (no collapse or flip removes them without a fold)" },
    { boundaryEdges, counted(boundaryEdges, kBoundaryEdge) },
    { components, counted(components, { "connected component", "connected components" }) },
    { closedComponents, counted(closedComponents, { "closed component", "closed components" }) },
    { nonOrientableComponents,
      counted(nonOrientableComponents, kNonOrientableComponent) + " with " +
        counted(nonOrientableTriangles, kTriangle) + " (left unoriented)" },
    { outputPoints, counted(outputPoints, { "output point", "output points" }) },
    { outputTriangles, counted(outputTriangles, { "output triangle", "output triangles" }) },
  };
  std::string text;
  for (const auto& [n, line] : lines)
  {
    if (n != 0)
    {
      text += line + "\n";
    }
  }
  return text;
}
} // namespace tc
