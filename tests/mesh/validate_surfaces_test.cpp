#include "igm/mesh/validate_surfaces.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "igm/core/error.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/generate.h"
#include "random_mesh.h"
#include "test_data.h"

using namespace igm;

namespace {

using Faces = std::vector<std::vector<std::int64_t>>;

PolygonSoup make_soup(int num_vertices, const Faces& faces) {
  PolygonSoup s;
  for (int i = 0; i < num_vertices; ++i)
    s.positions.push_back({double(i % 5), double(i / 5), double(i % 3)});
  for (const auto& f : faces) s.add_face(f.begin(), f.end());
  return s;
}

SurfaceOptions split_options() {
  SurfaceOptions o;
  o.split_nonmanifold = true;
  return o;
}

// The error validate_surfaces throws (Internal when it throws nothing).
Error error_of(const PolygonSoup& s, const SurfaceOptions& o = {}) {
  try {
    validate_surfaces(s, o);
  } catch (const Error& e) {
    return e;
  }
  return Error(ErrorKind::Internal, "nothing thrown");
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Independent check of one component: every directed edge once, boundary half-edges (no reverse)
// are exactly the loops' edges, each vertex used and with one fan (faces around it joined
// through its edges), genus from V - E + F. Cost O(F log F).
void check_component(const SurfaceComponent& c) {
  const int V = static_cast<int>(c.positions.size());
  REQUIRE(c.input_vertex.size() == c.positions.size());
  REQUIRE(c.input_face.size() == c.triangles.size());
  std::map<std::pair<int, int>, int> directed;  // (a, b) -> triangle
  std::vector<int> used(static_cast<std::size_t>(V), 0);
  for (std::size_t t = 0; t < c.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int a = c.triangles[t][i], b = c.triangles[t][(i + 1) % 3];
      REQUIRE(a >= 0);
      REQUIRE(a < V);
      CHECK(a != b);
      CHECK(directed.emplace(std::make_pair(a, b), static_cast<int>(t)).second);
      used[static_cast<std::size_t>(a)] = 1;
    }
  CHECK(std::count(used.begin(), used.end(), 1) == V);
  std::set<std::pair<int, int>> boundary, loop_edges;
  for (const auto& [e, t] : directed)
    if (!directed.count({e.second, e.first})) boundary.insert(e);
  for (const auto& loop : c.boundary_loops) {
    CHECK(loop.size() >= 3);
    CHECK(*std::min_element(loop.begin(), loop.end()) == loop[0]);
    for (std::size_t i = 0; i < loop.size(); ++i)
      loop_edges.insert({loop[i], loop[(i + 1) % loop.size()]});
  }
  CHECK(boundary == loop_edges);
  for (std::size_t l = 1; l < c.boundary_loops.size(); ++l)
    CHECK(c.boundary_loops[l - 1][0] < c.boundary_loops[l][0]);
  // Fans: join the corners (t, v) of triangles sharing an edge (v, x) around v.
  std::map<std::pair<int, int>, std::pair<int, int>> parent;  // corner -> parent corner
  std::function<std::pair<int, int>(std::pair<int, int>)> find = [&](std::pair<int, int> x) {
    auto it = parent.find(x);
    if (it == parent.end() || it->second == x) return x;
    return it->second = find(it->second);
  };
  for (const auto& [e, t] : directed) {
    const auto r = directed.find({e.second, e.first});
    if (r == directed.end()) continue;
    parent[find({t, e.first})] = find({r->second, e.first});  // both corners at e.first
  }
  std::map<int, std::set<std::pair<int, int>>> fans;
  for (std::size_t t = 0; t < c.triangles.size(); ++t)
    for (int v : c.triangles[t]) fans[v].insert(find({static_cast<int>(t), v}));
  for (const auto& [v, roots] : fans) CHECK_MESSAGE(roots.size() == 1, "vertex " << v);
  const std::int64_t E = static_cast<std::int64_t>(directed.size() + boundary.size()) / 2;
  const std::int64_t chi = V - E + static_cast<std::int64_t>(c.triangles.size());
  CHECK(c.euler_characteristic == chi);
  CHECK(2 * c.genus == 2 - chi - static_cast<std::int64_t>(c.boundary_loops.size()));
  CHECK(c.genus >= 0);
}

std::size_t loop_edges(const SurfaceSet& s) {
  std::size_t n = 0;
  for (const auto& c : s.components)
    for (const auto& l : c.boundary_loops) n += l.size();
  return n;
}

}  // namespace

TEST_CASE("a single triangle is a disk: genus 0, one loop along its half-edges") {
  const SurfaceSet s = validate_surfaces(make_soup(3, {{0, 1, 2}}));
  REQUIRE(s.components.size() == 1);
  const SurfaceComponent& c = s.components[0];
  check_component(c);
  CHECK(c.triangles == std::vector<std::array<int, 3>>{{0, 1, 2}});
  CHECK(c.boundary_loops == std::vector<std::vector<int>>{{0, 1, 2}});
  CHECK(c.euler_characteristic == 1);
  CHECK(c.genus == 0);
  CHECK(s.warnings.empty());
  // Reversed input: the loop follows the input's direction.
  const SurfaceSet r = validate_surfaces(make_soup(3, {{0, 2, 1}}));
  CHECK(r.components.at(0).boundary_loops == std::vector<std::vector<int>>{{0, 2, 1}});
  // A disk cannot be a ValidMesh; not allowing boundary rejects it like validate().
  const Error e = error_of(make_soup(3, {{0, 1, 2}}), {ValidateOptions{}, false, true, false});
  CHECK(e.kind() == ErrorKind::Boundary);
  CHECK(e.elements() == std::vector<std::int64_t>{0});
  CHECK_THROWS_AS(to_valid_mesh(c), Error);
}

TEST_CASE("a triangulated annulus: two loops, the outer along, the inner against the faces") {
  // Outer square 0..3 counter-clockwise, inner square 4..7; quad i is (o_i, o_i+1, in_i+1, in_i).
  Faces faces;
  for (int i = 0; i < 4; ++i) {
    faces.push_back({i, (i + 1) % 4, 4 + (i + 1) % 4});
    faces.push_back({i, 4 + (i + 1) % 4, 4 + i});
  }
  const SurfaceSet s = validate_surfaces(make_soup(8, faces));
  REQUIRE(s.components.size() == 1);
  const SurfaceComponent& c = s.components[0];
  check_component(c);
  CHECK(c.boundary_loops == std::vector<std::vector<int>>{{0, 1, 2, 3}, {4, 7, 6, 5}});
  CHECK(c.euler_characteristic == 0);  // 8 - 16 + 8
  CHECK(c.genus == 0);
  CHECK(c.input_vertex == std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6, 7});
  const Error e = error_of(make_soup(8, faces), {ValidateOptions{}, false, true, false});
  CHECK(e.kind() == ErrorKind::Boundary);
  CHECK(e.elements() == std::vector<std::int64_t>{0, 7});  // the faces of edges 0 -> 1 and 4 -> 7
  CHECK(contains(e.what(), "(allow_boundary is off): 2 boundary loops (8 edges with one face)"));

