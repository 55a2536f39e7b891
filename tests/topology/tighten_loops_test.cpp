// Tests of loop tightening: the tightened surface is re-checked as an exact refinement of the input
// (tests/support/refinement_check.h, from the raw input triangles), the loops from their raw vertex
// lists, and the order of the loop ends around the root against the untightened cut.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "igm/core/error.h"
#include "igm/exact/rational.h"
#include "igm/topology/cut_to_canonical_disk.h"
#include "igm/topology/tighten_loops.h"
#include "generated_mesh.h"
#include "loop_check.h"
#include "refinement_check.h"
#include "test_data.h"

using namespace igm;

namespace {

// The loop ends around the root, counter-clockwise from the end of loop 0's first edge: per end,
// (loop, 0 for its first edge, 1 for its last). Empty if an edge at the root is on two loops.
std::vector<std::pair<int, int>> ends_at_root(const TriMesh& M, const std::vector<std::vector<int>>& loops, int root) {
  std::vector<std::pair<int, int>> ends;
  const int h0 = M.vertex_halfedge(root);
  int h = h0;
  do {
    const int t = M.target(h);
    int found = 0;
    for (int i = 0; i < static_cast<int>(loops.size()); ++i) {
      if (loops[i][1] == t) ends.push_back({i, 0}), ++found;
      if (loops[i].back() == t) ends.push_back({i, 1}), ++found;
    }
    if (found > 1) return {};
    h = M.next_around_origin(h);
  } while (h != h0);
  const auto start = std::find(ends.begin(), ends.end(), std::pair{0, 0});
  if (start == ends.end()) return {};
  std::rotate(ends.begin(), start, ends.end());
  return ends;
}

// Tightens the untightened cut of `in` and checks everything the header promises; returns the
// number of vertices removed.
int check_tightening(const ValidMesh& in, bool normal_form) {
  CutOptions o;
  o.normal_form = normal_form;
  o.tighten = false;
  // The first basis: its bundles leave the tightening work to do. The congestion reweighting's
  // (cut_to_canonical_disk.h, step 1c) leave none on helmet, elephant and anchor.
  o.congestion_rounds = 0;
  const CutResult raw = cut_to_canonical_disk(in.mesh, in.positions, o);
  const int before = raw.surface.mesh.num_vertices();
  const auto ends_before = ends_at_root(raw.surface.mesh, raw.loops, raw.root);
  REQUIRE(!ends_before.empty());
  TightenedLoops t = tighten_loops(raw.surface, raw.loops, raw.root);
  // The dirty-vertex passes make exactly the moves of checking every vertex in every pass.
  const TightenedLoops reference = tighten_loops(raw.surface, raw.loops, raw.root, true);
  CHECK(t.loops == reference.loops);
  CHECK(t.surface.mesh.num_vertices() == reference.surface.mesh.num_vertices());
  CHECK(t.surface.mesh.num_faces() == reference.surface.mesh.num_faces());
  for (int f = 0; f < t.surface.mesh.num_faces() && f < reference.surface.mesh.num_faces(); ++f)
    if (t.surface.mesh.face_vertices(f) != reference.surface.mesh.face_vertices(f)) {
      CHECK_MESSAGE(false, "face " << f << " differs from the reference's");
      break;
    }
  CHECK(t.stats.collapsed == reference.stats.collapsed);
  CHECK(t.stats.shortcuts == reference.stats.shortcuts);
  CHECK(t.stats.pushes == reference.stats.pushes);
  CHECK(t.stats.passes == reference.stats.passes);
  const TriMesh& M = t.surface.mesh;
  CHECK(M.check_invariants() == "");
  CHECK(M.num_vertices() - M.num_edges() + M.num_faces() == 2 - 2 * raw.genus);
  CHECK(t.surface.num_input_vertices == in.mesh.num_vertices());
  CHECK(M.num_vertices() == before - t.stats.collapsed);
  CHECK(igm_test::refinement_violation(in, t.surface, true) == "");
  CHECK(igm_test::loop_violation(M, t.loops, raw.root, raw.genus) == "");
  CHECK(ends_at_root(M, t.loops, raw.root) == ends_before);  // the same system: same order, same word
  // A fixed point: tightening again changes nothing.
  const TightenedLoops again = tighten_loops(t.surface, t.loops, raw.root);
  CHECK(again.stats.collapsed == 0);
  CHECK(again.stats.shortcuts == 0);
  CHECK(again.loops == t.loops);
  return t.stats.collapsed;
}

}  // namespace

