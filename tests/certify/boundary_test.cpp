// The certifier on open surfaces (boundary loops) and on meshes with several components:
// valid cases pass with hand-counted boundary indices, loops, genera and Poincare-Hopf sums;
// each mutation fails the right rule with the right witness; with the options off, every such
// mesh still fails exactly as before.
#include <doctest/doctest.h>

#include <algorithm>

#include "boundary_builders.h"
#include "certify/certify.h"

using namespace igm::certify;
using namespace certify_test;

namespace {

Options open_surfaces() {
  Options o;
  o.allow_boundary = true;
  return o;
}

Options open_components() {
  Options o = open_surfaces();
  o.allow_components = true;
  return o;
}

using Bins = std::map<std::int64_t, std::int64_t>;

// The patch with vertex v moved to p in every corner, certified as an open surface.
Report certify_moved(GridPatch s, int v, const Uv& p) {
  move_vertex(s.igm, v, p);
  return certify_igm(s.igm, open_surfaces());
}

// Expectations of a valid open IGM, all hand-counted.
struct OpenCase {
  std::int64_t V, E, F, boundary_edges, loops, genus;
  Bins interior, boundary;  // vertex_index_k, boundary_index_k
};

void check_valid_open(const IgmInput& in, const OpenCase& e) {
  const Report r = certify_igm(in, open_surfaces());
  INFO(to_json(r));
  REQUIRE(r.verdict == Verdict::Valid);
  CHECK(r.num_vertices == e.V);
  CHECK(r.num_edges == e.E);
  CHECK(r.num_faces == e.F);
  CHECK(r.num_boundary_edges == e.boundary_edges);
  REQUIRE(r.boundary_loops.has_value());
  CHECK(*r.boundary_loops == e.loops);
  REQUIRE(r.genus.has_value());
  CHECK(*r.genus == e.genus);
  const std::int64_t chi = e.V - e.E + e.F;
  CHECK(chi == 2 - 2 * e.genus - e.loops);
  REQUIRE(r.components.size() == 1);
  CHECK(r.components[0].boundary_loops == e.loops);
  CHECK(r.components[0].genus == e.genus);
  CHECK(r.components[0].poincare_hopf_sum == 4 * chi);
  CHECK(chk(r, 1).count("boundary_loops") == e.loops);
  CHECK(chk(r, 1).count("boundary_vertices") == e.boundary_edges);  // one loop vertex per edge
  const CheckResult& c3 = chk(r, 3);
  CHECK(c3.count("boundary_edges_checked") == e.boundary_edges);
  CHECK(c3.count("boundary_edges_off_isoline") == 0);
  CHECK(c3.count("rigid") == e.E - e.boundary_edges);
  const CheckResult& c4 = chk(r, 4);
  CHECK(c4.histogram == e.interior);
  CHECK(c4.boundary_histogram == e.boundary);
  CHECK(c4.count("boundary_vertices") == e.boundary_edges);
  CHECK(c4.count("boundary_corners") == e.boundary_edges - (e.boundary.count(2) ? e.boundary.at(2) : 0));
  CHECK(c4.count("poincare_hopf_checked") == 1);
  CHECK(c4.count("poincare_hopf_sum") == 4 * chi);
  CHECK(c4.count("poincare_hopf_expected") == 4 * chi);
  CHECK(c4.count("transport_inconsistent") == 0);
}

// The old behaviour: without allow_boundary a valid open IGM fails check 1 on its boundary edges,
// check 3 is incomplete (boundary edges are not interior) and its boundary vertices undetermined.
void check_fails_as_closed(const IgmInput& in, std::int64_t boundary_edges) {
  const Report r = certify_igm(in);
  INFO(to_json(r));
  CHECK(r.verdict == Verdict::Invalid);
  const CheckResult& c1 = chk(r, 1);
  CHECK(c1.status == Status::Fail);
  CHECK(c1.count("boundary_edges") == boundary_edges);
  CHECK(c1.offending >= boundary_edges);
  REQUIRE_FALSE(c1.witnesses.empty());
  CHECK(c1.witnesses[0].reason == "boundary edge (one face)");
  CHECK_FALSE(r.genus.has_value());
  CHECK(chk(r, 3).status == Status::Incomplete);
  CHECK(chk(r, 3).count("edges_not_interior") == boundary_edges);
  CHECK(chk(r, 3).count("boundary_edges_checked") == -1);  // no boundary counts without the option
  CHECK(chk(r, 4).status == Status::Incomplete);
  CHECK(chk(r, 4).count("vertices_undetermined") >= c1.count("boundary_vertices"));
  CHECK(chk(r, 4).count("poincare_hopf_checked") == 0);
  CHECK(chk(r, 4).boundary_histogram.empty());
}

}  // namespace