  // Two faces flipped (their boundary edges then come last, first in the repaired face):
  // repaired with a warning, the same surface.
  Faces two = faces;
  for (int f : {0, 3}) std::swap(two[f][1], two[f][2]);
  const SurfaceSet r = validate_surfaces(make_soup(8, two));
  CHECK(r.components.at(0).triangles == c.triangles);
  CHECK(r.components.at(0).boundary_loops == c.boundary_loops);
  REQUIRE(r.warnings.size() == 1);
  CHECK(contains(r.warnings[0], "re-oriented 2 triangles"));
  // All faces flipped: the input's orientation wins, the loops run the other way.
  Faces all = faces;
  for (auto& f : all) std::swap(f[1], f[2]);
  const SurfaceSet a = validate_surfaces(make_soup(8, all));
  CHECK(a.components.at(0).boundary_loops ==
        std::vector<std::vector<int>>{{0, 3, 2, 1}, {4, 5, 6, 7}});
  CHECK(a.warnings.empty());
}

TEST_CASE("a Moebius strip is rejected as non-orientable, with or without splitting") {
  // Triangles (i, i+1, i+2) mod 5: every inner edge joins two faces of the same direction, an odd
  // cycle of them; the edges (i, i+2) form one boundary loop.
  Faces faces;
  for (int i = 0; i < 5; ++i) faces.push_back({i, (i + 1) % 5, (i + 2) % 5});
  for (const SurfaceOptions& o : {SurfaceOptions{}, split_options()}) {
    const Error e = error_of(make_soup(5, faces), o);
    CHECK(e.kind() == ErrorKind::NonOrientable);
    // Edges in key order: (3, 4) closes the odd cycle T3-T4-T0-T1-T2.
    CHECK(e.elements() == std::vector<std::int64_t>{2, 3});
    CHECK(contains(
        e.what(),
        "not orientable: the component of face 2 (orientation contradiction at edge (3, 4)"));
  }
}

