#include <doctest/doctest.h>

#include <sstream>

#include "certify/certify.h"
#include "igm/output/igm_mesh.h"
#include "igm/output/schema_svg.h"

using namespace igm;

namespace {
// The unit-square torus split into 2 triangles: one vertex, every corner UV on the square.
IgmMesh square_torus(int n) {
  IgmMesh m;
  auto id = [n](int i, int j) { return ((j % n + n) % n) * n + ((i % n + n) % n); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m.positions.push_back({double(i), double(j), 0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      auto P = [](int a, int b) { return Point2q{Rational(a), Rational(b)}; };
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.corner_uv.push_back({P(i, j), P(i + 1, j), P(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      m.corner_uv.push_back({P(i, j), P(i + 1, j + 1), P(i, j + 1)});
    }
  return m;
}
}  // namespace

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