TEST_CASE("boundary valid: square disk [0,n]^2 has four boundary corners of index 1") {
  // V = (n+1)^2, E = 2n(n+1) + n^2, F = 2n^2, boundary 4n; interior (n-1)^2 vertices k = 4
  check_valid_open(square_disk(1).igm, {4, 5, 2, 4, 1, 0, {}, {{1, 4}}});
  check_valid_open(square_disk(3).igm, {16, 33, 18, 12, 1, 0, {{4, 4}}, {{1, 4}, {2, 8}}});
  check_fails_as_closed(square_disk(3).igm, 12);
}

TEST_CASE("boundary valid: cylinder [0,n] x [0,m], x periodic, is an annulus with two loops") {
  const IgmInput in = cylinder(4, 2).igm;
  // V = 4*3, E = 12 horizontal + 8 vertical + 8 diagonal, F = 16: chi = 0, genus 0, 2 loops
  check_valid_open(in, {12, 28, 16, 8, 2, 0, {{4, 4}}, {{2, 8}}});
  const Report r = certify_igm(in, open_surfaces());
  CHECK(chk(r, 3).histogram == Bins{{0, 20}});  // the wrap seams are translations by (4, 0)
  check_fails_as_closed(in, 8);
}

TEST_CASE("boundary valid: L-shape has five corners k = 1 and one concave corner k = 3") {
  const GridPatch l = l_shape(2);  // [0,4]^2 minus [2,4)^2: 12 cells
  check_valid_open(l.igm, {21, 44, 24, 16, 1, 0, {{4, 5}}, {{1, 5}, {2, 10}, {3, 1}}});
  const Report r = certify_igm(l.igm, open_surfaces());
  CHECK(r.check(4)->boundary_histogram.at(3) == 1);
  // the concave corner is (2, 2): its only k = 3 vertex; no witness anywhere
  for (const auto& c : r.checks) CHECK(c.witnesses.empty());
  check_fails_as_closed(l.igm, 16);
}

TEST_CASE("boundary valid: slit square, the slit's tip has boundary index 4 at an integer point") {
  const GridPatch s = slit_square(4, 2, 2);
  // 25 points, (2,0) and (2,1) doubled: V = 27; E = 56 + 2; F = 32; boundary 16 + 4 edges.
  // k = 1: four corners and both copies of (2,0); k = 4: the tip (2,2); 13 flat.
  check_valid_open(s.igm, {27, 58, 32, 20, 1, 0, {{4, 7}}, {{1, 6}, {2, 13}, {4, 1}}});
  check_fails_as_closed(s.igm, 20);
}

TEST_CASE("boundary valid: a disk with interior cones balanced by boundary corners") {
  // pillow (4 cones k = 2) with one front cell removed: the hole's four corners have k = 3;
  // sum = 4 * (4 - 2) + 4 * (2 - 3) = 4 = 4 chi. V = 20, E = 54 - 1, F = 36 - 2.
  const IgmInput hole = pillow_with_hole(3, 1, 1);
  check_valid_open(hole, {20, 53, 34, 4, 1, 0, {{2, 4}, {4, 12}}, {{3, 4}}});
  check_fails_as_closed(hole, 4);
  // three sides of the cube [0,2]^3 around (2,2,2): one interior cone k = 3 balanced by three
  // boundary corners k = 1. V = 27 - 9 + 1, E = 48 - 6, F = 24.
  const IgmInput corner = cube(2, 2 + 8 + 32);
  check_valid_open(corner, {19, 42, 24, 12, 1, 0, {{3, 1}, {4, 6}}, {{1, 3}, {2, 9}}});
  check_fails_as_closed(corner, 12);
  // the cube without its top: four cones k = 3, a flat rim
  check_valid_open(cube(2, 63 - 32), {25, 64, 40, 8, 1, 0, {{3, 4}, {4, 13}}, {{2, 8}}});
  check_fails_as_closed(cube(2, 63 - 32), 8);
  // the cube's four vertical sides: an annulus whose charts meet with rotations.
  // V = 26 - 2, E = 4 * 16 - 4 * 2, F = 4 * 8
  const IgmInput band = cube(2, 15);
  check_valid_open(band, {24, 56, 32, 16, 2, 0, {{4, 8}}, {{2, 16}}});
  const Report band_report = certify_igm(band, open_surfaces());
  const Bins& rotations = chk(band_report, 3).histogram;
  CHECK(rotations.count(1) + rotations.count(3) == 2);  // boundary fans cross rotated seams
  check_fails_as_closed(band, 16);
}