TEST_CASE("two triangles sharing a vertex: non-manifold, split into two disks") {
  const PolygonSoup soup = make_soup(5, {{0, 1, 2}, {0, 3, 4}});
  const Error e = error_of(soup);
  CHECK(e.kind() == ErrorKind::NonManifoldVertex);
  CHECK(e.elements() == std::vector<std::int64_t>{0});
  CHECK(contains(e.what(), "vertex 0 (2 fans)"));
  const SurfaceSet s = validate_surfaces(soup, split_options());
  REQUIRE(s.components.size() == 2);
  for (const SurfaceComponent& c : s.components) {
    check_component(c);
    CHECK(c.triangles == std::vector<std::array<int, 3>>{{0, 1, 2}});
    CHECK(c.boundary_loops == std::vector<std::vector<int>>{{0, 1, 2}});
    CHECK(c.genus == 0);
  }
  CHECK(s.components[0].input_vertex == std::vector<std::int64_t>{0, 1, 2});
  CHECK(s.components[1].input_vertex == std::vector<std::int64_t>{0, 3, 4});
  CHECK(s.components[1].input_face == std::vector<std::int64_t>{1});
  CHECK(s.warnings == std::vector<std::string>{"cut 1 non-manifold vertex into one copy per fan (2 "
                                               "vertices in all): vertex 0 (2 fans)"});
  // Splitting allowed but components not: the split result is two components.
  SurfaceOptions one = split_options();
  one.allow_components = false;
  const Error c = error_of(soup, one);
  CHECK(c.kind() == ErrorKind::SeveralComponents);
  CHECK(c.elements() == std::vector<std::int64_t>{0, 1});
}

