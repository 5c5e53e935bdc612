// SPDX-License-Identifier: BSD-3-Clause
#include "hole_filling.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

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
} // namespace

HoleFilling fillHoles(TriMesh& mesh, int64_t maxEdges, const Progress& progress)
{
  progress.report(0.0);
  HoleFilling out;
  const int64_t nv = mesh.numPoints();
  const int64_t nf = mesh.numTriangles();
  Surface surface;
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
      out.nonManifold = true;
      progress.report(1.0);
      return out;
    }
  }

  // One border half-edge per boundary loop, in the order of the half-edges.
  std::vector<Surface::Halfedge_index> loops;
  std::vector<int64_t> loopEdges;
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

  // New points keep the order CGAL added them in (after the input's), new faces the order of
  // their holes.
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
  out.addedPoints = total - nv;
  out.addedTriangles = static_cast<int64_t>(faces.size());
  progress.report(1.0);
  return out;
}
} // namespace tc
