#pragma once
// Hand-made surface layouts for tests and benchmarks: a triangle mesh (its own input), the edges
// that arcs run along and every patch's four corners give the SurfaceLayout (arcs traced between
// nodes, patches flood-filled, sides split at the corners). Grid surfaces (torus, cylinder, square)
// with patches as rectangles of cells, random T-meshes on a torus, and a subdivided cube.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "igm/layout/surface_layout.h"

namespace igm_test {

struct LayoutSpec {
  std::vector<igm::Vec3d> positions;
  std::vector<std::array<int, 3>> triangles;
  /// Edges (either direction) the arcs run along; the surface's boundary edges are added.
  std::vector<std::pair<int, int>> arc_edges;
  /// Per patch: corner k as the directed boundary edge (v, w) leaving it along side k, the patch on
  /// its left. Nodes: the corners, the vertices with other than two arc edges, `extra_nodes`.
  std::vector<std::array<std::pair<int, int>, 4>> corners;
  std::vector<int> extra_nodes;
};

/// The layout of `spec`; throws std::runtime_error if the spec does not describe one (a cycle of
/// arc edges without a node, a triangle in two patches' flood fills, one in none, a corner's
/// edge off the boundary).
inline igm::SurfaceLayout build_layout(const LayoutSpec& spec) {
  using namespace igm;
  SurfaceLayout L;
  const int nv = static_cast<int>(spec.positions.size()), nf = static_cast<int>(spec.triangles.size());
  const int np = static_cast<int>(spec.corners.size());
  L.num_input_vertices = nv;
  L.positions = spec.positions;
  for (int v = 0; v < nv; ++v) L.locations.push_back(SurfacePoint::vertex(v));
  L.triangles = spec.triangles;
  L.triangle_patch.assign(nf, 0);
  L.patches.resize(1);
  const LayoutAdjacency A = layout_adjacency(L);  // no arcs yet: the half-edges only
  if (!A.error.empty()) throw std::runtime_error(A.error);
  auto he = [&](int a, int b) {
    const int h = A.halfedge(a, b);
    if (h < 0) throw std::runtime_error("no half-edge " + std::to_string(a) + "->" + std::to_string(b));
    return h;
  };
  std::vector<char> on_arc(3 * nf, 0);
  std::vector<std::set<int>> nbr(nv);
  auto add_arc_edge = [&](int a, int b) {
    nbr[a].insert(b);
    nbr[b].insert(a);
    const int h = A.halfedge(a, b), g = A.halfedge(b, a);
    if (h < 0 && g < 0) throw std::runtime_error("arc edge is no edge");
    if (h >= 0) on_arc[h] = 1;
    if (g >= 0) on_arc[g] = 1;
  };
  for (const auto& [a, b] : spec.arc_edges) add_arc_edge(a, b);
  for (int h = 0; h < 3 * nf; ++h)
    if (A.twin[h] < 0) add_arc_edge(L.triangles[h / 3][h % 3], A.head[h]);
  std::vector<char> node(nv, 0);
  for (int v = 0; v < nv; ++v) node[v] = !nbr[v].empty() && nbr[v].size() != 2;
  for (const auto& c : spec.corners)
    for (const auto& e : c) node[e.first] = 1;
  for (int v : spec.extra_nodes) node[v] = 1;
  // Patches: flood fill from each patch's corner 0.
  L.triangle_patch.assign(nf, -1);
  for (int p = 0; p < np; ++p) {
    std::vector<int> queue{he(spec.corners[p][0].first, spec.corners[p][0].second) / 3};
    if (L.triangle_patch[queue[0]] >= 0) throw std::runtime_error("two patches share a triangle");
    L.triangle_patch[queue[0]] = p;
    for (std::size_t i = 0; i < queue.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const int h = 3 * queue[i] + k;
        if (on_arc[h]) continue;
        const int t = A.twin[h] / 3;
        if (L.triangle_patch[t] == p) continue;
        if (L.triangle_patch[t] >= 0) throw std::runtime_error("two patches share a triangle");
        L.triangle_patch[t] = p;
        queue.push_back(t);
      }
  }
  for (int t = 0; t < nf; ++t)
    if (L.triangle_patch[t] < 0) throw std::runtime_error("a triangle in no patch");
  L.patches.assign(np, {});
  // Arcs: from every node along every arc edge to the next node.
  std::map<std::pair<int, int>, std::array<int, 3>> use_of;  // directed edge -> (arc, forward, index)
  std::set<std::pair<int, int>> done;
  for (int v = 0; v < nv; ++v) {
    if (!node[v]) continue;
    for (int w0 : nbr[v]) {
      if (done.count({std::min(v, w0), std::max(v, w0)})) continue;
      LayoutArc arc;
      arc.vertices = {v, w0};
      done.insert({std::min(v, w0), std::max(v, w0)});
      for (int guard = 0; !node[arc.vertices.back()]; ++guard) {
        if (guard > nv) throw std::runtime_error("arc without end");
        const int x = arc.vertices.back(), prev = arc.vertices[arc.vertices.size() - 2];
        const int y = *nbr[x].begin() == prev ? *nbr[x].rbegin() : *nbr[x].begin();
        done.insert({std::min(x, y), std::max(x, y)});
        arc.vertices.push_back(y);
      }
      const int h = A.halfedge(arc.vertices[0], arc.vertices[1]), g = A.halfedge(arc.vertices[1], arc.vertices[0]);
      arc.patch = {h >= 0 ? L.triangle_patch[h / 3] : -1, g >= 0 ? L.triangle_patch[g / 3] : -1};
      const int a = static_cast<int>(L.arcs.size()), m = static_cast<int>(arc.vertices.size());
      for (int s = 0; s + 1 < m; ++s) {
        use_of[{arc.vertices[s], arc.vertices[s + 1]}] = {a, 1, s};
        use_of[{arc.vertices[s + 1], arc.vertices[s]}] = {a, 0, m - 2 - s};
      }
      L.arcs.push_back(std::move(arc));
    }
  }
  if (done.size() * 2 != [&] {
        std::size_t n = 0;
        for (const auto& s : nbr) n += s.size();
        return n;
      }())
    throw std::runtime_error("a cycle of arc edges without a node");
  // Sides: the boundary loop from corner 0, split at the corners.
  for (int p = 0; p < np; ++p) {
    std::array<int, 4> corner_he{};
    for (int k = 0; k < 4; ++k) corner_he[k] = he(spec.corners[p][k].first, spec.corners[p][k].second);
    const int h0 = corner_he[0];
    int h = h0, side = 0;
    for (int guard = 0;; ++guard) {
      if (guard > 3 * nf) throw std::runtime_error("boundary loop does not close");
      if (side < 3 && h == corner_he[side + 1]) ++side;
      const int a = L.triangles[h / 3][h % 3], b = A.head[h];
      const auto it = use_of.find({a, b});
      if (it == use_of.end()) throw std::runtime_error("boundary edge on no arc");
      if (it->second[2] == 0) L.patches[p].sides[side].push_back({it->second[0], it->second[1] == 1});
      int g = h % 3 == 2 ? h - 2 : h + 1;  // next half-edge in the triangle, leaving b
      for (int turn = 0; !on_arc[g]; ++turn) {
        if (turn > nv) throw std::runtime_error("no boundary successor");
        const int t = A.twin[g];
        g = t % 3 == 2 ? t - 2 : t + 1;
      }
      h = g;
      if (h == h0) break;
    }
  }
  return L;
}

/// A rectangle of cells [i0, i1] x [j0, j1] of a grid.
struct Rect {
  int i0, j0, i1, j1;
};

/// A grid of n x m cells, each split in two triangles, wrapped in i and/or j (torus, cylinder,
/// square), embedded by `embed(i, j)`; patches the rectangles (tiling the grid), arcs along their
/// sides, corners at theirs.
template <class Embed>
LayoutSpec grid_spec(int n, int m, bool wrap_i, bool wrap_j, const std::vector<Rect>& rects, Embed embed) {
  LayoutSpec s;
  const int ni = wrap_i ? n : n + 1, nj = wrap_j ? m : m + 1;
  auto id = [&](int i, int j) { return ((i % ni) + ni) % ni + (((j % nj) + nj) % nj) * ni; };
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) s.positions.push_back(embed(i, j));
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  for (const Rect& r : rects) {
    for (int i = r.i0; i < r.i1; ++i) {
      s.arc_edges.push_back({id(i, r.j0), id(i + 1, r.j0)});
      s.arc_edges.push_back({id(i, r.j1), id(i + 1, r.j1)});
    }
    for (int j = r.j0; j < r.j1; ++j) {
      s.arc_edges.push_back({id(r.i0, j), id(r.i0, j + 1)});
      s.arc_edges.push_back({id(r.i1, j), id(r.i1, j + 1)});
    }
    s.corners.push_back({std::pair{id(r.i0, r.j0), id(r.i0 + 1, r.j0)}, std::pair{id(r.i1, r.j0), id(r.i1, r.j0 + 1)},
                         std::pair{id(r.i1, r.j1), id(r.i1 - 1, r.j1)}, std::pair{id(r.i0, r.j1), id(r.i0, r.j1 - 1)}});
  }
  std::sort(s.arc_edges.begin(), s.arc_edges.end());
  return s;
}