TEST_CASE("an edge with three faces: one pair of opposite faces, the third cut off") {
  // Faces 0 and 2 run 0 -> 1, face 1 runs 1 -> 0: face 0 pairs with face 1, face 2 is cut off.
  const PolygonSoup soup = make_soup(5, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const Error e = error_of(soup);
  CHECK(e.kind() == ErrorKind::NonManifoldEdge);
  CHECK(e.elements() == std::vector<std::int64_t>{0, 1, 2});
  const SurfaceSet s = validate_surfaces(soup, split_options());
  REQUIRE(s.components.size() == 2);
  const SurfaceComponent &a = s.components[0], &b = s.components[1];
  check_component(a);
  check_component(b);
  CHECK(a.input_vertex == std::vector<std::int64_t>{0, 1, 2, 3});
  CHECK(a.triangles == std::vector<std::array<int, 3>>{{0, 1, 2}, {1, 0, 3}});
  CHECK(a.boundary_loops == std::vector<std::vector<int>>{{0, 3, 1, 2}});
  CHECK(a.euler_characteristic == 1);  // 4 - 5 + 2
  CHECK(b.input_vertex == std::vector<std::int64_t>{0, 1, 4});
  CHECK(b.input_face == std::vector<std::int64_t>{2});
  REQUIRE(s.warnings.size() == 2);
  CHECK(s.warnings[0] ==
        "cut 1 edge with more than two faces (opposite faces paired in input order, the others "
        "left as boundary "
        "edges): edge (0, 1) of faces 0, 1, 2 into 1 pair and 1 boundary edge");
  CHECK(s.warnings[1] ==
        "cut 2 non-manifold vertices into one copy per fan (4 vertices in all): vertex 0 (2 fans); "
        "vertex 1 (2 fans)");
}

TEST_CASE("two tetrahedra sharing an edge: split into two spheres, unless paired crosswise") {
  // Tetrahedron A on 0..3, B on 0, 1, 4, 5; edge (0, 1) has four faces.
  const Faces a = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}},
              b = {{0, 4, 1}, {0, 1, 5}, {0, 5, 4}, {1, 4, 5}};
  Faces faces = a;
  faces.insert(faces.end(), b.begin(), b.end());
  CHECK(error_of(make_soup(6, faces)).kind() == ErrorKind::NonManifoldEdge);
  const SurfaceSet s = validate_surfaces(make_soup(6, faces), split_options());
  REQUIRE(s.components.size() == 2);
  for (const SurfaceComponent& c : s.components) {
    check_component(c);
    CHECK(c.boundary_loops.empty());
    CHECK(c.genus == 0);
    CHECK(to_valid_mesh(c).mesh.check_invariants() == "");
  }
  CHECK(s.components[1].input_vertex == std::vector<std::int64_t>{0, 1, 4, 5});
  CHECK(contains(s.warnings.at(0),
                 "edge (0, 1) of faces 0, 1, 4, 5 into 2 pairs and 0 boundary edges"));
  // Order A1, B0, B1, A0, ...: the pairs (A1, B0) and (B1, A0) join the two tetrahedra into one
  // fan at 0 and at 1, so both pieces of the edge run between the same two vertices.
  const Faces cross = {a[1], b[0], b[1], a[0], a[2], a[3], b[2], b[3]};
  const Error e = error_of(make_soup(6, cross), split_options());
  CHECK(e.kind() == ErrorKind::NonManifoldEdge);
  CHECK(e.elements() == std::vector<std::int64_t>{0, 1, 2, 3});
  CHECK(contains(e.what(), "cannot cut edge (0, 1)"));
}

TEST_CASE("components: ordered by their smallest input face, closed ones become ValidMeshes") {
  // A triangle (face 0), a tetrahedron (faces 1..4 on vertices 3..6) and another triangle (face 5).
  Faces faces = {{7, 8, 9}, {3, 5, 4}, {3, 4, 6}, {3, 6, 5}, {4, 5, 6}, {0, 1, 2}};
  const SurfaceSet s = validate_surfaces(make_soup(10, faces));
  REQUIRE(s.components.size() == 3);
  CHECK(s.components[0].input_face == std::vector<std::int64_t>{0});
  CHECK(s.components[0].input_vertex == std::vector<std::int64_t>{7, 8, 9});
  CHECK(s.components[1].input_face == std::vector<std::int64_t>{1, 2, 3, 4});
  CHECK(s.components[2].input_face == std::vector<std::int64_t>{5});
  CHECK(s.components[1].boundary_loops.empty());
  for (const auto& c : s.components) check_component(c);
  const ValidMesh m = to_valid_mesh(s.components[1], {"w"});
  CHECK(m.mesh.num_faces() == 4);
  CHECK(m.genus == 0);
  CHECK(m.input_vertex == std::vector<std::int64_t>{3, 4, 5, 6});
  CHECK(m.warnings == std::vector<std::string>{"w"});
  const Error e = error_of(make_soup(10, faces), {ValidateOptions{}, true, false, false});
  CHECK(e.kind() == ErrorKind::SeveralComponents);
  CHECK(e.elements() == std::vector<std::int64_t>{0, 1, 5});
}

