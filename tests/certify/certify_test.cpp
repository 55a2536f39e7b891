// The certifier on synthetic IGMs built here: valid ones pass with the right counts, and each
// mutation is rejected by the right check with the right witness.
#include <doctest/doctest.h>

#include <algorithm>

#include "certify/certify.h"
#include "igm_builders.h"

using namespace igm::certify;
using namespace certify_test;

TEST_CASE("valid: n x n torus with wrap-around seams") {
  for (int n : {1, 2, 5}) {
    CAPTURE(n);
    const Report r = certify_igm(torus(n));
    INFO(to_json(r));
    if (n == 1) {
      // a single vertex with two triangles: edges are loops, not a valid mesh
      CHECK(r.verdict == Verdict::Invalid);
      continue;
    }
    if (n == 2) {
      // 2x2 torus: vertices (i,j) and (i+1,j) ... edges appear twice (non-manifold edges)
      CHECK(r.verdict == Verdict::Invalid);
      CHECK(chk(r, 1).count("nonmanifold_edges") > 0);
      continue;
    }
    CHECK(r.verdict == Verdict::Valid);
    CHECK(r.num_vertices == n * n);
    CHECK(r.num_edges == 3 * n * n);
    CHECK(r.num_faces == 2 * n * n);
    REQUIRE(r.genus.has_value());
    CHECK(*r.genus == 1);
    CHECK(chk(r, 2).count("positive") == 2 * n * n);
    CHECK(chk(r, 3).count("rigid") == 3 * n * n);
    CHECK(chk(r, 3).histogram.at(0) == 3 * n * n);
    CHECK(chk(r, 4).count("cones") == 0);
    CHECK(chk(r, 4).count("poincare_hopf_checked") == 1);
    CHECK(chk(r, 4).histogram.at(4) == n * n);
  }
}

TEST_CASE("valid: cube of unit squares has 8 cones of index 3") {
  for (int m : {1, 3}) {
    CAPTURE(m);
    const Report r = certify_igm(cube(m));
    INFO(to_json(r));
    CHECK(r.verdict == Verdict::Valid);
    REQUIRE(r.genus.has_value());
    CHECK(*r.genus == 0);
    CHECK(r.num_faces == 12 * m * m);
    CHECK(chk(r, 4).count("cones") == 8);
    CHECK(chk(r, 4).histogram.at(3) == 8);
    CHECK(chk(r, 4).count("poincare_hopf_sum") == 8);
    CHECK(chk(r, 4).count("poincare_hopf_expected") == 8);
    // adjacent squares meet with rotations: all four k occur on the cube's seams
    CHECK(chk(r, 3).histogram.size() >= 2);
  }
}

TEST_CASE("valid: pillow has 4 cones of index 2") {
  const Report r = certify_igm(pillow(3));
  INFO(to_json(r));
  CHECK(r.verdict == Verdict::Valid);
  CHECK(*r.genus == 0);
  CHECK(chk(r, 4).count("cones") == 4);
  CHECK(chk(r, 4).histogram.at(2) == 4);
  CHECK(chk(r, 4).histogram.at(4) == 16 + 4 - 4);  // 4x4 front grid + 2x2 back interior - 4 corners
  CHECK(chk(r, 3).histogram.at(2) == 2 * 3);        // the two sides glued by a half turn
}

TEST_CASE("valid: rotated charts give seams with k = 1 and k = 3") {
  const Report r = certify_igm(rotated_chart_torus(8));
  INFO(to_json(r));
  CHECK(r.verdict == Verdict::Valid);
  const CheckResult& c3 = chk(r, 3);
  REQUIRE(c3.histogram.count(1) == 1);
  REQUIRE(c3.histogram.count(3) == 1);
  CHECK(c3.histogram.at(1) + c3.histogram.at(3) == 16);  // two 2x2 blocks, 8 boundary edges each
  CHECK(c3.histogram.at(1) == 8);
  CHECK(c3.histogram.at(3) == 8);
  CHECK(chk(r, 4).count("cones") == 0);
}

