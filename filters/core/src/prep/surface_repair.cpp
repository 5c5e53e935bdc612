// SPDX-License-Identifier: BSD-3-Clause
#include "prep/surface_repair.h"

#include "detail/geometry2d.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <tuple>
#include <vector>

namespace tc
{
namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Surface = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

/// `mesh` as a Surface_mesh with the same point and face indices; false if a face cannot be
/// added (a non-manifold vertex or edge, or a face against its neighbours' orientation).
bool toSurface(const TriMesh& mesh, Surface& surface)
{
  const int64_t nv = mesh.numPoints();
  const int64_t nf = mesh.numTriangles();
  surface.reserve(static_cast<Surface::size_type>(nv), static_cast<Surface::size_type>(3 * nf),
    static_cast<Surface::size_type>(nf));
  for (int64_t v = 0; v < nv; ++v)
  {
    surface.add_vertex(
      Kernel::Point_3(mesh.points[3 * v], mesh.points[3 * v + 1], mesh.points[3 * v + 2]));
  }
  for (int64_t f = 0; f < nf; ++f)
  {
    const int32_t* t = &mesh.triangles[3 * f];
    if (surface.add_face(Surface::Vertex_index(static_cast<Surface::size_type>(t[0])),
          Surface::Vertex_index(static_cast<Surface::size_type>(t[1])),
          Surface::Vertex_index(static_cast<Surface::size_type>(t[2]))) == Surface::null_face())
    {
      return false;
    }
  }
  return true;
}

/// The triangles removeSlivers looks for: a needle (longest side over shortest above
/// maxEdgeRatio, or a side of no length) or a cap (largest angle above maxAngleDegrees),
/// with both thresholds turned once into what the test compares.
struct SliverTest
{
  double capCosine; ///< cosine of the largest angle a triangle may have
  double ratio2;    ///< squared largest ratio of longest to shortest side
  SliverTest(double maxAngleDegrees, double maxEdgeRatio)
    : capCosine(std::cos(maxAngleDegrees * detail::kPi / 180.0))
    , ratio2(maxEdgeRatio * maxEdgeRatio)
  {
  }
  bool operator()(const double* a, const double* b, const double* c) const
  {
    const double* p[3] = { a, b, c };
    double len2[3];
    for (int i = 0; i < 3; ++i)
    {
      const double* u = p[(i + 1) % 3];
      const double* w = p[(i + 2) % 3];
      len2[i] = (u[0] - w[0]) * (u[0] - w[0]) + (u[1] - w[1]) * (u[1] - w[1]) +
        (u[2] - w[2]) * (u[2] - w[2]); // side opposite corner i
    }
    const int k = static_cast<int>(std::max_element(len2, len2 + 3) - len2);
    const double longest = len2[k];
    const double s1 = len2[(k + 1) % 3], s2 = len2[(k + 2) % 3];
    const double shortest = std::min(s1, s2);
    if (!(shortest > 0.0) || longest > ratio2 * shortest)
    {
      return true;
    }
    // The largest angle is opposite the longest side.
    return (s1 + s2 - longest) / (2.0 * std::sqrt(s1 * s2)) < capCosine;
  }
  int64_t count(const TriMesh& m) const
  {
    int64_t n = 0;
    for (int64_t f = 0; f < m.numTriangles(); ++f)
    {
      const int32_t* t = &m.triangles[3 * f];
      n += (*this)(&m.points[3 * static_cast<size_t>(t[0])],
             &m.points[3 * static_cast<size_t>(t[1])], &m.points[3 * static_cast<size_t>(t[2])])
        ? 1
        : 0;
    }
    return n;
  }
};

/// One border half-edge per boundary loop, in the order of the half-edges, and the number of
/// edges of each loop.
void borderLoops(const Surface& surface, std::vector<Surface::Halfedge_index>& loops,
  std::vector<int64_t>& loopEdges)
{
  std::vector<uint8_t> seen(surface.number_of_halfedges(), 0);
  for (const Surface::Halfedge_index h : surface.halfedges())
  {
    if (!surface.is_border(h) || seen[h.idx()])
    {
      continue;
    }
    int64_t edges = 0;
    Surface::Halfedge_index g = h;
    do
    {
      seen[g.idx()] = 1;
      ++edges;
      g = surface.next(g);
    } while (g != h);
    loops.push_back(h);
    loopEdges.push_back(edges);
  }
}

/// Appends to `mesh` the points CGAL added to `surface` after its first nv, in the order it
/// added them, and the triangles `faces`, in the order of their holes.
void appendPatches(
  const Surface& surface, int64_t nv, const std::vector<Surface::Face_index>& faces, TriMesh& mesh)
{
  const int64_t total = static_cast<int64_t>(surface.number_of_vertices());
  for (int64_t v = nv; v < total; ++v)
  {
    const Kernel::Point_3& p =
      surface.point(Surface::Vertex_index(static_cast<Surface::size_type>(v)));
    mesh.points.insert(mesh.points.end(), { p.x(), p.y(), p.z() });
  }
  for (const Surface::Face_index f : faces)
  {
    for (const Surface::Vertex_index v : surface.vertices_around_face(surface.halfedge(f)))
    {
      mesh.triangles.push_back(static_cast<int32_t>(v.idx()));
    }
  }
}
} // namespace

