// Tests of the ring-capacity lower bound: recounted independently (explicit vertex and edge sets,
// boundary walked), never above what a cut adds, positive where the rings are small, typed errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <deque>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "igm/core/error.h"
#include "igm/mesh/validate.h"
#include "igm/topology/cut_to_canonical_disk.h"
#include "igm/topology/ring_bound.h"
#include "generated_mesh.h"
#include "test_data.h"

using namespace igm;

namespace {

// Hop distances from root by BFS over an explicit adjacency (-1: unreached).
std::vector<int> hop_distances(const std::vector<std::set<int>>& adj, int root) {
  std::vector<int> d(adj.size(), -1);
  d[root] = 0;
  std::deque<int> q{root};
  while (!q.empty()) {  // each vertex enters once
    const int u = q.front();
    q.pop_front();
    for (int w : adj[u])
      if (d[w] < 0) d[w] = d[u] + 1, q.push_back(w);
  }
  return d;
}

// The bound recounted from the triangle list alone: hop distances by BFS over an edge set, each D_k
// as a set of triangles, a disk iff V - E + F = 1, every vertex's triangles in D_k are joined
// through shared edges around it into one fan, and the boundary edges form one closed walk.
long long recount(const std::vector<std::array<int, 3>>& tris, int nv, int root) {
  std::vector<std::set<int>> adj(nv);
  for (const auto& t : tris)
    for (int i = 0; i < 3; ++i) adj[t[i]].insert(t[(i + 1) % 3]), adj[t[(i + 1) % 3]].insert(t[i]);
  const std::vector<int> d = hop_distances(adj, root);
  const long long edges_total = static_cast<long long>(tris.size()) * 3 / 2;
  const long long genus = (2 - (nv - edges_total + static_cast<long long>(tris.size()))) / 2;
  const int top = *std::max_element(d.begin(), d.end());
  long long bound = 0;
  for (int k = 1; k <= top; ++k) {
    const long long ring = std::count(d.begin(), d.end(), k);
    if (ring >= 4 * genus) continue;
    std::vector<std::array<int, 3>> disk;
    for (const auto& t : tris)
      if (std::min({d[t[0]], d[t[1]], d[t[2]]}) <= k) disk.push_back(t);
    std::map<std::pair<int, int>, int> edge_use;  // undirected edge -> faces of D_k on it
    std::set<int> verts;
    for (const auto& t : disk)
      for (int i = 0; i < 3; ++i) {
        const int a = t[i], b = t[(i + 1) % 3];
        ++edge_use[{std::min(a, b), std::max(a, b)}];
        verts.insert(a);
      }
    if (static_cast<long long>(verts.size()) - static_cast<long long>(edge_use.size()) + static_cast<long long>(disk.size()) != 1)
      continue;
    // one fan per vertex: the triangles at v, joined when they share an edge at v, are connected
    bool fans = true;
    for (int v : verts) {
      std::vector<std::array<int, 3>> at;
      for (const auto& t : disk)
        if (t[0] == v || t[1] == v || t[2] == v) at.push_back(t);
      std::vector<int> comp(at.size());
      for (std::size_t i = 0; i < at.size(); ++i) comp[i] = static_cast<int>(i);
      for (int pass = 0; pass < static_cast<int>(at.size()); ++pass)  // label propagation: <= |at| passes
        for (std::size_t i = 0; i < at.size(); ++i)
          for (std::size_t j = 0; j < at.size(); ++j) {
            int shared = 0;
            for (int x : at[i])
              if (x != v && std::find(at[j].begin(), at[j].end(), x) != at[j].end()) ++shared;
            if (i != j && shared > 0) comp[i] = comp[j] = std::min(comp[i], comp[j]);
          }
      fans &= std::all_of(comp.begin(), comp.end(), [&](int c) { return c == comp[0]; });
    }
    if (!fans) continue;
    // boundary edges form one closed walk
    std::map<int, std::vector<int>> bnb;
    std::size_t bcount = 0;
    for (const auto& [e, uses] : edge_use)
      if (uses == 1) bnb[e.first].push_back(e.second), bnb[e.second].push_back(e.first), ++bcount;
    if (bcount == 0) continue;
    std::size_t walked = 0;
    const int start = bnb.begin()->first;
    int prev = -1, cur = start;
    do {
      const auto& nb = bnb[cur];
      if (nb.size() != 2) break;
      const int next = nb[0] != prev ? nb[0] : nb[1];
      prev = cur, cur = next, ++walked;
    } while (cur != start && walked <= bcount);
    if (cur != start || walked != bcount) continue;
    bound += 4 * genus - ring;
  }
  return bound;
}

std::vector<std::array<int, 3>> triangles(const TriMesh& M) {
  std::vector<std::array<int, 3>> t;
  for (int f = 0; f < M.num_faces(); ++f) t.push_back(M.face_vertices(f));
  return t;
}

}  // namespace