TEST_CASE("boundary valid: a torus with a square hole has genus 1 and one loop") {
  // torus(4) without cell (1,1): chi = 16 - 47 + 30 = -1 = 2 - 2*1 - 1
  const IgmInput in = without_faces(torus(4), {2 * 5, 2 * 5 + 1});
  check_valid_open(in, {16, 47, 30, 4, 1, 1, {{4, 12}}, {{3, 4}}});
  check_fails_as_closed(in, 4);
}

TEST_CASE("boundary: allow_boundary on closed meshes changes no verdict") {
  for (const IgmInput& in : {torus(4), cube(2), pillow(3)}) {
    const Report closed = certify_igm(in), open = certify_igm(in, open_surfaces());
    CHECK(closed.verdict == Verdict::Valid);
    CHECK(open.verdict == Verdict::Valid);
    CHECK(open.genus == closed.genus);
    CHECK(open.boundary_loops == std::optional<std::int64_t>(0));
    CHECK(chk(open, 4).count("boundary_vertices") == 0);
    CHECK(chk(open, 4).histogram == chk(closed, 4).histogram);
  }
}

TEST_CASE("components valid: each component judged on its own") {
  SUBCASE("a square disk and a cube") {
    const IgmInput in = disjoint_union(square_disk(2).igm, cube(1));
    const Report r = certify_igm(in, open_components());
    INFO(to_json(r));
    REQUIRE(r.verdict == Verdict::Valid);
    REQUIRE(r.components.size() == 2);
    const ComponentInfo &a = r.components[0], &b = r.components[1];
    CHECK(a.first_vertex == 0);
    CHECK(a.vertices == 9);
    CHECK(a.faces == 8);
    CHECK(a.boundary_loops == 1);
    CHECK(a.genus == 0);
    CHECK(a.euler_characteristic == 1);
    CHECK(a.poincare_hopf_sum == 4);
    CHECK(b.first_vertex == 9);
    CHECK(b.vertices == 8);
    CHECK(b.faces == 12);
    CHECK(b.boundary_loops == 0);
    CHECK(b.euler_characteristic == 2);
    CHECK(b.poincare_hopf_sum == 8);
    CHECK(*r.genus == 0);
    CHECK(*r.boundary_loops == 1);
    CHECK(chk(r, 4).count("poincare_hopf_sum") == 12);
    CHECK(chk(r, 4).count("poincare_hopf_components_checked") == 2);
    CHECK(chk(r, 4).count("poincare_hopf_components_failed") == 0);
    // either option alone is not enough
    Options only_boundary = open_surfaces();
    const Report rb = certify_igm(in, only_boundary);
    CHECK(rb.verdict == Verdict::Invalid);
    CHECK(chk(rb, 1).count("connected_components") == 2);
    CHECK(has_witness(chk(rb, 1), "vertex", 9));
    Options only_components;
    only_components.allow_components = true;
    const Report rc = certify_igm(in, only_components);
    CHECK(rc.verdict == Verdict::Invalid);
    CHECK(chk(rc, 1).count("boundary_edges") == 8);
  }
  SUBCASE("two tori: genus is the sum, one per component") {
    const IgmInput in = disjoint_union(torus(3), torus(4));
    Options o;
    o.allow_components = true;
    const Report r = certify_igm(in, o);
    INFO(to_json(r));
    REQUIRE(r.verdict == Verdict::Valid);
    CHECK(*r.genus == 2);
    REQUIRE(r.components.size() == 2);
    CHECK(r.components[1].first_vertex == 9);
    CHECK(r.components[0].genus == 1);
    CHECK(r.components[1].genus == 1);
    CHECK(r.components[1].vertices == 16);
    // the old behaviour without the option
    const Report old = certify_igm(in);
    CHECK(old.verdict == Verdict::Invalid);
    CHECK(chk(old, 1).witnesses.size() == 1);
    CHECK(chk(old, 1).witnesses[0].reason == "first vertex of another connected component");
    CHECK(chk(old, 4).count("poincare_hopf_checked") == 0);
  }
}

