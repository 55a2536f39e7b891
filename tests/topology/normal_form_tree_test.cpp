// Tests of what the normal form's two constructions share (src/topology/normal_form_tree.cpp,
// internal to the topology stage): the chords between wall vertices, the copy with every chord
// split, and the splits made again on the surface for the edges a search used on the copy.
// Everything is checked against brute force over the mesh's edges.
#include <doctest/doctest.h>

#include <set>
#include <utility>
#include <vector>

#include "../../src/topology/normal_form.h"
#include "generated_mesh.h"

using namespace igm;
using namespace igm::topology_internal;

namespace {

bool has_edge(const TriMesh& M, int a, int b) { return M.find_halfedge(a, b) >= 0; }

// V - E + F of a closed mesh.
long euler(const TriMesh& M) { return long(M.num_vertices()) - M.num_edges() + M.num_faces(); }

// Walls: every third vertex, so that many edges join two of them.
bool wall(int v) { return v % 3 == 0; }

}  // namespace

TEST_CASE("the chords are the edges between wall vertices but the skipped ones, sorted, and the copy splits each at its midpoint") {
  for (std::uint64_t seed : {1u, 2u}) {
    const ValidMesh in = igm_test::generated_mesh(3, 1500, seed);
    const TriMesh& M = in.mesh;
    const int nv = M.num_vertices();
    // Skip the edges whose lower end is even: sorted_chords must leave exactly those out.
    auto skip = [](int a, int b, int) { return std::min(a, b) % 2 == 0; };
    const auto chords = sorted_chords(M, wall, skip);
    std::set<std::pair<int, int>> brute;
    for (int h = 0; h < M.num_halfedges(); ++h) {
      const int a = M.origin(h), b = M.target(h);
      if (a < b && wall(a) && wall(b) && a % 2 != 0) brute.insert({a, b});
    }
    REQUIRE(!brute.empty());
    CHECK(std::set<std::pair<int, int>>(chords.begin(), chords.end()) == brute);
    for (std::size_t k = 1; k < chords.size(); ++k) CHECK(chords[k - 1] < chords[k]);

    std::vector<int> mid;
    std::vector<Vec3d> pos_copy;
    const TriMesh copy = split_copy(M, in.positions, chords, mid, pos_copy);
    CHECK(copy.check_invariants().empty());
    CHECK(euler(copy) == euler(M));
    REQUIRE(copy.num_vertices() == nv + static_cast<int>(chords.size()));
    REQUIRE(pos_copy.size() == static_cast<std::size_t>(copy.num_vertices()));
    for (std::size_t k = 0; k < chords.size(); ++k) {
      const auto [a, b] = chords[k];
      CHECK(mid[k] == nv + static_cast<int>(k));  // midpoints in chord order
      CHECK(has_edge(copy, a, mid[k]));
      CHECK(has_edge(copy, mid[k], b));
      CHECK(!has_edge(copy, a, b));
      CHECK(pos_copy[mid[k]].x == (in.positions[a].x + in.positions[b].x) / 2);
    }
    // The edges of the copy between two surface vertices are the surface's edges but the chords.
    for (int h = 0; h < copy.num_halfedges(); ++h) {
      const int a = copy.origin(h), b = copy.target(h);
      if (a < nv && b < nv) CHECK((has_edge(M, a, b) && !brute.count({std::min(a, b), std::max(a, b)})));
    }
  }
}

TEST_CASE("split_like_copy splits on the surface only what the used edges of the copy need, at exact midpoints") {
  const ValidMesh in = igm_test::generated_mesh(2, 1200, 5);
  const TriMesh& M = in.mesh;
  const int nv = M.num_vertices();
  const auto chords = sorted_chords(M, wall, [](int, int, int) { return false; });
  std::vector<int> mid;
  std::vector<Vec3d> pos_copy;
  const TriMesh copy = split_copy(M, in.positions, chords, mid, pos_copy);
  REQUIRE(chords.size() > 40);

  // Used: for every 10th chord, an edge of the copy from its midpoint to a neighbour that is not
  // an end of the chord: another chord's midpoint where its faces have one, else the vertex
  // opposite the chord.
  std::vector<std::pair<int, int>> used;
  int to_midpoints = 0;
  for (std::size_t k = 0; k < chords.size(); k += 10) {
    const int m = mid[k], h0 = copy.vertex_halfedge(m);
    int h = h0, pick = -1;
    do {
      const int y = copy.target(h);
      if (y != chords[k].first && y != chords[k].second && (pick < 0 || y >= nv)) pick = y;
      h = copy.next_around_origin(h);
    } while (h != h0);
    REQUIRE(pick >= 0);
    used.push_back({m, pick});
    to_midpoints += pick >= nv;
  }
  REQUIRE(to_midpoints > 0);
  REQUIRE(to_midpoints < static_cast<int>(used.size()));

  RefinedSurface rs;
  rs.mesh = M;
  rs.num_input_vertices = nv;
  rs.input_positions = in.positions;
  int splits = 0;
  const std::vector<int> to = split_like_copy(rs, chords, mid, copy.num_vertices(), used, splits);
  CHECK(rs.mesh.check_invariants().empty());
  CHECK(euler(rs.mesh) == euler(M));
  REQUIRE(to.size() == static_cast<std::size_t>(copy.num_vertices()));
  for (int v = 0; v < nv; ++v) CHECK(to[v] == v);
  int mapped = 0;
  for (std::size_t k = 0; k < chords.size(); ++k) {
    const auto [a, b] = chords[k];
    const int s = to[mid[k]];
    if (s < 0) {
      CHECK(has_edge(rs.mesh, a, b));  // not split: the chord is still an edge
      continue;
    }
    ++mapped;
    CHECK(s >= nv);
    CHECK(has_edge(rs.mesh, a, s));
    CHECK(has_edge(rs.mesh, s, b));
    const SurfacePoint p = rs.point(s);  // the exact midpoint of two input vertices
    CHECK(p.v[0] == a);
    CHECK(p.v[1] == b);
    CHECK(p.v[2] == -1);
    CHECK(p.w[0] == make_rational(1, 2));
    CHECK(p.w[1] == make_rational(1, 2));
  }
  CHECK(splits == mapped);
  CHECK(rs.mesh.num_vertices() == nv + splits);
  // Every used edge exists on the surface, and fewer chords were split than the copy splits.
  for (const auto& [p, q] : used) {
    REQUIRE(to[p] >= 0);
    REQUIRE(to[q] >= 0);
    CHECK(has_edge(rs.mesh, to[p], to[q]));
  }
  CHECK(splits < static_cast<int>(chords.size()));
}