TEST_CASE("tightening generated cuts keeps an exact refinement, the loops' order and the word") {
  int removed = 0;
  for (int g : {1, 2, 3, 5, 10})
    for (unsigned seed : {1u, 2u})
      for (bool nf : {false, true}) {
        CAPTURE(g);
        CAPTURE(seed);
        CAPTURE(nf);
        removed += check_tightening(igm_test::generated_mesh(g, 400 * g, seed), nf);
      }
  CHECK(removed > 0);
  MESSAGE("generated meshes: " << removed << " vertices removed in all");
}

TEST_CASE("tightening the shared meshes removes crossing vertices and keeps everything else") {
  IGM_REQUIRE_DATA(dir);
  for (const std::string name : {"helmet", "elephant", "anchor", "couplingdown"})
    for (bool nf : {false, true}) {
      CAPTURE(name);
      CAPTURE(nf);
      const ValidMesh in = load_mesh(dir / "meshes" / "clean" / (name + ".off"));
      const int removed = check_tightening(in, nf);
      // Measured (without / with the normal form): helmet 5 / 15, elephant 60 / 55, anchor 15 / 72,
      // couplingdown 117 / 195.
      CHECK(removed > 0);
      MESSAGE(name << std::string(nf ? " (normal form)" : "") << ": " << removed << " vertices removed");
    }
}

TEST_CASE("bad loops given to the tightening are typed errors") {
  const ValidMesh in = igm_test::generated_mesh(1, 200, 1);
  CutOptions o;
  o.tighten = false;
  const CutResult raw = cut_to_canonical_disk(in.mesh, in.positions, o);
  auto loops = raw.loops;
  loops[1][0] = loops[1][1];  // not from the root
  CHECK_THROWS_AS(tighten_loops(raw.surface, loops, raw.root), Error);
  loops = raw.loops;
  loops[1].push_back(loops[0][1]);  // shares a vertex with loop 0
  CHECK_THROWS_AS(tighten_loops(raw.surface, loops, raw.root), Error);
}

TEST_CASE("straightening removes path vertices inside input faces, keeps the others, and stays an exact refinement") {
  const ValidMesh in = igm_test::generated_mesh(2, 400, 3);
  const int nin = in.mesh.num_vertices();
  RefinedSurface base;
  base.mesh = in.mesh;
  base.num_input_vertices = nin;
  base.input_positions = in.positions;
  const auto abc = base.mesh.face_vertices(0);
  const int a = abc[0], b = abc[1], c = abc[2];
  RefinedSurface rs = base;
  const int s = rs.split_face(0);  // inside the input face (a, b, c), joined to a, b and c

  // The path a - s - b: s goes into a (its first listed neighbour), the path runs a - b.
  StraightenedPaths st = straighten_paths(rs, {{a, s}, {s, b}}, {}, nin);
  CHECK(st.removed == 1);
  CHECK(st.to[s] == a);
  CHECK(st.to[a] == a);
  CHECK(st.surface.mesh.num_vertices() == nin);
  CHECK(st.surface.mesh.find_halfedge(a, b) >= 0);
  CHECK(igm_test::refinement_violation(in, st.surface, true) == "");

  // Not removed: a vertex asked to be kept, one below `first`, one with three path neighbours.
  CHECK(straighten_paths(rs, {{a, s}, {s, b}}, {s}, nin).removed == 0);
  CHECK(straighten_paths(rs, {{a, s}, {s, b}}, {}, s + 1).removed == 0);
  CHECK(straighten_paths(rs, {{a, s}, {s, b}, {s, c}}, {}, nin).removed == 0);

  // Not removed: a point on an input edge (where a path crosses it).
  RefinedSurface on_edge = base;
  const int m = on_edge.split_edge(on_edge.mesh.find_halfedge(a, b), make_rational(1, 3));
  CHECK(straighten_paths(on_edge, {{c, m}, {m, a}}, {}, nin).removed == 0);

  // Two face points, only the second on a path: the first keeps its id, the second goes.
  RefinedSurface two = base;
  const int s1 = two.split_face(0);
  const int f2 = TriMesh::face(two.mesh.twin(two.mesh.find_halfedge(b, a)));  // the face across a-b
  const auto uvw = two.mesh.face_vertices(f2);
  const int s2 = two.split_face(f2);
  StraightenedPaths st2 = straighten_paths(two, {{uvw[0], s2}, {s2, uvw[1]}}, {}, nin);
  CHECK(st2.removed == 1);
  CHECK(st2.to[s1] == s1);
  CHECK(st2.to[s2] == uvw[0]);
  CHECK(st2.surface.mesh.num_vertices() == nin + 1);
  CHECK(igm_test::refinement_violation(in, st2.surface, true) == "");

  // A collapse that would flatten a face is refused, and the other neighbour is tried: with the
  // input edge a-c split at m, s into a would make (a, c, m) flat; s goes into b.
  RefinedSurface flat = base;
  const int s3 = flat.split_face(0);
  flat.split_edge(flat.mesh.find_halfedge(a, c), make_rational(1, 2));
  StraightenedPaths st3 = straighten_paths(flat, {{a, s3}, {s3, b}}, {}, s3);
  CHECK(st3.removed == 1);
  CHECK(st3.to[s3] == b);
  CHECK(igm_test::refinement_violation(in, st3.surface, true) == "");

  // A path edge that is not an edge of the mesh is a typed error, not a silent skip.
  CHECK_THROWS_AS(straighten_paths(rs, {{a, s}, {s, nin + 7}}, {}, nin), Error);
}