TEST_CASE("mutation: a boundary vertex moved off its isoline by 1/1000") {
  const GridPatch s = square_disk(3);
  const int v = s.id(1, 0);
  const Report r = certify_moved(s, v, uv(1, mpq_class(1, 1000)));
  INFO(to_json(r));
  CHECK(chk(r, 1).passed());
  CHECK(chk(r, 2).passed());
  const CheckResult& c3 = chk(r, 3);
  CHECK(c3.status == Status::Fail);
  CHECK(c3.count("non_rigid") == 0);  // moved in every corner: interior edges still rigid
  CHECK(c3.count("boundary_edges_off_isoline") == 2);
  CHECK(c3.offending == 2);
  CHECK(has_edge_witness(c3, s.id(0, 0), v));
  CHECK(has_edge_witness(c3, v, s.id(2, 0)));
  REQUIRE_FALSE(c3.witnesses.empty());
  const Witness& w = c3.witnesses[0];
  CHECK(w.reason == "boundary edge not on an integer isoline (u or v constant and integer)");
  CHECK((value(w, "uv_u") == "(1, 1/1000)" || value(w, "uv_v") == "(1, 1/1000)"));
  // the angles at its ends are not multiples of pi/2: undetermined, with witnesses
  const CheckResult& c4 = chk(r, 4);
  CHECK(c4.count("vertices_undetermined") == 3);
  for (int u : {s.id(0, 0), v, s.id(2, 0)}) {
    const Witness* x = find_witness(c4, "vertex", u);
    REQUIRE(x != nullptr);
    CHECK(x->reason == "boundary angle undetermined");
  }
  CHECK(value(*find_witness(c4, "vertex", v), "why") ==
        "outgoing boundary edge not parallel to an axis");
  CHECK(c4.count("poincare_hopf_checked") == 0);
  CHECK(c4.status == Status::Incomplete);
}

TEST_CASE("mutation: a boundary corner off the integer lattice") {
  SUBCASE("the slit's tip (k = 4) moved along the slit: every boundary edge still on x = 2") {
    const GridPatch s = slit_square(4, 2, 2);
    const int tip = s.id(2, 2);
    const Report r = certify_moved(s, tip, uv(2, mpq_class(5, 2)));
    INFO(to_json(r));
    CHECK(r.verdict == Verdict::Invalid);
    CHECK(chk(r, 2).passed());
    CHECK(chk(r, 3).passed());
    const CheckResult& c4 = chk(r, 4);
    CHECK(c4.status == Status::Fail);
    CHECK(c4.count("boundary_corners_off_integer") == 1);
    CHECK(c4.offending == 1);
    const Witness* w = find_witness(c4, "vertex", tip);
    REQUIRE(w != nullptr);
    CHECK(w->reason == "boundary corner (k != 2) not on an integer point");
    CHECK(value(*w, "k") == "4");
    CHECK(value(*w, "uv") == "(2, 5/2)");
    CHECK(c4.count("poincare_hopf_checked") == 1);  // still balanced: triangles all positive
  }
  SUBCASE("the left side of the square moved to x = 1/2: two corners k = 1 off the lattice") {
    GridPatch s = square_disk(3);
    for (int j = 0; j <= 3; ++j) move_vertex(s.igm, s.id(0, j), uv(mpq_class(1, 2), j));
    const Report r = certify_igm(s.igm, open_surfaces());
    INFO(to_json(r));
    CHECK(chk(r, 2).passed());
    CHECK(chk(r, 3).count("boundary_edges_off_isoline") == 3);  // on x = 1/2: not integer
    for (int j = 0; j < 3; ++j) CHECK(has_edge_witness(chk(r, 3), s.id(0, j), s.id(0, j + 1)));
    const CheckResult& c4 = chk(r, 4);
    CHECK(c4.count("boundary_corners_off_integer") == 2);
    CHECK(value(*find_witness(c4, "vertex", s.id(0, 0)), "uv") == "(1/2, 0)");
    CHECK(value(*find_witness(c4, "vertex", s.id(0, 3)), "uv") == "(1/2, 3)");
    CHECK(value(*find_witness(c4, "vertex", s.id(0, 3)), "k") == "1");
    // (0,1) and (0,2) are flat (k = 2): allowed off the lattice
    CHECK(find_witness(c4, "vertex", s.id(0, 1)) == nullptr);
    CHECK(c4.boundary_histogram == Bins{{1, 4}, {2, 8}});
  }
}

