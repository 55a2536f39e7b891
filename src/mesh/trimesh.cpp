#include "igm/mesh/trimesh.h"

#include <algorithm>
#include <string>

#include "igm/core/error.h"

namespace igm {

TriMesh TriMesh::from_triangles(int num_vertices, const std::vector<std::array<int, 3>>& triangles,
                                bool allow_boundary) {
  TriMesh m;
  const std::size_t nh = 3 * triangles.size();
  if (nh > static_cast<std::size_t>(INT32_MAX))
    throw Error(ErrorKind::TooLarge, "too many faces for 32-bit half-edge indices");
  m.origin_.resize(nh);
  m.twin_.assign(nh, -1);
  m.out_.assign(num_vertices, -1);
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      int v = triangles[f][i];
      if (v < 0 || v >= num_vertices)
        throw Error(ErrorKind::IndexOutOfRange, "face " + std::to_string(f) + " uses vertex " + std::to_string(v),
                    {static_cast<std::int64_t>(f)});
      m.origin_[3 * f + i] = v;
      m.out_[v] = static_cast<int>(3 * f + i);
    }
  // Pair half-edges by sorting (min, max, h): each undirected edge must appear exactly twice,
  // once in each direction. A counting sort by min (h ascending within each vertex), then each
  // vertex's bucket by (max, h): O(nh + sum of b log b) for buckets of b <= 2 x valence, not
  // O(nh log nh).
  struct Key {
    int a, b, h;
  };
  std::vector<int> start(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (std::size_t h = 0; h < nh; ++h)
    ++start[std::min(m.origin_[h], m.origin_[next(static_cast<int>(h))]) + 1];
  for (int v = 0; v < num_vertices; ++v) start[v + 1] += start[v];
  std::vector<Key> keys(nh);
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t h = 0; h < nh; ++h) {
      const int a = m.origin_[h], b = m.origin_[next(static_cast<int>(h))];
      keys[fill[std::min(a, b)]++] = {std::min(a, b), std::max(a, b), static_cast<int>(h)};
    }
  }
  for (int v = 0; v < num_vertices; ++v)
    std::sort(keys.begin() + start[v], keys.begin() + start[v + 1],
              [](const Key& x, const Key& y) { return x.b != y.b ? x.b < y.b : x.h < y.h; });
  for (std::size_t i = 0; i < nh;) {
    std::size_t j = i;
    while (j < nh && keys[j].a == keys[i].a && keys[j].b == keys[i].b) ++j;
    auto edge_name = [&] { return "edge (" + std::to_string(keys[i].a) + ", " + std::to_string(keys[i].b) + ")"; };
    if (j - i == 1 && allow_boundary) {  // a boundary half-edge: no twin; its origin's first corner
      m.out_[m.origin_[keys[i].h]] = keys[i].h;
      i = j;
      continue;
    }
    if (j - i == 1)
      throw Error(ErrorKind::Boundary, edge_name() + " has one face", {keys[i].h / 3});
    if (j - i > 2) {
      std::vector<std::int64_t> faces;
      for (std::size_t k = i; k < j; ++k) faces.push_back(keys[k].h / 3);
      throw Error(ErrorKind::NonManifoldEdge, edge_name() + " has " + std::to_string(j - i) + " faces", faces);
    }
    int h0 = keys[i].h, h1 = keys[i + 1].h;
    if (m.origin_[h0] == m.origin_[h1])
      throw Error(ErrorKind::NonManifoldEdge, edge_name() + ": its two faces have the same orientation",
                  {h0 / 3, h1 / 3});
    m.link(h0, h1);
    i = j;
  }
  return m;
}

TriMesh TriMesh::from_halfedges(int num_vertices, std::vector<int> origin, std::vector<int> twin) {
  const std::size_t nh = origin.size();
  auto broken = [](const std::string& what, std::size_t h) {
    return Error(ErrorKind::Internal, "half-edge arrays: " + what + " at half-edge " + std::to_string(h),
                 {static_cast<std::int64_t>(h)});
  };
  if (nh % 3 != 0 || twin.size() != nh)
    throw Error(ErrorKind::Internal, "half-edge arrays: " + std::to_string(nh) + " origins and " +
                                         std::to_string(twin.size()) + " twins do not make whole triangles");
  if (nh > static_cast<std::size_t>(INT32_MAX))
    throw Error(ErrorKind::TooLarge, "too many faces for 32-bit half-edge indices");
  TriMesh m;
  m.out_.assign(num_vertices, -1);
  for (std::size_t h = 0; h < nh; ++h) {
    const int v = origin[h];
    if (v < 0 || v >= num_vertices)
      throw Error(ErrorKind::IndexOutOfRange, "face " + std::to_string(h / 3) + " uses vertex " + std::to_string(v),
                  {static_cast<std::int64_t>(h / 3)});
    m.out_[v] = static_cast<int>(h);  // the last one, as from_triangles
  }
  // Each half-edge h = 3f + i against its twin t = 3g + j: t's twin is h, t starts where h ends
  // (at corner i + 1 of f), and h starts where t ends.
  for (std::size_t f3 = 0; f3 < nh; f3 += 3)
    for (std::size_t i = 0; i < 3; ++i) {
      const std::size_t h = f3 + i;
      const int t = twin[h];
      if (t < 0 || static_cast<std::size_t>(t) >= nh || static_cast<std::size_t>(t) == h) throw broken("no twin", h);
      const int g3 = t - t % 3, tn = t + 1 == g3 + 3 ? g3 : t + 1;
      if (twin[t] != static_cast<int>(h)) throw broken("twin not an involution", h);
      if (origin[t] != origin[i == 2 ? f3 : h + 1] || origin[tn] != origin[h])
        throw broken("twins not between the same vertices in opposite directions", h);
    }
  m.origin_ = std::move(origin);
  m.twin_ = std::move(twin);
  return m;
}

