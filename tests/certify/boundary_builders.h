#pragma once
// Synthetic open surfaces (with boundary) and multi-component meshes for the certifier tests:
// triangulated grid patches with their UV on the grid, built here (linking only igm::certify).
#include <array>
#include <map>
#include <set>

#include "igm_builders.h"

namespace certify_test {

using igm::certify::QuadInput;

/// A grid point (i, j) as seen from one cell, and a side that tells copies of a point apart
/// (the two banks of a slit); equal keys are one vertex.
using GridKey = std::array<int, 3>;

struct GridPatch {
  IgmInput igm;
  std::map<GridKey, int> ids;  // key -> vertex id (ids in order of first use)
  int id(int i, int j, int side = 0) const { return ids.at({i, j, side}); }
};

/// The kept cells [i, i+1] x [j, j+1] of [0, n] x [0, m], each split along (i, j)-(i+1, j+1)
/// into two counter-clockwise triangles whose corner UVs are the grid points themselves.
/// key(i, j, ci, cj) names the vertex at grid point (i, j) of cell (ci, cj).
template <class Keep, class Key>
GridPatch grid_patch(int n, int m, Keep keep, Key key) {
  GridPatch g;
  auto vid = [&](int i, int j, int ci, int cj) {
    const GridKey k = key(i, j, ci, cj);
    auto it = g.ids.find(k);
    if (it != g.ids.end()) return it->second;
    const int v = static_cast<int>(g.ids.size());
    g.ids.emplace(k, v);
    return v;
  };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      if (!keep(i, j)) continue;
      const int a = vid(i, j, i, j), b = vid(i + 1, j, i, j), c = vid(i + 1, j + 1, i, j),
                d = vid(i, j + 1, i, j);
      add_tri(g.igm, a, b, c, uv(i, j), uv(i + 1, j), uv(i + 1, j + 1));
      add_tri(g.igm, a, c, d, uv(i, j), uv(i + 1, j + 1), uv(i, j + 1));
    }
  g.igm.num_vertices = static_cast<std::int64_t>(g.ids.size());
  return g;
}

inline bool all_cells(int, int) { return true; }
inline GridKey plain_key(int i, int j, int, int) { return {i, j, 0}; }

/// The square [0, n]^2: a disk with four boundary corners of index 1.
inline GridPatch square_disk(int n) { return grid_patch(n, n, all_cells, plain_key); }

/// [0, n] x [0, m] with x periodic (the chart unwrapped, seams x -> x + n): an annulus with two
/// boundary loops, every boundary vertex flat (k = 2). Needs n >= 3.
inline GridPatch cylinder(int n, int m) {
  return grid_patch(n, m, all_cells, [n](int i, int j, int, int) { return GridKey{i % n, j, 0}; });
}

/// [0, 2n]^2 without its upper right quarter: five boundary corners of index 1 and one of index 3.
inline GridPatch l_shape(int n) {
  return grid_patch(2 * n, 2 * n, [n](int i, int j) { return i < n || j < n; }, plain_key);
}

/// [0, n]^2 minus the cells [a, b)^2: an annulus, outer corners k = 1, the hole's corners k = 3.
inline GridPatch square_with_hole(int n, int a, int b) {
  return grid_patch(n, n, [a, b](int i, int j) { return !(a <= i && i < b && a <= j && j < b); },
                    plain_key);
}

/// [0, n]^2 cut along x = s from y = 0 to y = len: the points (s, j < len) are doubled (side 0
/// seen from the cells left of the cut, 1 from the right). The tip (s, len) is a boundary vertex
/// of index 4 (angle 2 pi), the two copies of (s, 0) have index 1.
inline GridPatch slit_square(int n, int s, int len) {
  return grid_patch(n, n, all_cells, [s, len](int i, int j, int ci, int) {
    return GridKey{i, j, i == s && j < len && ci >= s ? 1 : 0};
  });
}

/// The input without the listed faces.
inline IgmInput without_faces(const IgmInput& in, const std::set<int>& drop) {
  IgmInput out;
  out.num_vertices = in.num_vertices;
  for (int f = 0; f < static_cast<int>(in.faces.size()); ++f) {
    if (drop.count(f)) continue;
    add_tri(out, in.faces[f][0], in.faces[f][1], in.faces[f][2], in.corner_uv[3 * f],
            in.corner_uv[3 * f + 1], in.corner_uv[3 * f + 2]);
  }
  return out;
}

/// pillow(m) with the front cell (ci, cj) removed (its two triangles): a disk whose four
/// interior cones have index 2 and whose hole has four boundary corners of index 3.
inline IgmInput pillow_with_hole(int m, int ci, int cj) {
  const int cell = 4 * (ci + m * cj);  // pillow() adds front, front, back, back per cell
  return without_faces(pillow(m), {cell, cell + 1});
}

/// Disjoint union: b's vertex ids shifted by a.num_vertices.
inline IgmInput disjoint_union(const IgmInput& a, const IgmInput& b) {
  IgmInput out = a;
  const int shift = static_cast<int>(a.num_vertices);
  for (std::size_t f = 0; f < b.faces.size(); ++f)
    add_tri(out, b.faces[f][0] + shift, b.faces[f][1] + shift, b.faces[f][2] + shift,
            b.corner_uv[3 * f], b.corner_uv[3 * f + 1], b.corner_uv[3 * f + 2]);
  out.num_vertices = a.num_vertices + b.num_vertices;
  return out;
}

/// Moves vertex v to p in every corner.
inline void move_vertex(IgmInput& in, int v, const Uv& p) {
  for (std::size_t c = 0; c < in.corner_uv.size(); ++c)
    if (in.faces[c / 3][c % 3] == v) in.corner_uv[c] = p;
}

/// Quad grid of the kept cells of [0, n] x [0, m], vertex (i, j) = i + (n + 1) j, counter-clockwise;
/// `first` shifts every id (a second component after another grid).
template <class Keep>
QuadInput quad_grid(int n, int m, Keep keep, int first = 0) {
  QuadInput q;
  auto id = [&](int i, int j) { return first + i + (n + 1) * j; };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i)
      if (keep(i, j)) q.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  q.num_vertices = first + (n + 1) * (m + 1);
  return q;
}

}  // namespace certify_test
