// find_quad_defects / describe_quad_defects on the isolines of valid IGMs whose grids are too
// coarse: the 1 x 1 torus (one quad, two loops), the 2 x 2 torus (double edges), the genus-0 pillow
// of 2 x 1 quads a side (the 4-quad, 6-vertex pillow of issue 47: a double edge between the cones'
// neighbours); and none where the certifier accepts the quads.
#include <doctest/doctest.h>

#include <string>

#include "../certify/igm_builders.h"
#include "certify/certify.h"
#include "igm/extract/isolines.h"
#include "igm/extract/quad_defects.h"

using namespace igm;

namespace {

// The builder's IGM with every u multiplied by sx and every v by sy.
IsolineInput scaled(const certify::IgmInput& in, const Rational& sx, const Rational& sy) {
  IsolineInput out;
  out.triangles = in.faces;
  for (std::size_t f = 0; f < in.faces.size(); ++f) {
    std::array<Point2q, 3> t;
    for (int i = 0; i < 3; ++i) t[i] = {in.corner_uv[3 * f + i][0] * sx, in.corner_uv[3 * f + i][1] * sy};
    out.corner_uv.push_back(t);
  }
  return out;
}

IsolineQuads quads_of(const IsolineInput& in) {
  IsolineResult r = extract_isolines(in);
  REQUIRE(r.quads.has_value());
  return *r.quads;
}

bool quads_certified(const IsolineQuads& q, int genus) {
  certify::QuadInput in;
  in.quads = q.quads;
  in.num_vertices = static_cast<std::int64_t>(q.vertices.size());
  certify::Options o;
  o.expected_genus = genus;
  return certify::certify_quads(in, o).valid();
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("quad defects: none where the certifier accepts the quads (3 x 3 torus, 2 x 2 pillow)") {
  for (const IsolineQuads& q : {quads_of(scaled(certify_test::torus(3), 1, 1)), quads_of(scaled(certify_test::pillow(2), 1, 1))}) {
    CHECK(find_quad_defects(q).empty());
    CHECK(describe_quad_defects(q, {}).empty());
  }
}

TEST_CASE("quad defects: the 1 x 1 torus is one quad on one vertex with two loops") {
  const IsolineQuads q = quads_of(scaled(certify_test::torus(3), Rational(1, 3), Rational(1, 3)));
  REQUIRE(q.quads.size() == 1);
  CHECK_FALSE(quads_certified(q, 1));
  const std::vector<QuadDefect> d = find_quad_defects(q);
  REQUIRE(d.size() == 2);
  for (const QuadDefect& x : d) {
    CHECK(x.kind == QuadDefectKind::Loop);
    CHECK(x.vertices == std::vector<int>{0});
    CHECK(x.quads == std::vector<int>{0});
    CHECK(x.cones.empty());
  }
  CHECK(d[0].edges != d[1].edges);
  const std::string text = describe_quad_defects(q, d);
  CHECK(has(text, "is a loop at vertex 0"));
  CHECK(has(text, "no cone among them"));
  CHECK(find_quad_defects(q, 1).size() == 1);
}

TEST_CASE("quad defects: the 2 x 2 torus has four double edges") {
  const IsolineQuads q = quads_of(scaled(certify_test::torus(3), Rational(2, 3), Rational(2, 3)));
  REQUIRE(q.quads.size() == 4);
  CHECK_FALSE(quads_certified(q, 1));
  const std::vector<QuadDefect> d = find_quad_defects(q);
  REQUIRE(d.size() == 4);
  for (const QuadDefect& x : d) {
    CHECK(x.kind == QuadDefectKind::MultiEdge);
    CHECK(x.edges.size() == 2);
    CHECK(x.vertices.size() == 2);
    CHECK(x.quads.size() == 4);  // each edge between two of the four quads
  }
}

TEST_CASE("quad defects: the 2 x 1 pillow (4 quads, 6 vertices) joins two vertices twice, its quads hold the four cones") {
  const IsolineQuads q = quads_of(scaled(certify_test::pillow(2), 1, Rational(1, 2)));
  REQUIRE(q.quads.size() == 4);
  REQUIRE(q.vertices.size() == 6);
  CHECK_FALSE(quads_certified(q, 0));
  const std::vector<QuadDefect> d = find_quad_defects(q);
  REQUIRE(d.size() == 1);
  CHECK(d[0].kind == QuadDefectKind::MultiEdge);
  CHECK(d[0].edges.size() == 2);
  CHECK(d[0].quads == std::vector<int>{0, 1, 2, 3});
  REQUIRE(d[0].cones.size() == 4);
  for (int c : d[0].cones) CHECK(q.vertices[c].valence == 2);
  // The two ends are the regular vertices between the cones.
  for (int v : d[0].vertices) CHECK(q.vertices[v].valence == 4);
  const std::string text = describe_quad_defects(q, d);
  CHECK(has(text, "2 edges"));
  CHECK(has(text, "share the cones"));
  CHECK(has(text, "(valence 2)"));
  CHECK(has(text, "more quads separate them"));
}
