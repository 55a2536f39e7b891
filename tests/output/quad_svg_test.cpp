#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "igm/output/quad_svg.h"

using namespace igm;

namespace {

// The box [0,3] x [0,2] x [0,1] as 6 quads, counter-clockwise seen from outside: every vertex
// has valence 3. Quad 0 is the bottom (z = 0), quad 1 the top (z = 1).
QuadMesh box() {
  QuadMesh m;
  for (int k = 0; k < 8; ++k) m.positions.push_back({3.0 * (k & 1), 2.0 * ((k >> 1) & 1), 1.0 * (k >> 2)});
  m.quads = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return m;
}

// An n x n quad torus (radii 3 and 1): every vertex has valence 4.
QuadMesh torus(int n) {
  QuadMesh m;
  const double pi = 3.141592653589793;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = 2 * pi * i / n, v = 2 * pi * j / n;
      m.positions.push_back({(3 + std::cos(v)) * std::cos(u), (3 + std::cos(v)) * std::sin(u), std::sin(v)});
    }
  const auto id = [n](int i, int j) { return (j % n) * n + (i % n); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

// Structural XML checks: one root <svg>, every element closed in order, attribute quotes paired,
// no '&' (nothing here needs an entity). Returns "" when well-formed, else what is wrong.
std::string xml_problem(const std::string& s) {
  std::vector<std::string> open;
  std::size_t roots = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '&') return "an '&' at " + std::to_string(i);
    if (s[i] == '>') return "a stray '>' at " + std::to_string(i);
    if (s[i] != '<') continue;
    const std::size_t end = s.find('>', i);
    if (end == std::string::npos) return "an unclosed tag at " + std::to_string(i);
    const std::string tag = s.substr(i + 1, end - i - 1);
    if (count(tag, "\"") % 2 != 0 || tag.find('<') != std::string::npos) return "a broken tag: " + tag;
    const std::string name = tag.substr(tag[0] == '/', tag.find_first_of(" /", 1) - (tag[0] == '/'));
    if (tag[0] == '/') {
      if (open.empty() || open.back() != name) return "</" + name + "> closes nothing open";
      open.pop_back();
    } else if (tag.back() != '/') {
      if (open.empty()) ++roots;
      open.push_back(name);
    } else if (open.empty()) {
      return "an element outside the root";
    }
    i = end;
  }
  if (!open.empty()) return "<" + open.back() + "> never closed";
  return roots == 1 ? "" : std::to_string(roots) + " root elements";
}

std::vector<std::string> polygons(const std::string& svg) {
  std::vector<std::string> out;
  for (std::size_t at = svg.find("<polygon"); at != std::string::npos; at = svg.find("<polygon", at + 1))
    out.push_back(svg.substr(at, svg.find('>', at) - at + 1));
  return out;
}

}  // namespace

TEST_CASE("quad svg: a box seen from above, painter's order, 8 valence-3 markers and the legend") {
  QuadSvgOptions o;
  o.view = {0, 0, 1};  // right = x (largest spread), up = z x x = y
  std::ostringstream s;
  const QuadSvgStats st = write_quad_svg(s, box(), o);
  const std::string svg = s.str();
  CHECK(xml_problem(svg) == "");
  CHECK(st.quads == 6);
  CHECK(st.quads_drawn == 6);
  CHECK(st.irregular == std::map<int, std::size_t>{{3, 8}});
  const std::vector<std::string> p = polygons(svg);
  REQUIRE(p.size() == 6);
  CHECK(count(svg, "<circle class=\"valence-3\"") == 8);
  CHECK(count(svg, "class=\"valence-") == 8);
  CHECK(count(svg, "valence 3: 8 vertices") == 1);
  CHECK(count(svg, ">6 quads<") == 1);
  // 800 px, margin 40: scale 720 / 3 = 240; x 0..3 -> 40..760; y 0..2 -> 640..160 (centred).
  // The bottom (depth 0) first, the top (depth 1) last; both face the viewer's light alike:
  // shade 0.3 + 0.7 * 0.8 / |(-0.35, 0.5, 0.8)| = 0.85654 -> rgb(135,168,198).
  CHECK(p.front() == "<polygon points=\"40.0,640.0 40.0,160.0 760.0,160.0 760.0,640.0\" fill=\"rgb(135,168,198)\"/>");
  CHECK(p.back() == "<polygon points=\"40.0,640.0 760.0,640.0 760.0,160.0 40.0,160.0\" fill=\"rgb(135,168,198)\"/>");
  // The top's 4 markers come after the last polygon.
  CHECK(count(svg.substr(svg.rfind("<polygon")), "class=\"valence-3\"") == 4);
}

TEST_CASE("quad svg: the default view shows three faces of the box, shaded apart") {
  std::ostringstream s;
  write_quad_svg(s, box());
  const std::string svg = s.str();
  CHECK(xml_problem(svg) == "");
  const std::vector<std::string> p = polygons(svg);
  REQUIRE(p.size() == 6);
  // Seen along e3 + 0.5 e2 + 0.35 e1: the top, a long side and a short side face the viewer, at
  // three different angles to the light: the last three polygons have three different fills.
  std::vector<std::string> fills;
  for (std::size_t i = 3; i < 6; ++i) fills.push_back(p[i].substr(p[i].find("fill=")));
  CHECK(fills[0] != fills[1]);
  CHECK(fills[1] != fills[2]);
  CHECK(fills[0] != fills[2]);
  CHECK(count(svg, "class=\"valence-3\"") == 8);
}

TEST_CASE("quad svg: a regular torus has no markers, above max_quads a subset is drawn") {
  std::ostringstream s;
  const QuadSvgStats st = write_quad_svg(s, torus(20));
  CHECK(xml_problem(s.str()) == "");
  CHECK(st.quads_drawn == 400);
  CHECK(st.irregular.empty());
  CHECK(count(s.str(), "class=\"valence-") == 0);
  CHECK(count(s.str(), "every vertex of valence 4") == 1);
  QuadSvgOptions o;
  o.max_quads = 50;
  std::ostringstream t;
  const QuadSvgStats sub = write_quad_svg(t, torus(20), o);
  CHECK(xml_problem(t.str()) == "");
  CHECK(sub.quads == 400);
  CHECK(sub.quads_drawn <= 50);
  CHECK(sub.quads_drawn >= 25);
  CHECK(polygons(t.str()).size() == sub.quads_drawn);
  CHECK(count(t.str(), " drawn (subset)") == 1);
}

TEST_CASE("quad svg: bad quads are skipped, an empty mesh gives an empty picture") {
  QuadMesh m = box();
  m.quads.push_back({0, 1, 2, 99});                                       // out of range
  m.positions.push_back({std::numeric_limits<double>::quiet_NaN(), 0, 0});  // vertex 8
  m.quads.push_back({8, 0, 1, 2});
  std::ostringstream s;
  const QuadSvgStats st = write_quad_svg(s, m);
  CHECK(st.quads == 8);
  CHECK(st.quads_drawn == 6);
  CHECK(polygons(s.str()).size() == 6);
  CHECK(xml_problem(s.str()) == "");
  std::ostringstream e;
  CHECK(write_quad_svg(e, QuadMesh{}).quads_drawn == 0);
  CHECK(xml_problem(e.str()) == "");
  CHECK(count(e.str(), ">0 quads<") == 1);
}