/// A torus of revolution (radii R > r), grid point (i, j) at angles 2 pi i / n, 2 pi j / m,
/// oriented outwards.
inline auto torus_embedding(int n, int m, double R = 3, double r = 1) {
  return [=](int i, int j) {
    const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
    return igm::Vec3d{(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)};
  };
}

/// A cylinder of radius 1: grid point (i, j) at angle 2 pi i / n, height h j (for a grid wrapped in i).
inline auto cylinder_embedding(int n, double h = 1) {
  return [=](int i, int j) { return igm::Vec3d{std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), h * j}; };
}

/// Rectangles tiling an n x m torus grid: a k x k array of blocks, then `splits` random guillotine
/// splits (a block of >= 2 cells across, cut along a grid line), seeded mt19937 (its raw outputs:
/// the same on every machine).
inline std::vector<Rect> random_t_mesh(int n, int m, int k, int splits, std::uint32_t seed) {
  std::vector<Rect> rects;
  for (int b = 0; b < k; ++b)
    for (int a = 0; a < k; ++a) rects.push_back({a * n / k, b * m / k, (a + 1) * n / k, (b + 1) * m / k});
  std::mt19937 rng(seed);
  for (int s = 0, tries = 0; s < splits && tries < 100 * splits + 100; ++tries) {
    Rect& r = rects[rng() % rects.size()];
    const int w = r.i1 - r.i0, h = r.j1 - r.j0;
    if (w < 2 && h < 2) continue;
    const bool vertical = w >= 2 && (h < 2 || rng() % 2 == 0);
    Rect other = r;
    if (vertical) {
      const int c = r.i0 + 1 + static_cast<int>(rng() % (w - 1));
      other.i0 = c;
      r.i1 = c;
    } else {
      const int c = r.j0 + 1 + static_cast<int>(rng() % (h - 1));
      other.j0 = c;
      r.j1 = c;
    }
    rects.push_back(other);
    ++s;
  }
  return rects;
}

