#include "igm/topology/ring_bound.h"

#include <algorithm>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/core/union_find.h"

namespace igm {
namespace {

// Whether the faces with in_set[f] form a closed disk: every vertex's faces in the set form one
// fan (or all of its faces), V - E + F = 1, and the boundary edges form one cycle. O(F).
bool is_disk(const TriMesh& M, const std::vector<char>& in_set) {
  const int F = M.num_faces();
  long long faces = 0, boundary = 0;
  for (int f = 0; f < F; ++f) {
    if (!in_set[f]) continue;
    ++faces;
    for (int i = 0; i < 3; ++i) boundary += !in_set[TriMesh::face(M.twin(TriMesh::halfedge(f, i)))];
  }
  if (faces == 0) return false;
  const long long edges = (3 * faces + boundary) / 2;
  long long vertices = 0;
  UnionFind boundary_graph(static_cast<std::size_t>(M.num_vertices()));
  std::vector<int> on_boundary;
  for (int v = 0; v < M.num_vertices(); ++v) {
    const int h0 = M.vertex_halfedge(v);
    if (h0 < 0) continue;
    int entries = 0, inside = 0, h = h0;  // entries: a face in the set after one outside, going ccw
    bool boundary_here = false;
    do {
      const bool cur = in_set[TriMesh::face(h)];
      const bool before = in_set[TriMesh::face(M.twin(TriMesh::prev(h)))];  // the face cw of h's
      inside += cur;
      entries += cur && !before;
      if (cur && !in_set[TriMesh::face(M.twin(h))]) {
        boundary_graph.unite(v, M.target(h));
        boundary_here = true;
      }
      h = M.next_around_origin(h);
    } while (h != h0);
    if (inside == 0) continue;
    ++vertices;
    if (entries > 1) return false;  // two fans meet at v: not a surface with boundary
    if (boundary_here) on_boundary.push_back(v);
  }
  if (vertices - edges + faces != 1) return false;
  // Boundary cycles = components of the boundary graph (each boundary vertex has one fan, so two
  // boundary edges; every boundary vertex starts one, which the union above records).
  int cycles = 0;
  for (int v : on_boundary) cycles += boundary_graph.find(v) == v;
  return cycles == 1;
}

}  // namespace

void HopRings::start(int root) {
  ++starts_;
  level_ = 0;
  ring_.assign(1, root);
  mark_[root] = starts_;
}

bool HopRings::next() {
  next_.clear();
  for (int x : ring_) {
    const int h0 = mesh_.vertex_halfedge(x);
    int h = h0;
    do {  // valence steps
      const int w = mesh_.target(h);
      if (mark_[w] != starts_) mark_[w] = starts_, next_.push_back(w);
      h = mesh_.next_around_origin(h);
    } while (h != h0);
  }
  std::swap(ring_, next_);
  ++level_;
  return !ring_.empty();
}

RingBound ring_capacity_bound(const TriMesh& M, int root) {
  const int n = M.num_vertices();
  if (root < 0 || root >= n || M.vertex_halfedge(root) < 0)
    throw Error(ErrorKind::InvalidArgument,
                "ring bound: root vertex " + std::to_string(root) + " is not a vertex of the mesh (" +
                    std::to_string(n) + " vertices)",
                {root});
  RingBound out;
  const long long chi = static_cast<long long>(n) - M.num_edges() + M.num_faces();
  out.genus = static_cast<int>((2 - chi) / 2);
  std::vector<int> dist(n, -1);
  HopRings rings(M);
  rings.start(root);
  dist[root] = 0;
  while (rings.next()) {  // each vertex is in one ring
    out.max_level = rings.level();
    for (int w : rings.ring()) dist[w] = rings.level();
  }
  if (out.genus <= 0) return out;
  std::vector<long long> ring(out.max_level + 1, 0);
  for (int v = 0; v < n; ++v)
    if (dist[v] >= 0) ++ring[dist[v]];
  const long long ends = 4LL * out.genus;
  std::vector<int> face_level(M.num_faces());
  for (int f = 0; f < M.num_faces(); ++f) {
    const auto t = M.face_vertices(f);
    face_level[f] = std::min({dist[t[0]], dist[t[1]], dist[t[2]]});
  }
  std::vector<char> in_set(M.num_faces());
  for (int k = 1; k <= out.max_level; ++k) {  // at most max_level disk tests, O(F) each
    if (ring[k] >= ends) continue;
    for (int f = 0; f < M.num_faces(); ++f) in_set[f] = face_level[f] <= k;
    if (!is_disk(M, in_set)) continue;
    out.new_vertices += ends - ring[k];
    ++out.levels_counted;
  }
  return out;
}

}  // namespace igm