int TriMesh::valence(int v) const {
  int h0 = out_[v];
  if (h0 < 0) return 0;
  int n = 0, h = h0;
  do {
    ++n;
    h = next_around_origin(h);
  } while (h != h0 && n <= num_halfedges());
  return n;
}

int TriMesh::find_halfedge(int a, int b) const {
  int h0 = out_[a];
  if (h0 < 0) return -1;
  int h = h0, n = 0;
  do {
    if (target(h) == b) return h;
    h = next_around_origin(h);
  } while (h != h0 && ++n <= num_halfedges());
  return -1;
}

int TriMesh::split_edge(int h) {
  // Face f0 = (u, w, x) with h: u->w; face f1 = (w, u, y) with t = twin(h): w->u.
  const int t = twin_[h];
  const int hn = next(h), hp = prev(h), tn = next(t), tp = prev(t);
  const int w = origin_[hn], x = origin_[hp], y = origin_[tp];
  const int m = add_vertex();
  const int hn_twin = twin_[hn], tp_twin = twin_[tp];
  // f0 becomes (u, m, x); new face f2 = (m, w, x) with a: m->w, b: w->x, c: x->m.
  origin_[hn] = m;
  const int a = num_halfedges(), b = a + 1, c = a + 2;
  origin_.insert(origin_.end(), {m, w, x});
  // f1 becomes (m, u, y); new face f3 = (w, m, y) with d: w->m, e: m->y, g: y->w.
  origin_[t] = m;
  const int d = a + 3, e = a + 4, g = a + 5;
  origin_.insert(origin_.end(), {w, m, y});
  twin_.resize(origin_.size(), -1);
  link(b, hn_twin);
  link(c, hn);
  link(g, tp_twin);
  link(e, tp);
  link(h, t);
  link(a, d);
  out_[w] = b;
  out_[m] = a;
  (void)tn;
  return m;
}

int TriMesh::split_face(int f) {
  // f = (a, b, c) with h0: a->b, h1: b->c, h2: c->a.
  const int h0 = 3 * f, h1 = h0 + 1, h2 = h0 + 2;
  const int va = origin_[h0], vb = origin_[h1], vc = origin_[h2];
  const int m = add_vertex();
  const int h1_twin = twin_[h1], h2_twin = twin_[h2];
  // f becomes (a, b, m); f' = (b, c, m) with k0: b->c, k1: c->m, k2: m->b;
  // f'' = (c, a, m) with j0: c->a, j1: a->m, j2: m->c.
  origin_[h2] = m;
  const int k0 = num_halfedges(), k1 = k0 + 1, k2 = k0 + 2;
  origin_.insert(origin_.end(), {vb, vc, m});
  const int j0 = k0 + 3, j1 = k0 + 4, j2 = k0 + 5;
  origin_.insert(origin_.end(), {vc, va, m});
  twin_.resize(origin_.size(), -1);
  link(k0, h1_twin);
  link(j0, h2_twin);
  link(h1, k2);
  link(k1, j2);
  link(j1, h2);
  out_[vc] = k1;
  out_[m] = h2;
  return m;
}

std::string TriMesh::check_invariants() const {
  const int nh = num_halfedges();
  if (twin_.size() != origin_.size()) return "twin and origin arrays differ in size";
  for (int h = 0; h < nh; ++h) {
    int t = twin_[h];
    if (t < 0 || t >= nh) return "half-edge " + std::to_string(h) + " has no twin";
    if (t == h || twin_[t] != h) return "twin is not an involution at half-edge " + std::to_string(h);
    if (origin_[t] != target(h) || target(t) != origin_[h])
      return "twin of half-edge " + std::to_string(h) + " does not run backwards";
    if (origin_[h] < 0 || origin_[h] >= num_vertices()) return "half-edge " + std::to_string(h) + " has a bad origin";
  }
  std::vector<int> fan_size(num_vertices(), 0);
  for (int v = 0; v < num_vertices(); ++v) {
    int h0 = out_[v];
    if (h0 < 0) continue;
    if (h0 >= nh || origin_[h0] != v) return "vertex " + std::to_string(v) + " has a half-edge that does not leave it";
    int h = h0;
    do {
      ++fan_size[v];
      h = next_around_origin(h);
      if (fan_size[v] > nh) return "fan of vertex " + std::to_string(v) + " does not close";
    } while (h != h0);
  }
  std::vector<int> count(num_vertices(), 0);
  for (int h = 0; h < nh; ++h) ++count[origin_[h]];
  for (int v = 0; v < num_vertices(); ++v)
    if (count[v] != fan_size[v])
      return "vertex " + std::to_string(v) + " has " + std::to_string(count[v]) + " half-edges but its fan has " +
             std::to_string(fan_size[v]) + " (non-manifold vertex)";
  return {};
}

}  // namespace igm