/// A cube [0, s]^3 with every face an s x s grid (two triangles per cell), oriented outwards; patch
/// f = face f (order -z, +z, -y, +y, -x, +x), its corners at the cube's; with `split_top`, face +z
/// is two patches, split across its middle (s even), which puts T-junctions on faces -y and +y.
inline LayoutSpec cube_spec(int s, bool split_top) {
  LayoutSpec spec;
  std::map<std::array<int, 3>, int> id;
  auto vertex = [&](std::array<int, 3> p) {
    auto [it, fresh] = id.emplace(p, static_cast<int>(spec.positions.size()));
    if (fresh) spec.positions.push_back({double(p[0]), double(p[1]), double(p[2])});
    return it->second;
  };
  struct Face {
    std::array<int, 3> o, u, v;
  };
  const Face faces[6] = {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}, {{0, 0, s}, {1, 0, 0}, {0, 1, 0}},
                         {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, s, 0}, {0, 0, 1}, {1, 0, 0}},
                         {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{s, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  std::vector<int> face_of_triangle;
  for (int f = 0; f < 6; ++f) {
    const Face& F = faces[f];
    auto at = [&](int a, int b) {
      return vertex({F.o[0] + a * F.u[0] + b * F.v[0], F.o[1] + a * F.u[1] + b * F.v[1], F.o[2] + a * F.u[2] + b * F.v[2]});
    };
    for (int b = 0; b < s; ++b)
      for (int a = 0; a < s; ++a) {
        spec.triangles.push_back({at(a, b), at(a + 1, b), at(a + 1, b + 1)});
        spec.triangles.push_back({at(a, b), at(a + 1, b + 1), at(a, b + 1)});
        face_of_triangle.push_back(f);
        face_of_triangle.push_back(f);
      }
    std::vector<std::pair<int, int>> ranges = {{0, s}};
    if (f == 1 && split_top) ranges = {{0, s / 2}, {s / 2, s}};
    for (auto [a0, a1] : ranges) {
      spec.corners.push_back({std::pair{at(a0, 0), at(a0 + 1, 0)}, std::pair{at(a1, 0), at(a1, 1)},
                              std::pair{at(a1, s), at(a1 - 1, s)}, std::pair{at(a0, s), at(a0, s - 1)}});
      for (int b = 0; b < s; ++b) spec.arc_edges.push_back({at(a0, b), at(a0, b + 1)}), spec.arc_edges.push_back({at(a1, b), at(a1, b + 1)});
      for (int a = a0; a < a1; ++a) spec.arc_edges.push_back({at(a, 0), at(a + 1, 0)}), spec.arc_edges.push_back({at(a, s), at(a + 1, s)});
    }
  }
  std::sort(spec.arc_edges.begin(), spec.arc_edges.end());
  return spec;
}

}  // namespace igm_test
