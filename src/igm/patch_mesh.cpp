#include "igm/igm/patch_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "igm/core/error.h"
#include "igm/mesh/scale.h"

namespace igm {

namespace {

std::string str(std::int64_t x) { return std::to_string(x); }

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

bool same_location(const SurfacePoint& a, const SurfacePoint& b) {
  for (int i = 0; i < 3; ++i)
    if (a.v[i] != b.v[i] || (a.v[i] >= 0 && a.w[i] != b.w[i])) return false;
  return true;
}

}  // namespace

PatchMesh build_patch_mesh(PatchMeshInput in) {
  if (!in.layout || !in.overlay || !in.disk_to_surface || !in.disk_triangles || !in.input_positions)
    throw Error(ErrorKind::InvalidArgument, "build_patch_mesh: missing input");
  const QuadLayout& L = *in.layout;
  const OverlayResult& ov = *in.overlay;
  const auto& P = ov.mesh.positions;
  const auto& F = ov.mesh.triangles;
  const int nov = static_cast<int>(P.size());
  const int ne = static_cast<int>(L.edges.size());
  const int nd = in.num_disk_vertices;
  if (static_cast<int>(ov.chains.size()) < ne || nd < 0 || nd > nov || static_cast<int>(in.disk_to_surface->size()) != nd)
    throw Error(ErrorKind::InvalidArgument, "build_patch_mesh: the overlay does not match the layout or the disk");
  PatchMesh m;
  m.num_overlay_vertices = nov;
  m.edge_chain.assign(ov.chains.begin(), ov.chains.begin() + ne);
  for (int e = 0; e < ne; ++e) {
    const auto& c = m.edge_chain[e];
    if (c.size() < 2 || !same_point(P[c.front()], L.points[L.edges[e].a]) || !same_point(P[c.back()], L.points[L.edges[e].b]))
      throw Error(ErrorKind::InvalidArgument, "build_patch_mesh: chain " + str(e) + " does not match layout edge " + str(e),
                  {e});
  }
  m.point_vertex.assign(L.points.size(), -1);
  for (int e = 0; e < ne; ++e) {
    m.point_vertex[L.edges[e].a] = m.edge_chain[e].front();
    m.point_vertex[L.edges[e].b] = m.edge_chain[e].back();
  }
  // --- surface ids ---
  m.locations = std::move(in.surface_locations);
  m.vertex_of.assign(nov, -1);
  for (int v = 0; v < nd; ++v) m.vertex_of[v] = (*in.disk_to_surface)[v];
  auto new_location = [&](int v) {
    const VertexOrigin& o = ov.origin[v];
    if (o.input_vertex >= 0 || o.input_triangle < 0)
      throw Error(ErrorKind::Internal, "overlay vertex " + str(v) + " has no location in a disk triangle", {v});
    const auto& tri = (*in.disk_triangles)[o.input_triangle];
    return barycentric_point(m.locations[(*in.disk_to_surface)[tri[0]]], m.locations[(*in.disk_to_surface)[tri[1]]],
                             m.locations[(*in.disk_to_surface)[tri[2]]], o.barycentric);
  };
  // A new point on a polygon side is one surface vertex with its glued partner on the mate side.
  const int ns = L.num_corners();
  for (int s = 0; s < ns; ++s) {
    if (L.side_mate[s] < 0) continue;  // a free side: its new points are vertices of their own (below)
    const auto &sp = L.side_points[s], &mp = L.side_points[L.side_mate[s]];
    const std::size_t n = sp.size() - 1;
    for (std::size_t j = 1; j < n; ++j) {
      const int v = m.point_vertex[sp[j]], w = m.point_vertex[mp[n - j]];
      if ((v < nd) != (w < nd))
        throw Error(ErrorKind::Internal, "layout point " + str(sp[j]) + " is a disk vertex on one side of its gluing only",
                    {sp[j]});
      if (v < nd) continue;  // both disk vertices: their surface vertex, checked with the chains below
      if (m.vertex_of[v] >= 0) continue;
      SurfacePoint p = new_location(v);
      if (m.vertex_of[w] < 0 && !same_location(p, new_location(w)))
        throw Error(ErrorKind::Internal, "the glued copies of layout point " + str(sp[j]) + " are different surface points",
                    {sp[j]});
      m.vertex_of[v] = m.vertex_of[w] = static_cast<int>(m.locations.size());
      m.locations.push_back(std::move(p));
    }
  }
  for (int v = nd; v < nov; ++v)
    if (m.vertex_of[v] < 0) {
      m.vertex_of[v] = static_cast<int>(m.locations.size());
      m.locations.push_back(new_location(v));
    }
  // Glued chains: the same surface vertices, in opposite orders.
  std::vector<std::vector<int>> piece_edge(ns);
  for (int e = 0; e < ne; ++e)
    if (L.edges[e].side >= 0) {
      auto& pe = piece_edge[L.edges[e].side];
      if (static_cast<int>(pe.size()) <= L.edges[e].piece) pe.resize(L.edges[e].piece + 1, -1);
      pe[L.edges[e].piece] = e;
    }
  for (int e = 0; e < ne; ++e) {
    const LayoutEdge& E = L.edges[e];
    if (E.side < 0 || L.side_mate[E.side] < 0) continue;
    const auto& mate_pieces = piece_edge[L.side_mate[E.side]];
    const int f = mate_pieces[mate_pieces.size() - 1 - E.piece];
    const auto &a = m.edge_chain[e], &b = m.edge_chain[f];
    bool same = a.size() == b.size();
    for (std::size_t i = 0; same && i < a.size(); ++i) same = m.vertex_of[a[i]] == m.vertex_of[b[b.size() - 1 - i]];
    if (!same)
      throw Error(ErrorKind::Internal, "piece " + str(E.piece) + " of side " + str(E.side) +
                                           " and its glued piece do not carry the same surface vertices",
                  {E.side});
  }
  // --- patches: flood fill bounded by the layout edges ---
  const PlanarAdjacency adj = PlanarAdjacency::build(nov, F);
  auto directed = [&](int a, int b) {  // the triangle with directed edge a -> b, or -1; O(deg a)
    for (int k = adj.star_begin[a]; k < adj.star_begin[a + 1]; ++k) {
      const auto& T = F[adj.star[k]];
      for (int i = 0; i < 3; ++i)
        if (T[i] == a && T[(i + 1) % 3] == b) return adj.star[k];
    }
    return -1;
  };
  const int nf = static_cast<int>(F.size());
  m.triangle_quad.assign(nf, -1);
  std::unordered_set<std::uint64_t> barrier;
  std::vector<int> queue;
  auto seed = [&](int tri, int quad, int e) {
    if (tri < 0) {
      if (quad >= 0) throw Error(ErrorKind::Internal, "layout edge " + str(e) + " has no triangle on a quad's side", {e});
      return;
    }
    if (quad < 0) throw Error(ErrorKind::Internal, "a triangle lies outside the polygon", {tri});
    if (m.triangle_quad[tri] >= 0 && m.triangle_quad[tri] != quad)
      throw Error(ErrorKind::Internal, "triangle " + str(tri) + " touches two layout quads", {tri});
    if (m.triangle_quad[tri] < 0) queue.push_back(tri);
    m.triangle_quad[tri] = quad;
  };
  for (int e = 0; e < ne; ++e) {
    const auto& c = m.edge_chain[e];
    for (std::size_t k = 0; k + 1 < c.size(); ++k) {
      barrier.insert(edge_key(c[k], c[k + 1]));
      seed(directed(c[k], c[k + 1]), L.edges[e].quad[0], e);
      seed(directed(c[k + 1], c[k]), L.edges[e].quad[1], e);
    }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {  // each triangle enters once: bounded by F
    const int tri = queue[head];
    for (int i = 0; i < 3; ++i) {
      const int n = adj.neighbor[tri][i];
      if (n < 0 || barrier.count(edge_key(F[tri][i], F[tri][(i + 1) % 3]))) continue;
      if (m.triangle_quad[n] < 0) {
        m.triangle_quad[n] = m.triangle_quad[tri];
        queue.push_back(n);
      } else if (m.triangle_quad[n] != m.triangle_quad[tri]) {
        throw Error(ErrorKind::Internal, "layout quads leak into each other at triangle " + str(n), {n});
      }
    }
  }
  for (int t = 0; t < nf; ++t)
    if (m.triangle_quad[t] < 0) throw Error(ErrorKind::Internal, "triangle " + str(t) + " got no layout quad", {t});
  m.triangles = F;
  m.positions.resize(m.locations.size());
  for (std::size_t v = 0; v < m.locations.size(); ++v) m.positions[v] = evaluate(m.locations[v], *in.input_positions);
  return m;
}

SurfaceLayout to_surface_layout(const QuadLayout& L, PatchMesh& m, int num_input_vertices) {
  SurfaceLayout out;
  std::vector<int> id(m.locations.size(), -1);
  for (const auto& t : m.triangles)
    for (int v : t) id[m.vertex_of[v]] = 0;
  int next = 0;
  for (int& x : id)
    if (x == 0) x = next++;
  out.num_input_vertices = num_input_vertices;
  out.locations.resize(next);
  out.positions.resize(next);
  for (std::size_t v = 0; v < id.size(); ++v)
    if (id[v] >= 0) out.locations[id[v]] = std::move(m.locations[v]), out.positions[id[v]] = m.positions[v];
  m.locations = {};
  m.positions = {};
  out.triangles.reserve(m.triangles.size());
  for (const auto& t : m.triangles) out.triangles.push_back({id[m.vertex_of[t[0]]], id[m.vertex_of[t[1]]], id[m.vertex_of[t[2]]]});
  out.triangle_patch = m.triangle_quad;
  out.arcs.resize(L.num_surface_edges);
  std::vector<char> has_chain(L.num_surface_edges, 0);
  for (std::size_t e = 0; e < L.edges.size(); ++e) {
    const int s = L.surface_edge[e];
    const bool along = L.surface_edge_forward[e] != 0;
    LayoutArc& arc = out.arcs[s];
    for (int side : {0, 1}) {
      const int q = L.edges[e].quad[side];
      if (q >= 0) arc.patch[along ? side : 1 - side] = q;
    }
    if (along && !has_chain[s]) {
      has_chain[s] = 1;
      for (int v : m.edge_chain[e]) arc.vertices.push_back(id[m.vertex_of[v]]);
    }
  }
  out.patches.resize(L.quads.size());
  for (std::size_t q = 0; q < L.quads.size(); ++q)
    for (int k = 0; k < 4; ++k) {
      const int e = L.quad_edge[q][k];
      out.patches[q].sides[k].push_back({L.surface_edge[e], (L.quad_edge_forward[q][k] != 0) == (L.surface_edge_forward[e] != 0)});
    }
  return out;
}

std::vector<double> layout_edge_lengths(const QuadLayout& L, const PatchMesh& m, double scale) {
  std::vector<double> len(L.num_surface_edges, 0.0);
  std::vector<char> done(L.num_surface_edges, 0);
  for (std::size_t e = 0; e < L.edges.size(); ++e) {
    const int s = L.surface_edge[e];
    if (done[s]) continue;
    done[s] = 1;
    const auto& c = m.edge_chain[e];
    double sum = 0;
    for (std::size_t k = 0; k + 1 < c.size(); ++k) {
      sum += scaled_distance(m.positions[m.vertex_of[c[k]]], m.positions[m.vertex_of[c[k + 1]]], scale);
    }
    len[s] = sum;
  }
  return len;
}

}  // namespace igm
