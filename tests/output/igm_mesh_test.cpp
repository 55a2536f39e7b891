#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "certify/certify.h"
#include "igm/core/threads.h"
#include "igm/output/igm_mesh.h"
#include "igm/output/schema_svg.h"
#include "square_torus.h"

using namespace igm;

using igm_test::square_torus;

TEST_CASE("exact and double IGM files are read back by the certifier as valid") {
  IgmMesh m = square_torus(4);
  m.corner_uv[0][1].x = Rational(1, 3) + 1;  // exact non-dyadic value: 4/3 must survive the exact format
  for (bool exact : {true, false}) {
    std::ostringstream s;
    write_igm_obj(s, m, exact);
    auto report = igm::certify::certify_igm_text(s.str());
    INFO(s.str().substr(0, 200));
    // Moving one corner to 4/3 breaks the transitions: the exact file must show it, the
    // double file (4/3 rounded) must show it too.
    CHECK_FALSE(report.valid());
  }
  IgmMesh ok = square_torus(4);
  std::ostringstream s;
  write_igm_obj(s, ok, true);
  CHECK(igm::certify::certify_igm_text(s.str()).valid());
  CHECK(s.str().find("vt 1 0") != std::string::npos);
}

TEST_CASE("quad OBJ and schema SVG are well formed") {
  QuadMesh q;
  q.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  q.quads = {{0, 1, 2, 3}};
  std::ostringstream s;
  write_quad_obj(s, q);
  CHECK(s.str().find("f 1 2 3 4") != std::string::npos);
  SchemaDrawing d;
  d.polygon = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  d.side_pair = {2, 3, 0, 1};
  d.template_edges = {{Vec2d{0, 0}, Vec2d{1, 1}}};
  std::ostringstream svg;
  write_schema_svg(svg, d);
  const std::string t = svg.str();
  CHECK(t.rfind("<svg", 0) == 0);
  CHECK(t.find("</svg>") != std::string::npos);
  // four polygon sides + one template edge
  std::size_t lines = 0;
  for (std::size_t p = t.find("<line"); p != std::string::npos; p = t.find("<line", p + 1)) ++lines;
  CHECK(lines == 5);
}

namespace {
// The `vt` lines of an OBJ text, each coordinate as written.
std::vector<std::array<std::string, 2>> vt_fields(const std::string& text) {
  std::vector<std::array<std::string, 2>> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("vt ", 0) == 0) {
      std::istringstream f(line.substr(3));
      std::array<std::string, 2> uv;
      f >> uv[0] >> uv[1];
      out.push_back(uv);
    }
  return out;
}
}  // namespace

TEST_CASE("the doubles file writes a UV coordinate that is a double as its exact decimal expansion") {
  // One triangle (the writer does not judge the map): expectations computed by hand / Python's
  // Decimal of the doubles.
  IgmMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}};
  const double tiny = std::ldexp(1.0, -1074);
  m.corner_uv = {{Point2q{to_rational(0.1), to_rational(-tiny)}, Point2q{Rational(3), Rational(-5, 8)},
                  Point2q{Rational(1, 3), Rational(1, 2) * to_rational(tiny)}}};
  std::ostringstream s;
  write_igm_obj(s, m, false);
  const auto vt = vt_fields(s.str());
  REQUIRE(vt.size() == 3);
  CHECK(vt[0][0] == "0.1000000000000000055511151231257827021181583404541015625");
  CHECK(vt[0][1].size() == 1077);  // "-0." and 1074 digits
  CHECK(vt[0][1].rfind("-0.000000000", 0) == 0);
  CHECK(vt[0][1].substr(vt[0][1].size() - 20) == "19718265533447265625");
  CHECK(vt[1][0] == "3");
  CHECK(vt[1][1] == "-0.625");
  CHECK(vt[2][0] == "0.33333333333333331");  // not a double: %.17g of its truncation, as before
  CHECK(vt[2][1] == "0");                     // 2^-1075 is below every double: truncated to 0
  // Every exact one reads back as the same rational.
  CHECK(parse_rational(vt[0][0]) == m.corner_uv[0][0].x);
  CHECK(parse_rational(vt[0][1]) == m.corner_uv[0][0].y);
  CHECK(parse_rational(vt[1][1]) == m.corner_uv[0][1].y);
  CHECK(parse_rational(vt[2][0]) != m.corner_uv[0][2].x);
}

TEST_CASE("a map on a double grid certifies from the doubles file and reads back exactly") {
  // Vertex (1, 1) of the 4 x 4 torus moved in all its corners (no seam there: all of them are at
  // (1, 1)) to (1 + 3 2^-45, 1 - 2^-44): doubles, the map still valid.
  IgmMesh m = square_torus(4);
  const Point2q moved{Rational(1) + Rational(3) * to_rational(std::ldexp(1.0, -45)),
                      Rational(1) - to_rational(std::ldexp(1.0, -44))};
  for (std::size_t f = 0; f < m.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i)
      if (m.triangles[f][i] == 5) m.corner_uv[f][i] = moved;
  std::ostringstream s;
  write_igm_obj(s, m, false);
  const std::string text = s.str();
  CHECK(text.find("vt 1.000000000000085265128291212022304534912109375 0.99999999999994315658113919198513031005859375") !=
        std::string::npos);
  CHECK(igm::certify::certify_igm_text(text).valid());
  const auto vt = vt_fields(text);
  REQUIRE(vt.size() == 3 * m.triangles.size());
  for (std::size_t c = 0; c < vt.size(); ++c) {
    const Point2q& uv = m.corner_uv[c / 3][c % 3];
    CHECK(parse_rational(vt[c][0]) == uv.x);
    CHECK(parse_rational(vt[c][1]) == uv.y);
  }
}

TEST_CASE("the IGM files are the same bytes for any thread count, line by line in order") {
  // 80 x 80 squares: 12,800 triangles, 38,400 vt lines, more than one batch of the parallel
  // formatting (64 strings of 2048 lines); one UV made non-dyadic so both formats take both paths.
  IgmMesh m = square_torus(80);
  m.corner_uv[5][2].y = Rational(2, 3);
  for (bool exact : {true, false}) {
    std::string text[3];
    int k = 0;
    for (int threads : {1, 2, 3})
      with_threads(threads, [&] {
        std::ostringstream s;
        write_igm_obj(s, m, exact);
        text[k++] = s.str();
      });
    CHECK(text[0] == text[1]);
    CHECK(text[0] == text[2]);
    // The lines in order: the vertices, then one vt per corner, then the faces.
    std::istringstream in(text[0]);
    std::string line;
    std::size_t v = 0, vt = 0, f = 0;
    bool order = true;
    while (std::getline(in, line)) {
      if (line.rfind("v ", 0) == 0) order = order && vt == 0 && f == 0, ++v;
      else if (line.rfind("vt ", 0) == 0) order = order && f == 0, ++vt;
      else if (line.rfind("f ", 0) == 0) {
        // face f's corners are the vt lines 3f+1 .. 3f+3
        order = order && line.find("/" + std::to_string(3 * f + 1) + " ") != std::string::npos;
        ++f;
      }
    }
    CHECK(order);
    CHECK(v == m.positions.size());
    CHECK(vt == 3 * m.triangles.size());
    CHECK(f == m.triangles.size());
    if (exact) CHECK(text[0].find(" 2/3\n") != std::string::npos);
  }
}