TEST_CASE("fatal element problems are validate()'s") {
  CHECK(error_of(PolygonSoup{}).kind() == ErrorKind::Empty);
  CHECK(error_of(make_soup(4, {})).kind() == ErrorKind::NoFaces);
  CHECK(error_of(make_soup(3, {{0, 1, 3}})).kind() == ErrorKind::IndexOutOfRange);
  CHECK(error_of(make_soup(3, {{0, 1, 1}})).kind() == ErrorKind::RepeatedVertex);
  CHECK(error_of(make_soup(3, {{0, 1}})).kind() == ErrorKind::InvalidArgument);
  PolygonSoup nan = make_soup(3, {{0, 1, 2}});
  nan.positions[1].y = std::numeric_limits<double>::quiet_NaN();
  const Error e = error_of(nan, split_options());
  CHECK(e.kind() == ErrorKind::NonFinite);
  CHECK(e.elements() == std::vector<std::int64_t>{1});
  // Unreferenced vertices: dropped with a warning, or (kept) a component without faces.
  const PolygonSoup extra = make_soup(5, {{0, 1, 3}});
  const SurfaceSet s = validate_surfaces(extra);
  CHECK(s.components.at(0).input_vertex == std::vector<std::int64_t>{0, 1, 3});
  CHECK(s.warnings == std::vector<std::string>{"dropped 2 unreferenced vertices (2, 4)"});
  SurfaceOptions keep;
  keep.base.drop_unreferenced = false;
  const Error k = error_of(extra, keep);
  CHECK(k.kind() == ErrorKind::SeveralComponents);
  CHECK(k.elements() == std::vector<std::int64_t>{2, 4});
  // Inconsistent orientation with the repair off stays fatal.
  SurfaceOptions strict;
  strict.base.repair_orientation = false;
  CHECK(error_of(make_soup(4, {{0, 1, 2}, {0, 1, 3}}), strict).kind() ==
        ErrorKind::NonManifoldEdge);
}

TEST_CASE("a closed connected soup gives validate()'s mesh") {
  PolygonSoup soup = generate_closed_mesh({.genus = 3, .faces = 900, .seed = 4});
  for (std::size_t f = 0; f < soup.num_faces();
       f += 7)  // some faces flipped: repaired the same way
    std::swap(soup.corners[soup.face_begin[f] + 1], soup.corners[soup.face_begin[f] + 2]);
  const ValidMesh want = validate(soup);
  SurfaceOptions closed;
  closed.allow_boundary = closed.allow_components = false;
  const SurfaceSet s = validate_surfaces(soup, closed);
  REQUIRE(s.components.size() == 1);
  const ValidMesh got = to_valid_mesh(s.components[0], s.warnings);
  CHECK(got.mesh.origins() == want.mesh.origins());
  CHECK(got.mesh.twins() == want.mesh.twins());
  CHECK(got.input_vertex == want.input_vertex);
  CHECK(got.input_face == want.input_face);
  CHECK(got.warnings == want.warnings);
  CHECK(got.genus == 3);
  REQUIRE(got.positions.size() == want.positions.size());
  for (std::size_t v = 0; v < got.positions.size(); ++v)
    CHECK(got.positions[v].x == want.positions[v].x);
}