TEST_CASE("mutation: boundary vertices with index k <= 0") {
  // square_disk(2) with (1,0) moved along its isoline y = 0 to (3,0): both bottom edges stay on
  // y = 0, triangle (1,0)(2,0)(2,1) flips. By hand, the fan at (1,0) crosses -1 + 0 + 1 quadrant
  // boundaries (k = 0) and the corner (2,0), in the flipped triangle only, -1 (k = -1).
  const GridPatch s = square_disk(2);
  const Report r = certify_moved(s, s.id(1, 0), uv(3, 0));
  INFO(to_json(r));
  CHECK(chk(r, 2).count("flipped") == 1);
  CHECK(chk(r, 3).passed());
  const CheckResult& c4 = chk(r, 4);
  CHECK(c4.status == Status::Fail);
  CHECK(c4.count("boundary_nonpositive_index") == 2);
  const Witness* a = find_witness(c4, "vertex", s.id(1, 0));
  const Witness* b = find_witness(c4, "vertex", s.id(2, 0));
  REQUIRE(a != nullptr);
  REQUIRE(b != nullptr);
  CHECK(a->reason == "boundary index k <= 0 (angle not positive)");
  CHECK(value(*a, "k") == "0");
  CHECK(value(*b, "k") == "-1");
  // one flipped triangle: the sum exceeds 4 chi by 4
  const Witness* m = nullptr;
  for (const auto& w : c4.witnesses)
    if (w.kind == "mesh") m = &w;
  REQUIRE(m != nullptr);
  CHECK(value(*m, "sum_index_defects") == "8");
  CHECK(value(*m, "4_chi") == "4");
}

TEST_CASE("mutation: Poincare-Hopf fails in one component, the other passes") {
  // second component: square_disk(3) with its interior vertex (1,1) moved to (5/2, 5/4), in every
  // corner; by hand two triangles flip: (1,0)(2,1)P and P(2,1)(2,2). Every index stays exact and
  // each positive triangle adds 2 to sum k, each flipped one -2: the sum is 4 chi + 4 * 2 = 12.
  GridPatch bad = square_disk(3);
  move_vertex(bad.igm, bad.id(1, 1), uv(mpq_class(5, 2), mpq_class(5, 4)));
  const IgmInput in = disjoint_union(square_disk(2).igm, bad.igm);
  const Report r = certify_igm(in, open_components());
  INFO(to_json(r));
  CHECK(r.verdict == Verdict::Invalid);
  CHECK(chk(r, 2).count("flipped") == 2);
  CHECK(chk(r, 3).passed());
  const CheckResult& c4 = chk(r, 4);
  CHECK(c4.status == Status::Fail);
  CHECK(c4.count("poincare_hopf_components_checked") == 2);
  CHECK(c4.count("poincare_hopf_components_failed") == 1);
  const Witness* w = find_witness(c4, "component", 9);
  REQUIRE(w != nullptr);
  CHECK(value(*w, "sum_index_defects") == "12");
  CHECK(value(*w, "4_chi") == "4");
  CHECK(find_witness(c4, "component", 0) == nullptr);
  REQUIRE(r.components.size() == 2);
  CHECK(r.components[0].poincare_hopf_sum == 4);
  CHECK(r.components[1].poincare_hopf_sum == 12);
  // alone, the same disk fails with a mesh witness
  const Report one = certify_igm(bad.igm, open_surfaces());
  bool mesh_witness = false;
  for (const auto& x : chk(one, 4).witnesses) mesh_witness |= x.kind == "mesh";
  CHECK(mesh_witness);
}

TEST_CASE("boundary: a non-manifold boundary vertex leaves the loops undefined") {
  IgmInput in;  // two triangles sharing only vertex 0 (a bowtie)
  add_tri(in, 0, 1, 2, uv(0, 0), uv(1, 0), uv(0, 1));
  add_tri(in, 0, 3, 4, uv(0, 0), uv(-1, 0), uv(0, -1));
  in.num_vertices = 5;
  const Report r = certify_igm(in, open_surfaces());
  CHECK(r.verdict == Verdict::Invalid);
  CHECK(chk(r, 1).count("nonmanifold_vertices") == 1);
  CHECK(chk(r, 1).count("boundary_loops") == -1);
  CHECK_FALSE(r.boundary_loops.has_value());
  CHECK(r.components.size() == 1);
  CHECK_FALSE(r.components[0].genus.has_value());
}

