#pragma once
// Shared by tests/igm and tests/extract: the stages before the patch maps, run directly on a mesh
// (topology, a uniform Tutte map of the disk with uniformly placed sides, a layout, its overlay,
// the patch mesh), so that the patch maps and grids can be tested on their own.
#include <stdexcept>
#include <string>
#include <vector>

#include "certify/certify.h"
#include "igm/arrange/overlay.h"
#include "igm/embed/polygon.h"
#include "igm/embed/tutte.h"
#include "igm/igm/layout_map.h"
#include "igm/igm/patch_maps.h"
#include "igm/igm/patch_mesh.h"
#include "igm/layout/quad_layout.h"
#include "igm/layout/sizing.h"
#include "igm/mesh/validate.h"
#include "igm/topology/cut_to_canonical_disk.h"

namespace igm_test {

struct PatchSetup {
  igm::QuadLayout layout;
  igm::OverlayResult overlay;
  igm::PatchMesh mesh;
  std::vector<igm::Vec3d> input_positions;
};

/// Runs the stages up to the patch mesh; `affine` adds the layout's diagonals to the overlay.
inline PatchSetup patch_setup(const igm::ValidMesh& mesh, igm::LayoutKind kind, bool affine) {
  using namespace igm;
  PatchSetup s;
  CutOptions co;
  co.congestion_rounds = 0;  // any valid cut will do here, the quickest
  CutResult cut = cut_to_canonical_disk(mesh.mesh, mesh.positions, co);
  const int g = cut.genus;
  const auto corners = canonical_polygon(g);
  std::vector<int> counts, mates;
  for (const BoundarySide& side : cut.sides) {
    counts.push_back(static_cast<int>(side.disk_vertices.size()) - 1);
    mates.push_back(side.mate);
  }
  const int nd = static_cast<int>(cut.disk_to_surface.size());
  TutteResult tutte = tutte_embed(nd, cut.disk_triangles, cut.boundary, place_boundary(corners, counts));
  LayoutOptions lo;
  lo.kind = kind;
  s.layout = make_layout(corners, polygon_centre(corners), mates, lo);
  std::vector<Segment2> segments;
  for (const LayoutEdge& e : s.layout.edges) segments.push_back({s.layout.points[e.a], s.layout.points[e.b]});
  if (affine) {
    const std::vector<int> d = quad_diagonals(s.layout);
    for (std::size_t q = 0; q < d.size(); ++q)
      if (d[q] >= 0) segments.push_back({s.layout.points[s.layout.quads[q][d[q]]], s.layout.points[s.layout.quads[q][d[q] + 2]]});
  }
  s.overlay = overlay_segments(PlanarTriangulation{tutte.uv, cut.disk_triangles}, segments);
  PatchMeshInput in;
  in.layout = &s.layout;
  in.overlay = &s.overlay;
  in.num_disk_vertices = nd;
  in.disk_to_surface = &cut.disk_to_surface;
  in.disk_triangles = &cut.disk_triangles;
  for (int v = 0; v < cut.surface.num_input_vertices; ++v) in.surface_locations.push_back(SurfacePoint::vertex(v));
  for (const SurfacePoint& p : cut.surface.constructed) in.surface_locations.push_back(p);
  s.input_positions = cut.surface.input_positions;
  in.input_positions = &s.input_positions;
  s.mesh = build_patch_mesh(std::move(in));
  return s;
}

/// The Tutte maps of the set-up's patches (map_layout on its surface layout, arcs sized by the
/// chords), whose triangles are the patch mesh's: throws if map_layout had to split an edge.
inline igm::LayoutMap tutte_maps(const PatchSetup& s, const igm::Sizing& sizing, double length_scale = 1) {
  igm::PatchMesh copy = s.mesh;
  igm::LayoutMapOptions o;
  o.length_scale = length_scale;
  igm::LayoutMap m = igm::map_layout(
      igm::to_surface_layout(s.layout, copy, static_cast<int>(s.input_positions.size())), sizing.edge_count, o);
  if (m.stats.splits != 0 || m.igm.triangles.size() != s.mesh.triangles.size())
    throw std::runtime_error("tutte_maps: map_layout split edges of the patch mesh");
  return m;
}

/// The certifier's report on the patch mesh with these corner UVs (checks 1-4).
inline igm::certify::Report certify_patch_maps(const igm::PatchMesh& m,
                                               const std::vector<std::array<igm::Point2q, 3>>& uv) {
  igm::certify::IgmInput in;
  for (const auto& t : m.triangles) in.faces.push_back({m.vertex_of[t[0]], m.vertex_of[t[1]], m.vertex_of[t[2]]});
  in.num_vertices = static_cast<std::int64_t>(m.locations.size());
  for (const auto& tri : uv)
    for (const igm::Point2q& p : tri) in.corner_uv.push_back({p.x, p.y});
  return igm::certify::certify_igm(in);
}

}  // namespace igm_test