TEST_CASE("random open meshes: one surface of the generated genus and loop count") {
  for (int i = 0; i < 12; ++i) {
    igm_test::RandomMeshSpec spec;
    spec.genus = i % 4;
    spec.faces = 1500 + 300 * i;
    spec.seed = static_cast<std::uint64_t>(100 + i);
    spec.boundaries = 1 + i % 6;
    spec.edge_splits = 40 * (i % 3);
    spec.face_splits = 30 * (i % 2);
    spec.geometry =
        static_cast<igm_test::Geometry>(i % static_cast<int>(igm_test::Geometry::Count));
    CAPTURE(igm_test::describe(spec));
    PolygonSoup soup = igm_test::random_mesh(spec);
    const SurfaceSet s = validate_surfaces(soup);
    REQUIRE(s.components.size() == 1);
    check_component(s.components[0]);
    CHECK(s.components[0].genus == spec.genus);
    CHECK(s.components[0].boundary_loops.size() == static_cast<std::size_t>(spec.boundaries));
    CHECK(s.components[0].triangles.size() == soup.num_faces());
    CHECK(s.warnings.empty());
    // Every third face flipped: repaired back to the same triangles and loops.
    for (std::size_t f = 0; f < soup.num_faces(); f += 3)
      std::swap(soup.corners[3 * f + 1], soup.corners[3 * f + 2]);
    const SurfaceSet r = validate_surfaces(soup);
    REQUIRE(r.components.size() == 1);
    CHECK(r.components[0].triangles == s.components[0].triangles);
    CHECK(r.components[0].boundary_loops == s.components[0].boundary_loops);
    CHECK(r.warnings.size() == 1);
  }
  igm_test::RandomMeshSpec open;
  open.boundaries = 2;
  CHECK_THROWS_AS(igm_test::random_closed_mesh(open), Error);
}

TEST_CASE("shared open meshes: one surface each, genus and loops as documented") {
  IGM_REQUIRE_DATA(dir);
  struct Case {
    const char* file;
    std::size_t vertices, faces, loops;
  };
  const Case cases[] = {
      {"open_cube.off", 8, 10, 1},
      {"corner_with_hole.off", 16, 13, 1},
      {"triangular_hole.off", 6, 6, 2},
      {"nefertiti.off", 299, 562, 1},
      {"mesh_with_border.off", 548, 1014, 1},
      {"patch-01.off", 735, 1396, 1},
      {"plane.off", 841, 1600, 1},
      {"cylinder.off", 1200, 2262, 1},
      {"head.off", 1487, 2918, 3},
      {"three_peaks.off", 1907, 3671, 1},
      {"mushroom.off", 2337, 4608, 1},
      {"lion-head.off", 8356, 16674, 1},
      {"blade.off", 8231, 16222, 2},
      {"ChineseDragon-10kv.off", 10000, 19994, 2},
      {"mannequin-devil.off", 12977, 25888, 1},
  };
  for (const Case& c : cases) {
    CAPTURE(c.file);
    const SurfaceSet s = validate_surfaces(read_soup(dir / "meshes" / "open" / c.file));
    REQUIRE(s.components.size() == 1);
    const SurfaceComponent& m = s.components[0];
    if (m.triangles.size() < 5000) check_component(m);
    CHECK(m.genus == 0);
    CHECK(m.boundary_loops.size() == c.loops);
    CHECK(m.positions.size() == c.vertices);
    CHECK(static_cast<std::size_t>(m.input_face.back() + 1) == c.faces);
  }
}