TEST_CASE("quad mode: boundary loops and per-component expectations") {
  const QuadInput disk = quad_grid(3, 3, all_cells);
  const QuadInput holed = quad_grid(3, 3, [](int i, int j) { return i != 1 || j != 1; });
  Options o = open_surfaces();
  o.expected_genus = 0;
  o.expected_boundary_loops = 1;
  Report r = certify_quads(disk, o);
  INFO(to_json(r));
  CHECK(r.verdict == Verdict::Valid);
  CHECK(*r.boundary_loops == 1);
  CHECK(r.check(5)->count("boundary_edges") == 12);
  o.expected_boundary_loops = 2;
  r = certify_quads(disk, o);
  CHECK(r.verdict == Verdict::Invalid);
  REQUIRE(r.check(5)->witnesses.size() == 1);
  const Witness& w = r.check(5)->witnesses[0];
  CHECK(w.reason == "number of boundary loops differs from the expected one");
  CHECK(value(w, "boundary_loops") == "1");
  CHECK(value(w, "expected") == "2");
  // a hole punched: two loops, no longer the expected one
  o.expected_boundary_loops = 1;
  r = certify_quads(holed, o);
  CHECK(r.verdict == Verdict::Invalid);
  CHECK(value(r.check(5)->witnesses.at(0), "boundary_loops") == "2");
  o.expected_boundary_loops = 2;
  CHECK(certify_quads(holed, o).verdict == Verdict::Valid);
  // the old behaviour: without allow_boundary the boundary fails
  r = certify_quads(disk);
  CHECK(r.verdict == Verdict::Invalid);
  CHECK(r.check(5)->count("boundary_edges") == 12);
  CHECK(r.check(5)->witnesses.at(0).reason == "boundary edge (one face)");

  // two components, (genus 0, 1 loop) and (genus 0, 2 loops), in either order
  QuadInput two = quad_grid(2, 2, all_cells);
  const QuadInput second = quad_grid(3, 3, [](int i, int j) { return i != 1 || j != 1; }, 9);
  two.quads.insert(two.quads.end(), second.quads.begin(), second.quads.end());
  two.num_vertices = second.num_vertices;
  Options c = open_components();
  c.expected_components = {{0, 2}, {0, 1}};
  c.expected_boundary_loops = 3;
  r = certify_quads(two, c);
  INFO(to_json(r));
  CHECK(r.verdict == Verdict::Valid);
  REQUIRE(r.components.size() == 2);
  CHECK(r.components[1].first_vertex == 9);
  CHECK(r.components[1].boundary_loops == 2);
  c.expected_components = {{0, 1}, {0, 1}};
  r = certify_quads(two, c);
  CHECK(r.verdict == Verdict::Invalid);
  REQUIRE(r.check(5)->witnesses.size() == 1);
  CHECK(value(r.check(5)->witnesses[0], "found") ==
        "(genus 0, loops 1) x 1, (genus 0, loops 2) x 1");
  CHECK(value(r.check(5)->witnesses[0], "expected") == "(genus 0, loops 1) x 2");
  c.expected_components = {{0, 1}};  // one component expected, two found
  CHECK(certify_quads(two, c).verdict == Verdict::Invalid);
  Options no_components = open_surfaces();
  CHECK(certify_quads(two, no_components).verdict == Verdict::Invalid);
}

TEST_CASE("boundary JSON: new keys, balanced") {
  const Report r = certify_igm(disjoint_union(square_disk(1).igm, cube(1)), open_components());
  const std::string j = to_json(r);
  CHECK(j.find("\"boundary_loops\": 1, \"connected_components\": 2}") != std::string::npos);
  CHECK(j.find("\"components\": [\n    {\"first_vertex\": 0, \"vertices\": 4, \"edges\": 5, "
               "\"faces\": 2, \"boundary_edges\": 4, \"boundary_loops\": 1, "
               "\"euler_characteristic\": 1, \"genus\": 0, \"poincare_hopf_sum\": 4, "
               "\"poincare_hopf_expected\": 4}") != std::string::npos);
  CHECK(j.find("\"boundary_histogram\": {\"name\": \"boundary_index_k\", \"bins\": {\"1\": 4}}") !=
        std::string::npos);
  CHECK(std::count(j.begin(), j.end(), '{') == std::count(j.begin(), j.end(), '}'));
  CHECK(std::count(j.begin(), j.end(), '[') == std::count(j.begin(), j.end(), ']'));
  CHECK(summary(r).find("boundary_loops=1 components=2") != std::string::npos);
  // unreadable: empty components list
  const std::string u = to_json(certify_igm(IgmInput{}));
  CHECK(u.find("\"components\": []") != std::string::npos);
}