TEST_CASE("mutation: one corner UV nudged by 2^-40 breaks exactly its two transitions") {
  IgmInput in = torus(4);
  const int f = 2 * (1 + 4 * 1);  // lower triangle of cell (1,1): vertices (1,1) (2,1) (2,2)
  mpq_class eps(1, 1);
  eps /= mpz_class(1) << 40;
  in.corner_uv[3 * f][0] += eps;  // the corner at vertex (1,1) = id 5
  const Report r = certify_igm(in);
  INFO(to_json(r));
  CHECK(r.verdict == Verdict::Invalid);
  CHECK(chk(r, 1).passed());
  CHECK(chk(r, 2).passed());
  const CheckResult& c3 = chk(r, 3);
  CHECK_FALSE(c3.passed());
  CHECK(c3.count("non_rigid") == 2);
  CHECK(c3.count("no_rotation_matches") == 2);
  CHECK(has_edge_witness(c3, 5, 6));   // (1,1)-(2,1)
  CHECK(has_edge_witness(c3, 5, 10));  // (1,1)-(2,2)
  CHECK(chk(r, 4).count("vertices_determined") == 16 - 3);
}

TEST_CASE("mutation: a translation by 1/2 across a seam is not integer") {
  IgmInput in = torus(5);
  // shift the whole chart of one block by (1/2, 0): its boundary edges keep k = 0 but t = 1/2
  map_faces(in, block_faces(5, 1, 3, 1, 3), 1, 0, 0, 1, mpq_class(1, 2), 0);
  const Report r = certify_igm(in);
  INFO(to_json(r));
  const CheckResult& c3 = chk(r, 3);
  CHECK(c3.count("translation_not_integer") == 8);
  CHECK(c3.count("no_rotation_matches") == 0);
  CHECK(chk(r, 2).passed());
  REQUIRE(!c3.witnesses.empty());
  bool found_t = false;
  for (const auto& w : c3.witnesses)
    for (const auto& [k, v] : w.values)
      if (k == "t" && (v == "(1/2, 0)" || v == "(-1/2, 0)")) found_t = true;
  CHECK(found_t);
}

TEST_CASE("mutation: one triangle flipped") {
  IgmInput in = torus(4);
  const int f = 7;
  std::swap(in.corner_uv[3 * f + 1], in.corner_uv[3 * f + 2]);
  const Report r = certify_igm(in);
  INFO(to_json(r));
  CHECK(r.verdict == Verdict::Invalid);
  const CheckResult& c2 = chk(r, 2);
  CHECK(c2.count("flipped") == 1);
  CHECK(c2.count("degenerate") == 0);
  REQUIRE(c2.witnesses.size() == 1);
  CHECK(c2.witnesses[0].ids == std::vector<std::int64_t>{f});
}

TEST_CASE("mutation: one triangle flipped by moving a vertex consistently (transitions stay rigid)") {
  IgmInput in = torus(5);
  // vertex (2,2) = id 12 is interior to the chart: move it in every corner to (3, 5/2)+(1/4,0);
  // the triangles of cell (2,1) upper (2,1)-(3,2)-(2,2) keep ... count flips independently below.
  const Uv target = uv(mpq_class(13, 4), mpq_class(5, 2));
  for (std::size_t c = 0; c < in.corner_uv.size(); ++c)
    if (in.faces[c / 3][c % 3] == 12) in.corner_uv[c] = target;
  // independent count with plain integer arithmetic on 4x-scaled coordinates
  int expect_flipped = 0;
  for (std::size_t f = 0; f < in.faces.size(); ++f) {
    long long p[3][2];
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) p[k][d] = mpq_class(in.corner_uv[3 * f + k][d] * 4).get_num().get_si();
    long long det = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if (det < 0) ++expect_flipped;
  }
  REQUIRE(expect_flipped > 0);
  const Report r = certify_igm(in);
  INFO(to_json(r));
  CHECK(chk(r, 2).count("flipped") == expect_flipped);
  CHECK(chk(r, 3).passed());  // the move is the same in every corner: transitions still rigid
  CHECK(chk(r, 3).count("non_rigid") == 0);
  CHECK(r.verdict == Verdict::Invalid);
}