TEST_CASE("ring bound: the library's count equals an independent recount") {
  int positive = 0;
  for (auto [genus, faces] : {std::pair{3, 600}, std::pair{6, 1200}, std::pair{10, 2000}, std::pair{2, 300}}) {
    const ValidMesh v = igm_test::generated_mesh(genus, faces, 5);
    const auto tris = triangles(v.mesh);
    for (int root = 0; root < v.mesh.num_vertices(); root += 37) {
      const RingBound b = ring_capacity_bound(v.mesh, root);
      CHECK(b.genus == genus);
      CHECK(b.new_vertices == recount(tris, v.mesh.num_vertices(), root));
      positive += b.new_vertices > 0;
    }
  }
  CHECK(positive > 0);  // the comparison also covers non-zero bounds
}

TEST_CASE("ring bound: no cut adds fewer vertices than the bound at its root") {
  int positive = 0;
  auto check = [&](const ValidMesh& v, bool normal_form) {
    CutOptions o;
    o.normal_form = normal_form;
    const CutResult r = cut_to_canonical_disk(v.mesh, v.positions, o);
    const RingBound b = ring_capacity_bound(v.mesh, r.root);
    CAPTURE(normal_form);
    CAPTURE(r.root);
    CHECK(b.genus == r.genus);
    CHECK(r.surface.mesh.num_vertices() - v.mesh.num_vertices() >= b.new_vertices);
    positive += b.new_vertices > 0;
  };
  for (auto [genus, faces] : {std::pair{3, 2000}, std::pair{6, 2000}, std::pair{10, 2000}, std::pair{10, 20000}}) {
    const ValidMesh v = igm_test::generated_mesh(genus, faces, 1);
    check(v, false);
    check(v, true);
  }
  CHECK(positive >= 6);  // generated g >= 6 meshes have small first rings: the check is not 0 >= 0
  auto dir_opt = igm_test::data_dir();
  if (!dir_opt) {
    MESSAGE("shared meshes skipped: shared test data not found (set IGM_DATA_DIR)");
    return;
  }
  for (const char* name : {"helmet", "elephant", "anchor", "couplingdown"}) {
    CAPTURE(name);
    const ValidMesh v = load_mesh(*dir_opt / "meshes" / "clean" / (std::string(name) + ".off"));
    check(v, false);
  }
}

TEST_CASE("ring bound: couplingdown's first rings are too small for its 36 loop ends") {
  IGM_REQUIRE_DATA(dir);
  const ValidMesh v = load_mesh(dir / "meshes" / "clean" / "couplingdown.off");
  const auto tris = triangles(v.mesh);
  long long best = -1;
  for (int root = 0; root < v.mesh.num_vertices(); ++root) {
    const long long b = ring_capacity_bound(v.mesh, root).new_vertices;
    if (best < 0 || b < best) best = b;
    if (root % 97 == 0) CHECK(b == recount(tris, v.mesh.num_vertices(), root));
  }
  // every root needs new vertices: no cut of couplingdown can stay at its input size
  CHECK(best > 0);
  MESSAGE("couplingdown: at least " << best << " new vertices at any root");
}

TEST_CASE("ring bound: genus 0 gives 0, a root out of range is a typed error naming it") {
  const ValidMesh sphere = igm_test::generated_mesh(0, 400, 2);
  const RingBound b = ring_capacity_bound(sphere.mesh, 0);
  CHECK(b.genus == 0);
  CHECK(b.new_vertices == 0);
  CHECK(b.max_level > 0);
  const ValidMesh torus = igm_test::generated_mesh(1, 400, 2);
  for (int bad : {-1, torus.mesh.num_vertices(), 1 << 30}) {
    CAPTURE(bad);
    try {
      ring_capacity_bound(torus.mesh, bad);
      FAIL("no error for a bad root");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::InvalidArgument);
      REQUIRE(e.elements().size() == 1);
      CHECK(e.elements()[0] == bad);
    }
  }
}

TEST_CASE("hop rings: each ring holds the vertices at that hop distance, from root after root") {
  // One HopRings object started at many roots in turn (its marks are kept between starts), against
  // a fresh BFS over an explicit edge set per root; a start that stops after two rings must not
  // leave marks that hide vertices from the next.
  for (const auto& [g, faces] : {std::pair{0, 200}, std::pair{2, 600}, std::pair{5, 1500}}) {
    const ValidMesh in = igm_test::generated_mesh(g, faces, 7);
    const TriMesh& M = in.mesh;
    const int nv = M.num_vertices();
    std::vector<std::set<int>> adj(nv);
    for (const auto& t : triangles(M))
      for (int i = 0; i < 3; ++i) adj[t[i]].insert(t[(i + 1) % 3]), adj[t[(i + 1) % 3]].insert(t[i]);
    HopRings rings(M);
    for (int root = 0; root < nv; root += 7) {
      CAPTURE(g);
      CAPTURE(root);
      const std::vector<int> d = hop_distances(adj, root);
      rings.start(root);
      REQUIRE(rings.ring() == std::vector<int>{root});
      std::vector<int> seen(nv, -1);
      seen[root] = 0;
      const bool stop_early = root % 2 == 1;
      while (rings.next()) {
        CHECK(rings.level() >= 1);
        for (int v : rings.ring()) {
          CHECK(seen[v] == -1);  // each vertex in one ring
          seen[v] = rings.level();
        }
        if (stop_early && rings.level() == 2) break;
      }
      for (int v = 0; v < nv; ++v)
        if (!stop_early || d[v] <= 2) CHECK(seen[v] == d[v]);
      if (!stop_early) CHECK(rings.ring().empty());
    }
  }
}