TEST_CASE("straightening random paths through nested face points keeps an exact refinement and the paths' edges") {
  // Face points split again and again (each inside the one before), joined into vertex-disjoint
  // paths corner - p_k - ... - p_1 - corner; after the straightening every mapped path edge must be
  // an edge, and the surface an exact refinement of the input (re-checked from the raw triangles).
  std::mt19937 rng(21);
  for (int trial = 0; trial < 12; ++trial) {
    CAPTURE(trial);
    const ValidMesh in = igm_test::generated_mesh(1 + trial % 3, 300 + 40 * trial, 100 + trial);
    const int nin = in.mesh.num_vertices();
    RefinedSurface rs;
    rs.mesh = in.mesh;
    rs.num_input_vertices = nin;
    rs.input_positions = in.positions;
    std::vector<std::pair<int, int>> edges;
    std::vector<char> used(nin, 0);
    int paths = 0;
    for (int attempt = 0; attempt < 40 && paths < 6; ++attempt) {
      const int f = static_cast<int>(rng() % static_cast<unsigned>(in.mesh.num_faces()));
      const auto t = rs.mesh.face_vertices(f);
      if (std::any_of(t.begin(), t.end(), [&](int v) { return v >= nin || used[v]; })) continue;
      for (int v : t) used[v] = 1;
      // Nested points: each split of a face (corner a, corner b, previous point).
      const int a = t[0], b = t[1];
      int prev = rs.split_face(f);
      std::vector<int> chain{prev};
      const int depth = 1 + static_cast<int>(rng() % 4);
      for (int k = 1; k < depth; ++k) {
        int g = -1;
        for (int h = rs.mesh.vertex_halfedge(prev), h0 = h;;) {  // the face (prev, a, b)
          const auto u = rs.mesh.face_vertices(TriMesh::face(h));
          if (std::count(u.begin(), u.end(), a) && std::count(u.begin(), u.end(), b)) g = TriMesh::face(h);
          h = rs.mesh.next_around_origin(h);
          if (h == h0) break;
        }
        REQUIRE(g >= 0);
        prev = rs.split_face(g);
        chain.push_back(prev);
      }
      // The path a - p_last - ... - p_1 - b, every step an edge of the mesh.
      std::vector<int> path{a};
      for (auto it = chain.rbegin(); it != chain.rend(); ++it) path.push_back(*it);
      path.push_back(b);
      bool ok = true;
      for (std::size_t i = 0; i + 1 < path.size(); ++i) ok = ok && rs.mesh.find_halfedge(path[i], path[i + 1]) >= 0;
      if (!ok) continue;  // a nested point not adjacent to the one before: not a path
      for (std::size_t i = 0; i + 1 < path.size(); ++i) edges.push_back({path[i], path[i + 1]});
      ++paths;
    }
    REQUIRE(paths > 0);
    const int before = rs.mesh.num_vertices();
    const StraightenedPaths st = straighten_paths(rs, edges, {}, nin);
    CHECK(st.removed > 0);
    CHECK(st.surface.mesh.num_vertices() == before - st.removed);
    CHECK(igm_test::refinement_violation(in, st.surface, true) == "");
    for (const auto& [x, y] : edges)
      if (st.to[x] != st.to[y]) CHECK(st.surface.mesh.find_halfedge(st.to[x], st.to[y]) >= 0);
  }
}