TEST_CASE("mutation: one triangle degenerate") {
  IgmInput in = torus(4);
  const int f = 9;
  in.corner_uv[3 * f + 2] = uv((in.corner_uv[3 * f][0] + in.corner_uv[3 * f + 1][0]) / 2,
                               (in.corner_uv[3 * f][1] + in.corner_uv[3 * f + 1][1]) / 2);
  const Report r = certify_igm(in);
  INFO(to_json(r));
  const CheckResult& c2 = chk(r, 2);
  CHECK(c2.count("degenerate") == 1);
  CHECK(c2.count("flipped") == 0);
  REQUIRE(c2.witnesses.size() == 1);
  CHECK(c2.witnesses[0].ids == std::vector<std::int64_t>{f});
  CHECK(c2.witnesses[0].values.back().second == "0");  // exact orient2d value
}

TEST_CASE("mutation: cones moved off their integer points (pillow shifted by 1/2)") {
  const int m = 3;
  const Report r = certify_igm(pillow(m, mpq_class(1, 2), 0));
  INFO(to_json(r));
  CHECK(r.verdict == Verdict::Invalid);
  CHECK(chk(r, 1).passed());
  CHECK(chk(r, 2).passed());
  CHECK(chk(r, 3).passed());  // transitions are still integer: t = (1, 0) across the half turn
  const CheckResult& c4 = chk(r, 4);
  CHECK_FALSE(c4.passed());
  CHECK(c4.count("cones") == 4);
  CHECK(c4.count("cones_off_integer") == 4);
  for (int v : {0, m, m * (m + 1), m * (m + 1) + m}) CHECK(has_witness(c4, "vertex", v));
  // the regular vertices are off-integer too but are not cones: not reported
  CHECK(c4.offending == 4);
}

TEST_CASE("mutation: a seam rotated by 45 degrees") {
  IgmInput in = torus(6);
  // (x, y) -> (x - y, x + y): a 45-degree rotation scaled by sqrt 2, orientation preserving
  map_faces(in, block_faces(6, 1, 3, 1, 3), 1, -1, 1, 1, 0, 0);
  const Report r = certify_igm(in);
  INFO(to_json(r));
  CHECK(chk(r, 2).passed());
  const CheckResult& c3 = chk(r, 3);
  CHECK(c3.count("no_rotation_matches") == 8);
  CHECK(c3.count("non_rigid") == 8);
  CHECK(has_edge_witness(c3, 1 + 6 * 1, 2 + 6 * 1));  // (1,1)-(2,1): bottom side of the block
  CHECK(has_edge_witness(c3, 3 + 6 * 2, 3 + 6 * 3));  // (3,2)-(3,3): right side
  CHECK_FALSE(has_edge_witness(c3, 2 + 6 * 2, 2 + 6 * 3));  // interior of the block
}

TEST_CASE("mutation: a non-manifold edge") {
  IgmInput in = torus(4);
  const int extra = 16;
  in.num_vertices = 17;
  add_tri(in, 5, 6, extra, uv(0, 0), uv(1, 0), uv(0, 1));
  const Report r = certify_igm(in);
  INFO(to_json(r));
  const CheckResult& c1 = chk(r, 1);
  CHECK_FALSE(c1.passed());
  CHECK(c1.count("nonmanifold_edges") == 1);
  CHECK(has_edge_witness(c1, 5, 6));
  CHECK_FALSE(r.genus.has_value());
  CHECK(r.verdict == Verdict::Invalid);
}

