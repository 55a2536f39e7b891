#include "igm/layout/surface_layout.h"

#include <algorithm>

#include "igm/core/union_find.h"

namespace igm {

namespace {

std::string str(std::int64_t x) { return std::to_string(x); }

std::string edge_name(int a, int b) { return str(a) + "-" + str(b); }

// "" or why location `v` is not a valid exact point (input vertices first).
std::string location_error(const SurfaceLayout& L, int v) {
  const SurfacePoint& p = L.locations[v];
  const int n = L.num_input_vertices;
  if (v < n) {
    if (p.v[0] != v || p.v[1] != -1 || p.v[2] != -1 || p.w[0] != 1)
      return "vertex " + str(v) + " is an input vertex but its location is not the input vertex itself";
    return "";
  }
  Rational sum = 0;
  bool unused = false;
  for (int i = 0; i < 3; ++i) {
    if (p.v[i] == -1) {
      unused = true;
      continue;
    }
    if (unused) return "vertex " + str(v) + "'s location has a used slot after an unused one";
    if (p.v[i] < 0 || p.v[i] >= n || (i > 0 && p.v[i] <= p.v[i - 1]) || sgn(p.w[i]) <= 0)
      return "vertex " + str(v) + "'s location is not a combination of distinct input vertices with positive weights";
    sum += p.w[i];
  }
  if (p.v[0] == -1) return "vertex " + str(v) + " has no location";
  if (sum != 1) return "vertex " + str(v) + "'s location weights do not sum to 1";
  return "";
}

// "" or the first index, size or location violation (so that the adjacency can be built).
std::string index_error(const SurfaceLayout& L) {
  const int nv = static_cast<int>(L.locations.size());
  const int nf = static_cast<int>(L.triangles.size());
  const int np = static_cast<int>(L.patches.size());
  const int na = static_cast<int>(L.arcs.size());
  if (static_cast<int>(L.positions.size()) != nv) return "positions and locations differ in size";
  if (static_cast<int>(L.triangle_patch.size()) != nf) return "triangle_patch does not have one entry per triangle";
  if (L.num_input_vertices < 0 || L.num_input_vertices > nv) return "num_input_vertices out of range";
  if (nf == 0) return "no triangles";
  std::vector<char> used(nv, 0);
  for (int t = 0; t < nf; ++t) {
    const auto& T = L.triangles[t];
    for (int v : T)
      if (v < 0 || v >= nv) return "triangle " + str(t) + " has a vertex out of range";
    if (T[0] == T[1] || T[1] == T[2] || T[2] == T[0]) return "triangle " + str(t) + " repeats a vertex";
    for (int v : T) used[v] = 1;
    if (L.triangle_patch[t] < 0 || L.triangle_patch[t] >= np)
      return "triangle " + str(t) + " has patch " + str(L.triangle_patch[t]) + ", out of range";
  }
  for (int v = 0; v < nv; ++v) {
    if (!used[v]) return "vertex " + str(v) + " is used by no triangle";
    std::string e = location_error(L, v);
    if (!e.empty()) return e;
  }
  for (int a = 0; a < na; ++a) {
    const LayoutArc& A = L.arcs[a];
    if (A.vertices.size() < 2) return "arc " + str(a) + " has fewer than two vertices";
    for (int v : A.vertices)
      if (v < 0 || v >= nv) return "arc " + str(a) + " has a vertex out of range";
    for (int s : {0, 1})
      if (A.patch[s] < -1 || A.patch[s] >= np) return "arc " + str(a) + " has a patch out of range";
    if (A.patch[0] < 0 && A.patch[1] < 0) return "arc " + str(a) + " has no patch on either side";
  }
  for (int p = 0; p < np; ++p)
    for (int k = 0; k < 4; ++k) {
      if (L.patches[p].sides[k].empty()) return "patch " + str(p) + "'s side " + str(k) + " has no arc";
      for (const ArcUse& u : L.patches[p].sides[k])
        if (u.arc < 0 || u.arc >= na) return "patch " + str(p) + "'s side " + str(k) + " uses an arc out of range";
    }
  return "";
}

}  // namespace

int LayoutAdjacency::halfedge(int a, int b) const {
  for (int k = star_begin[a]; k < star_begin[a + 1]; ++k)
    if (head[star[k]] == b) return star[k];
  return -1;
}

LayoutAdjacency layout_adjacency(const SurfaceLayout& L) {
  LayoutAdjacency A;
  const int nv = static_cast<int>(L.locations.size());
  const int nf = static_cast<int>(L.triangles.size());
  const int np = static_cast<int>(L.patches.size());
  A.star_begin.assign(nv + 1, 0);
  A.head.resize(3 * static_cast<std::size_t>(nf));
  for (int t = 0; t < nf; ++t)
    for (int i = 0; i < 3; ++i) {
      ++A.star_begin[L.triangles[t][i] + 1];
      A.head[3 * t + i] = L.triangles[t][(i + 1) % 3];
    }
  for (int v = 0; v < nv; ++v) A.star_begin[v + 1] += A.star_begin[v];
  A.star.resize(3 * static_cast<std::size_t>(nf));
  {
    std::vector<int> fill(A.star_begin.begin(), A.star_begin.end() - 1);
    for (int h = 0; h < 3 * nf; ++h) A.star[fill[L.triangles[h / 3][h % 3]]++] = h;  // ascending per vertex
  }
  A.twin.assign(3 * static_cast<std::size_t>(nf), -1);
  for (int h = 0; h < 3 * nf; ++h) {
    const int a = L.triangles[h / 3][h % 3], b = A.head[h];
    for (int k = A.star_begin[a]; k < A.star_begin[a + 1]; ++k)
      if (A.star[k] != h && A.head[A.star[k]] == b) {
        A.error = "the directed edge " + edge_name(a, b) + " lies in triangles " + str(h / 3) + " and " + str(A.star[k] / 3) +
                  " (not edge-manifold or not consistently oriented)";
        return A;
      }
    A.twin[h] = A.halfedge(b, a);
  }
  A.on_arc.assign(3 * static_cast<std::size_t>(nf), 0);
  for (std::size_t a = 0; a < L.arcs.size(); ++a) {
    const LayoutArc& arc = L.arcs[a];
    const auto& V = arc.vertices;
    // A simple path: no vertex twice, except that the two ends may be one node.
    std::vector<int> sorted(V.begin(), V.end() - (V.front() == V.back() && V.size() > 2 ? 1 : 0));
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      A.error = "arc " + str(static_cast<std::int64_t>(a)) + " passes a vertex twice";
      return A;
    }
    for (std::size_t s = 0; s + 1 < V.size(); ++s) {
      const int x = V[s], y = V[s + 1];
      const int f = A.halfedge(x, y), b = A.halfedge(y, x);
      const std::string where = "arc " + str(static_cast<std::int64_t>(a)) + "'s edge " + edge_name(x, y);
      if (f < 0 && b < 0) {
        A.error = where + " is no edge of the surface";
        return A;
      }
      if ((f >= 0 && A.on_arc[f]) || (b >= 0 && A.on_arc[b])) {
        A.error = where + " lies on another arc too (or twice on this one)";
        return A;
      }
      if ((arc.patch[0] < 0 && f >= 0) || (arc.patch[1] < 0 && b >= 0)) {
        A.error = where + " has a triangle on the side where the arc has no patch";
        return A;
      }
      if (f >= 0) A.on_arc[f] = 1;
      if (b >= 0) A.on_arc[b] = 1;
    }
  }
  A.patch_begin.assign(np + 1, 0);
  for (int t = 0; t < nf; ++t) ++A.patch_begin[L.triangle_patch[t] + 1];
  for (int p = 0; p < np; ++p) A.patch_begin[p + 1] += A.patch_begin[p];
  A.patch_triangles.resize(nf);
  A.slot.resize(nf);
  {
    std::vector<int> fill(A.patch_begin.begin(), A.patch_begin.end() - 1);
    for (int t = 0; t < nf; ++t) {
      const int p = L.triangle_patch[t];
      A.slot[t] = fill[p] - A.patch_begin[p];
      A.patch_triangles[fill[p]++] = t;
    }
  }
  return A;
}