HoleFilling fillHoles(TriMesh& mesh, int64_t maxEdges, const Progress& progress)
{
  progress.report(0.0);
  HoleFilling out;
  const int64_t nv = mesh.numPoints();
  Surface surface;
  if (!toSurface(mesh, surface))
  {
    out.nonManifold = true;
    progress.report(1.0);
    return out;
  }
  std::vector<Surface::Halfedge_index> loops;
  std::vector<int64_t> loopEdges;
  borderLoops(surface, loops, loopEdges);

  std::vector<Surface::Face_index> faces;
  std::vector<Surface::Vertex_index> vertices;
  for (size_t i = 0; i < loops.size(); ++i)
  {
    progress.report(static_cast<double>(i) / static_cast<double>(loops.size()));
    if (maxEdges > 0 && loopEdges[i] > maxEdges)
    {
      ++out.skippedHoles;
      continue;
    }
    const size_t before = faces.size();
    const bool faired = std::get<0>(PMP::triangulate_refine_and_fair_hole(
      surface, loops[i], std::back_inserter(faces), std::back_inserter(vertices)));
    if (faces.size() == before)
    {
      ++out.skippedHoles; // no triangulation without a non-manifold edge
      continue;
    }
    ++out.filledHoles;
    out.unfairedHoles += faired ? 0 : 1;
  }

  appendPatches(surface, nv, faces, mesh);
  out.addedPoints = mesh.numPoints() - nv;
  out.addedTriangles = static_cast<int64_t>(faces.size());
  progress.report(1.0);
  return out;
}

SliverRemoval removeSlivers(
  TriMesh& mesh, double maxAngleDegrees, double maxEdgeRatio, const Progress& progress)
{
  progress.report(0.0);
  SliverRemoval out;
  const SliverTest sliver(maxAngleDegrees, maxEdgeRatio);
  out.slivers = sliver.count(mesh);
  if (out.slivers == 0)
  {
    progress.report(1.0);
    return out;
  }
  Surface surface;
  if (!toSurface(mesh, surface))
  {
    out.nonManifold = true;
    progress.report(1.0);
    return out;
  }
  progress.report(0.2);
  // CGAL's cap threshold is the cosine of the largest angle; no length limit on collapses.
  PMP::experimental::remove_almost_degenerate_faces(surface, sliver.capCosine, maxEdgeRatio, 0.0);
  progress.report(0.8);

  // Removed elements stay as holes in Surface_mesh's index ranges until collect_garbage, which
  // would reorder: the survivors are read in index order instead.
  std::vector<int32_t> newId(static_cast<size_t>(mesh.numPoints()), -1);
  TriMesh repaired;
  for (const Surface::Vertex_index v : surface.vertices())
  {
    newId[v.idx()] = static_cast<int32_t>(out.keptPoints.size());
    out.keptPoints.push_back(static_cast<int32_t>(v.idx()));
    const Kernel::Point_3& p = surface.point(v);
    repaired.points.insert(repaired.points.end(), { p.x(), p.y(), p.z() });
  }
  for (const Surface::Face_index f : surface.faces())
  {
    std::array<int32_t, 3> corners{};
    int k = 0;
    for (const Surface::Vertex_index v : surface.vertices_around_face(surface.halfedge(f)))
    {
      corners[k++] = static_cast<int32_t>(v.idx());
    }
    // Same triangle as before up to rotation, or reshaped?
    const int32_t* before = &mesh.triangles[3 * static_cast<size_t>(f.idx())];
    bool same = false;
    for (int r = 0; r < 3; ++r)
    {
      same |= before[r] == corners[0] && before[(r + 1) % 3] == corners[1] &&
        before[(r + 2) % 3] == corners[2];
    }
    out.reshapedTriangles += same ? 0 : 1;
    out.keptTriangles.push_back(static_cast<int32_t>(f.idx()));
    for (const int32_t c : corners)
    {
      repaired.triangles.push_back(newId[c]);
    }
  }
  out.collapsedPoints = mesh.numPoints() - repaired.numPoints();
  mesh = std::move(repaired);
  out.remainingSlivers = sliver.count(mesh);
  progress.report(1.0);
  return out;
}
} // namespace tc