TEST_CASE("topology: boundary, inconsistent orientation, two components, unreferenced vertex") {
  SUBCASE("boundary") {
    IgmInput in = torus(4);
    in.faces.pop_back();
    in.corner_uv.resize(in.corner_uv.size() - 3);
    const Report r = certify_igm(in);
    CHECK(chk(r, 1).count("boundary_edges") == 3);
  }
  SUBCASE("inconsistent orientation") {
    IgmInput in = torus(4);
    std::swap(in.faces[3][1], in.faces[3][2]);
    std::swap(in.corner_uv[10], in.corner_uv[11]);
    const Report r = certify_igm(in);
    CHECK(chk(r, 1).count("inconsistently_oriented_edges") == 3);
    CHECK(chk(r, 2).count("flipped") == 1);  // the UV triangle follows the reversed face
  }
  SUBCASE("two components") {
    IgmInput a = torus(3), b = torus(3);
    for (auto& f : b.faces)
      for (int& v : f) v += 9;
    a.faces.insert(a.faces.end(), b.faces.begin(), b.faces.end());
    a.corner_uv.insert(a.corner_uv.end(), b.corner_uv.begin(), b.corner_uv.end());
    a.num_vertices = 18;
    const Report r = certify_igm(a);
    CHECK(chk(r, 1).count("connected_components") == 2);
    CHECK(chk(r, 1).witnesses.size() == 1);
    CHECK(chk(r, 1).witnesses[0].ids == std::vector<std::int64_t>{9});
    CHECK(r.verdict == Verdict::Invalid);
  }
  SUBCASE("unreferenced vertex declared through positions") {
    IgmInput in = torus(3);
    in.num_vertices = -1;
    in.positions.assign(11, {0.0, 0.0, 0.0});
    const Report r = certify_igm(in);
    CHECK(r.num_vertices == 11);
    CHECK(chk(r, 1).count("unreferenced_vertices") == 2);
  }
  SUBCASE("unreferenced vertex") {
    IgmInput in = torus(3);
    in.num_vertices = 10;
    const Report r = certify_igm(in);
    CHECK(chk(r, 1).count("unreferenced_vertices") == 1);
    CHECK(has_witness(chk(r, 1), "vertex", 9));
  }
  SUBCASE("non-manifold vertex: two cubes sharing a vertex") {
    IgmInput a = cube(1), b = cube(1);
    // vertex 0 of b is identified with vertex 0 of a, the others renumbered
    for (auto& f : b.faces)
      for (int& v : f) v = v == 0 ? 0 : v + 7;
    a.faces.insert(a.faces.end(), b.faces.begin(), b.faces.end());
    a.corner_uv.insert(a.corner_uv.end(), b.corner_uv.begin(), b.corner_uv.end());
    a.num_vertices = 15;
    const Report r = certify_igm(a);
    CHECK(chk(r, 1).count("nonmanifold_vertices") == 1);
    CHECK(has_witness(chk(r, 1), "vertex", 0));
    CHECK(chk(r, 1).count("nonmanifold_edges") == 0);
  }
}

TEST_CASE("in-memory input errors are unreadable, not crashes") {
  IgmInput in = torus(3);
  in.corner_uv.pop_back();
  CHECK(certify_igm(in).verdict == Verdict::Unreadable);
  IgmInput bad = torus(3);
  bad.faces[0][1] = 99;
  CHECK(certify_igm(bad).verdict == Verdict::Unreadable);
  bad.faces[0][1] = -1;
  CHECK(certify_igm(bad).verdict == Verdict::Unreadable);
  CHECK(certify_igm(IgmInput{}).verdict == Verdict::Unreadable);
  IgmInput huge = torus(3);
  huge.num_vertices = std::int64_t(1) << 40;  // declared, absent: refused without allocating
  CHECK(certify_igm(huge).verdict == Verdict::Unreadable);
  QuadInput hq;
  hq.quads = {{0, 1, 2, 3}};
  hq.num_vertices = std::int64_t(1) << 40;
  CHECK(certify_quads(hq).verdict == Verdict::Unreadable);
}

TEST_CASE("witnesses are capped, counts are not") {
  IgmInput in = torus(6);
  for (int f = 0; f < 30; ++f) std::swap(in.corner_uv[3 * f + 1], in.corner_uv[3 * f + 2]);
  Options o;
  o.max_witnesses = 5;
  const Report r = certify_igm(in, o);
  CHECK(chk(r, 2).count("flipped") == 30);
  CHECK(chk(r, 2).offending == 30);
  CHECK(chk(r, 2).witnesses.size() == 5);
}

TEST_CASE("quad mode: cube quads, genus, non-quads, valence") {
  QuadInput q;
  // cube [0,1]^3 with outward quads
  q.quads = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  Report r = certify_quads(q);
  INFO(to_json(r));
  CHECK(r.verdict == Verdict::Valid);
  CHECK(*r.genus == 0);
  CHECK(r.check(5)->histogram.at(3) == 8);
  Options o;
  o.expected_genus = 1;
  CHECK(certify_quads(q, o).verdict == Verdict::Invalid);
  o.expected_genus = 0;
  CHECK(certify_quads(q, o).verdict == Verdict::Valid);
  QuadInput open = q;
  open.quads.pop_back();
  r = certify_quads(open);
  CHECK(r.verdict == Verdict::Invalid);
  CHECK(r.check(5)->count("boundary_edges") == 4);
  // text with a triangle among quads
  const std::string txt = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 4 3\nf 1 3 2\n";
  r = certify_quads_text(txt);
  CHECK(r.check(5)->count("non_quad_faces") == 2);
  CHECK(r.verdict == Verdict::Invalid);
}