PatchDisk patch_disk(const SurfaceLayout& L, const LayoutAdjacency& A, int p) {
  PatchDisk d;
  const std::string name = "patch " + str(p);
  d.triangles.assign(A.patch_triangles.begin() + A.patch_begin[p], A.patch_triangles.begin() + A.patch_begin[p + 1]);
  const int n = static_cast<int>(d.triangles.size());
  if (n == 0) {
    d.error = name + " has no triangle";
    return d;
  }
  // Wedges: corners 3k+i of the patch's triangle k joined across the edges on no arc.
  UnionFind corners(3 * static_cast<std::size_t>(n)), pieces(n);
  for (int k = 0; k < n; ++k) {
    const int t = d.triangles[k];
    for (int i = 0; i < 3; ++i) {
      const int h = 3 * t + i;
      if (A.on_arc[h]) continue;
      const int a = L.triangles[t][i], b = L.triangles[t][(i + 1) % 3];
      const int w = A.twin[h];
      if (w < 0) {
        d.error = "edge " + edge_name(a, b) + " of " + name + " lies on the surface's boundary but on no arc";
        return d;
      }
      const int t2 = w / 3, j = w % 3;  // w runs b -> a: corner j is b, corner j + 1 is a
      if (L.triangle_patch[t2] != p) {
        d.error = "edge " + edge_name(a, b) + " lies on no arc but joins " + name + " (triangle " + str(t) + ") and patch " +
                  str(L.triangle_patch[t2]) + " (triangle " + str(t2) + ")";
        return d;
      }
      const int k2 = A.slot[t2];
      corners.unite(3 * k + i, 3 * k2 + (j + 1) % 3);
      corners.unite(3 * k + (i + 1) % 3, 3 * k2 + j);
      pieces.unite(k, k2);
    }
  }
  std::vector<int> local_of_root(3 * static_cast<std::size_t>(n), -1);
  d.local_triangles.resize(n);
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i) {
      int& id = local_of_root[corners.find(3 * k + i)];
      if (id < 0) {
        id = static_cast<int>(d.vertex.size());
        d.vertex.push_back(L.triangles[d.triangles[k]][i]);
      }
      d.local_triangles[k][i] = id;
    }
  for (int k = 1; k < n; ++k)
    if (pieces.find(k) != pieces.find(0)) {
      d.error = name + " is not connected across its edges on no arc (triangles " + str(d.triangles[0]) + " and " +
                str(d.triangles[k]) + ")";
      return d;
    }
  // Boundary edges of the cut patch: the half-edges on arcs (the others are interior, above).
  std::vector<int> out(d.vertex.size(), -1);
  std::int64_t boundary_edges = 0;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i) {
      if (!A.on_arc[3 * d.triangles[k] + i]) continue;
      ++boundary_edges;
      int& o = out[d.local_triangles[k][i]];
      if (o >= 0) {
        d.error = name + " cut along its arcs has two boundary edges leaving one wedge at vertex " +
                  str(L.triangles[d.triangles[k]][i]);
        return d;
      }
      o = d.local_triangles[k][(i + 1) % 3];
    }
  const std::int64_t euler = static_cast<std::int64_t>(d.vertex.size()) - (3 * std::int64_t(n) + boundary_edges) / 2 + n;
  if (euler != 1) {
    d.error = name + " cut along its arcs has Euler characteristic " + str(euler) + ", not 1 (not a disk)";
    return d;
  }
  // The sides, one closed chain of distinct boundary half-edges covering them all.
  std::vector<char> walked(3 * static_cast<std::size_t>(n), 0);
  int first = -1, end = -1;
  std::int64_t walked_edges = 0;
  for (int side = 0; side < 4; ++side) {
    d.corner[side] = static_cast<int>(d.boundary.size());
    for (const ArcUse& u : L.patches[p].sides[side]) {
      const LayoutArc& arc = L.arcs[u.arc];
      const std::string use = name + "'s side " + str(side) + " (arc " + str(u.arc) + (u.forward ? " forward)" : " backward)");
      if (arc.patch[u.forward ? 0 : 1] != p) {
        d.error = use + ": the arc has patch " + str(arc.patch[u.forward ? 0 : 1]) + " on that side";
        return d;
      }
      const std::size_t m = arc.vertices.size();
      for (std::size_t s = 0; s + 1 < m; ++s) {
        const int x = u.forward ? arc.vertices[s] : arc.vertices[m - 1 - s];
        const int y = u.forward ? arc.vertices[s + 1] : arc.vertices[m - 2 - s];
        const int h = A.halfedge(x, y);
        if (h < 0 || L.triangle_patch[h / 3] != p) {
          d.error = use + ": no triangle of the patch on the left of edge " + edge_name(x, y);
          return d;
        }
        const int k = A.slot[h / 3], i = h % 3;
        if (walked[3 * k + i]) {
          d.error = use + " passes edge " + edge_name(x, y) + " a second time";
          return d;
        }
        walked[3 * k + i] = 1;
        const int a = d.local_triangles[k][i], b = d.local_triangles[k][(i + 1) % 3];
        if (end >= 0 && a != end) {
          d.error = use + " does not continue the boundary where the previous arc use ended (at vertex " + str(x) + ")";
          return d;
        }
        if (first < 0) first = a;
        d.boundary.push_back(a);
        end = b;
        ++walked_edges;
      }
    }
  }
  if (end != first) {
    d.error = name + "'s sides do not close into a loop";
    return d;
  }
  if (walked_edges != boundary_edges) {
    d.error = name + " cut along its arcs has " + str(boundary_edges) + " boundary edges, its sides run along " +
              str(walked_edges);
    return d;
  }
  return d;
}

std::string check_surface_layout(const SurfaceLayout& L) {
  std::string e = index_error(L);
  if (!e.empty()) return e;
  const LayoutAdjacency A = layout_adjacency(L);
  if (!A.error.empty()) return A.error;
  for (int p = 0; p < static_cast<int>(L.patches.size()); ++p) {
    PatchDisk d = patch_disk(L, A, p);
    if (!d.error.empty()) return d.error;
  }
  const int na = static_cast<int>(L.arcs.size());
  std::vector<int> forward(na, 0), backward(na, 0);
  for (const LayoutPatch& P : L.patches)
    for (const auto& side : P.sides)
      for (const ArcUse& u : side) ++(u.forward ? forward : backward)[u.arc];
  for (int a = 0; a < na; ++a)
    for (int s : {0, 1}) {
      const int uses = s == 0 ? forward[a] : backward[a], want = L.arcs[a].patch[s] >= 0 ? 1 : 0;
      if (uses != want)
        return "arc " + str(a) + " is used " + str(uses) + " times " + (s == 0 ? "forward" : "backward") + ", expected " +
               str(want) + " (by its " + (s == 0 ? "left" : "right") + " patch " + str(L.arcs[a].patch[s]) + ")";
    }
  return "";
}

}  // namespace igm