TEST_CASE("shared invalid meshes: components, loops and genus, non-manifold ones only when split") {
  IGM_REQUIRE_DATA(dir);
  const auto m = dir / "meshes" / "invalid";
  {
    const SurfaceSet s = validate_surfaces(read_soup(m / "blobby_3cc.off"));
    CHECK(s.components.size() == 3);
    std::size_t loops = 0;
    for (const auto& c : s.components) {
      check_component(c);
      loops += c.boundary_loops.size();
    }
    CHECK(loops == 4);
    CHECK(loop_edges(s) == 219);  // igm info: 219 edges with one face
  }
  {
    const SurfaceSet s = validate_surfaces(read_soup(m / "knot2.off"));
    REQUIRE(s.components.size() == 2);
    for (const auto& c : s.components) {
      CHECK(c.genus == 1);
      CHECK(c.boundary_loops.empty());
      CHECK(to_valid_mesh(c).genus == 1);
    }
  }
  {
    const SurfaceSet s = validate_surfaces(read_soup(m / "degtri_sliding.off"));
    REQUIRE(s.components.size() == 1);
    check_component(s.components[0]);
    CHECK(s.components[0].boundary_loops.size() == 1);
  }
  {
    const SurfaceSet s = validate_surfaces(read_soup(m / "double-torus-3-holes.off"));
    REQUIRE(s.components.size() == 1);
    check_component(s.components[0]);
    CHECK(s.components[0].genus == 2);
    CHECK(s.components[0].boundary_loops.size() == 3);
  }
  CHECK(error_of(read_soup(m / "b9.ply"), split_options()).kind() == ErrorKind::NoFaces);
  // Cutting vertices keeps edges and faces: the components' Euler characteristics add up to
  // (V + the extra copies) - E + F of the input (E from inspect), the loops to its boundary edges.
  struct Split {
    const char* file;
    std::int64_t non_manifold, copies;
  };
  for (const Split& c : {Split{"pig.stl", 421, 864}, Split{"polygon_mesh.off", 2, 5}}) {
    CAPTURE(c.file);
    const PolygonSoup soup = read_soup(m / c.file);
    const Error e = error_of(soup);
    CHECK(e.kind() == ErrorKind::NonManifoldVertex);
    CHECK(e.elements().size() ==
          std::min<std::size_t>(100, static_cast<std::size_t>(c.non_manifold)));
    const SurfaceSet s = validate_surfaces(soup, split_options());
    CHECK(!s.components.empty());
    const MeshReport r = inspect(soup);
    std::int64_t chi = 0, vertices = 0;
    for (const auto& comp : s.components) {
      chi += comp.euler_characteristic;
      vertices += static_cast<std::int64_t>(comp.positions.size());
      if (comp.triangles.size() < 5000) check_component(comp);
    }
    CHECK(vertices == r.vertices + c.copies - c.non_manifold);
    CHECK(chi == vertices - r.edges + r.triangles);
    CHECK(static_cast<std::int64_t>(loop_edges(s)) == r.boundary_edges);
    const std::string cut = "cut " + std::to_string(c.non_manifold) +
                            " non-manifold vertices into one copy per fan (" +
                            std::to_string(c.copies) + " vertices in all): ";
    CHECK(std::count_if(s.warnings.begin(), s.warnings.end(), [&](const std::string& w) {
            return w.rfind(cut, 0) == 0 &&
                   std::count(w.begin(), w.end(), ';') == c.non_manifold - 1;
          }) == 1);  // names every cut vertex
  }
}

TEST_CASE("split_nonmanifold_hint: what cutting a non-manifold input apart would give, or what would still be wrong") {
  // Two triangles sharing a vertex: cut apart, two disks.
  const PolygonSoup bow = make_soup(5, {{0, 1, 2}, {0, 3, 4}});
  CHECK(split_nonmanifold_hint(bow, {}, error_of(bow), "--split") ==
        "--split cuts its non-manifold vertices and edges apart: 2 surfaces (2 of genus 0 with 1 boundary loop), "
        "all valid input");
  // A Moebius strip touching a triangle at vertex 0: cut apart, still not orientable.
  Faces faces;
  for (int i = 0; i < 5; ++i) faces.push_back({i, (i + 1) % 5, (i + 2) % 5});
  faces.push_back({0, 5, 6});
  const PolygonSoup moebius = make_soup(7, faces);
  const Error e = error_of(moebius);
  REQUIRE(e.kind() == ErrorKind::NonManifoldVertex);
  const std::string hint = split_nonmanifold_hint(moebius, {}, e, "split=True");
  CHECK(contains(hint, "split=True would cut its non-manifold vertices and edges apart, but then: non_orientable: "));
  // Nothing to say: the split already asked for, or another problem.
  CHECK(split_nonmanifold_hint(bow, split_options(), e, "--split").empty());
  SurfaceOptions closed;
  closed.allow_boundary = false;
  const PolygonSoup disk = make_soup(3, {{0, 1, 2}});
  CHECK(split_nonmanifold_hint(disk, closed, error_of(disk, closed), "--split").empty());
}