TEST_CASE("quad mode: torus grid is genus 1 with valence 4") {
  const int n = 4;
  QuadInput q;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      q.quads.push_back({i + n * j, (i + 1) % n + n * j, (i + 1) % n + n * ((j + 1) % n), i + n * ((j + 1) % n)});
  const Report r = certify_quads(q);
  CHECK(r.verdict == Verdict::Valid);
  CHECK(*r.genus == 1);
  CHECK(r.check(5)->histogram.at(4) == n * n);
}

TEST_CASE("JSON shape") {
  const Report r = certify_igm(cube(1));
  const std::string j = to_json(r);
  CHECK(j.find("\"verdict\": \"valid\"") != std::string::npos);
  CHECK(j.find("\"index_base\": 0") != std::string::npos);
  CHECK(j.find("\"name\": \"transitions\"") != std::string::npos);
  CHECK(j.find("\"genus\": 0") != std::string::npos);
  CHECK(std::count(j.begin(), j.end(), '{') == std::count(j.begin(), j.end(), '}'));
  CHECK(std::count(j.begin(), j.end(), '[') == std::count(j.begin(), j.end(), ']'));
}

TEST_CASE("zero-length UV edge: degenerate triangles, its vertices undetermined") {
  IgmInput in = torus(5);
  // vertex (2,2) = id 12 moved onto its neighbour (3,2) = id 13 in every corner
  for (std::size_t c = 0; c < in.corner_uv.size(); ++c)
    if (in.faces[c / 3][c % 3] == 12) in.corner_uv[c] = uv(3, 2);
  const Report r = certify_igm(in);
  INFO(to_json(r));
  CHECK(chk(r, 2).count("degenerate") == 2);
  CHECK(chk(r, 2).count("flipped") == 0);
  CHECK(chk(r, 3).count("zero_length_both_sides") == 1);
  CHECK(chk(r, 3).count("non_rigid") == 0);
  CHECK(chk(r, 4).count("vertices_undetermined") == 2);
  CHECK(chk(r, 4).count("poincare_hopf_checked") == 0);
  CHECK(chk(r, 4).status == Status::Incomplete);
  CHECK(r.verdict == Verdict::Invalid);
}

TEST_CASE("threads: the same report for 1, 2, 3 and 7 threads, witnesses across the ranges in element order") {
  // 2 x 80^2 = 12,800 faces, 19,200 edges, 6,400 vertices: several ranges of every check.
  const int n = 80;
  IgmInput in = torus(n);
  // flipped faces spread over the ranges, a broken seam block near the end, a cone off its point
  for (int f : {3, 5000, 5001, 9000, 12700}) std::swap(in.corner_uv[3 * f + 1], in.corner_uv[3 * f + 2]);
  map_faces(in, block_faces(n, 70, 72, 70, 72), 1, 0, 0, 1, mpq_class(1, 2), 0);
  for (std::size_t max_witnesses : {std::size_t{3}, std::size_t{20}}) {
    CAPTURE(max_witnesses);
    Options o;
    o.max_witnesses = max_witnesses;
    o.threads = 1;
    const Report one = certify_igm(in, o);
    CHECK(one.verdict == Verdict::Invalid);
    CHECK(chk(one, 2).count("flipped") == 5);
    CHECK(chk(one, 2).witnesses.size() == std::min<std::size_t>(5, max_witnesses));
    CHECK(chk(one, 2).witnesses.front().ids == std::vector<std::int64_t>{3});
    CHECK(chk(one, 3).count("translation_not_integer") == 8);
    for (int threads : {2, 3, 7}) {
      CAPTURE(threads);
      o.threads = threads;
      CHECK(to_json(certify_igm(in, o)) == to_json(one));
    }
  }
}
