// Tests of the placement of exact maps on a dyadic double grid (smooth/dyadic.h).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "igm/smooth/dyadic.h"
#include "open_igm.h"
#include "smooth_fixture.h"

using namespace igm;
using igm_test::certify_uv;
using igm_test::pipeline_igm;

namespace {

bool is_double(const Rational& q) { return to_rational(to_double(q)) == q; }

// The doubles OBJ of `igm` with the UVs `uv`: certified by the certifier from its text, and each
// `vt` read back as exactly the rational it came from.
void check_doubles_file(const IgmMesh& igm, const std::vector<std::array<Point2q, 3>>& uv) {
  IgmMesh out;
  out.positions = igm.positions;
  out.triangles = igm.triangles;
  out.corner_uv = uv;
  std::ostringstream s;
  write_igm_obj(s, out, false);
  const std::string text = s.str();
  CHECK(certify::certify_igm_text(text).valid());
  std::istringstream in(text);
  std::string line;
  std::size_t c = 0, mismatches = 0;
  while (std::getline(in, line)) {
    if (line.rfind("vt ", 0) != 0) continue;
    std::istringstream f(line.substr(3));
    std::string x, y;
    f >> x >> y;
    const Point2q& p = uv[c / 3][c % 3];
    if (parse_rational(x) != p.x || parse_rational(y) != p.y) ++mismatches;
    ++c;
  }
  CHECK(c == 3 * uv.size());
  CHECK(mismatches == 0);
}

}  // namespace

TEST_CASE("the grid of the square torus by hand, and rounding to it") {
  // Vertex UVs up to 4 (vertex 0's reference corner is at (4, 4), seamless_test), so the bound is
  // the least power of two >= 8 * 4 = 32; the translations are up to 4: 32 + 4 < 2^6, spacing
  // 2^(6 - 53).
  const SeamlessStructure s = seamless_structure(igm_test::square_torus(4));
  const auto map = round_to_grid(s);
  REQUIRE(map.has_value());
  CHECK(map->grid.exponent == -47);
  CHECK(map->grid.bound == 32);
  for (int v = 0; v < 16; ++v) {  // integer points: unchanged
    CHECK(map->vertex_uv[v].x == to_double(s.vertex_uv[v].x));
    CHECK(map->vertex_uv[v].y == to_double(s.vertex_uv[v].y));
  }
  const DyadicGrid& g = map->grid;
  const double h = std::ldexp(1.0, -47);
  CHECK(round_to_grid(h / 2, g) == 0.0);      // a tie: to even
  CHECK(round_to_grid(1.5 * h, g) == 2 * h);  // a tie: to even
  CHECK(round_to_grid(0.75 * h, g) == h);
  CHECK(round_to_grid(-1 - 0.25 * h, g) == -1.0);
  CHECK(round_to_grid(32.0, g) == 32.0);
  CHECK_FALSE(round_to_grid(32.0 + 16 * h, g).has_value());  // beyond the bound
  CHECK_FALSE(round_to_grid(std::numeric_limits<double>::quiet_NaN(), g).has_value());
  CHECK_FALSE(round_to_grid(std::numeric_limits<double>::infinity(), g).has_value());
}

TEST_CASE("the pipeline's exact map rounds onto its grid, certifies, and keeps its structure") {
  for (int genus : {0, 1, 2}) {
    INFO("genus " << genus);
    const IgmMesh igm = pipeline_igm(genus, 400, 3);
    const SeamlessStructure s = seamless_structure(igm);
    const DyadicResult r = round_to_dyadic(igm, s);
    CHECK(r.stats.on_grid);
    CHECK(r.stats.nonpositive == 0);
    CHECK(r.stats.reason.empty());
    REQUIRE(r.corner_uv.size() == igm.corner_uv.size());
    // Every coordinate a double, within half a grid step of the exact one (rounding moves each
    // vertex by at most that, and its corners are rigid copies).
    const Rational half_step = Rational(1, 2) * to_rational(std::ldexp(1.0, r.stats.grid_exponent));
    int not_double = 0, too_far = 0;
    for (std::size_t f = 0; f < igm.corner_uv.size(); ++f)
      for (int i = 0; i < 3; ++i) {
        const Point2q &p = r.corner_uv[f][i], &q = igm.corner_uv[f][i];
        not_double += !is_double(p.x) + !is_double(p.y);
        too_far += (abs(Rational(p.x - q.x)) > half_step) + (abs(Rational(p.y - q.y)) > half_step);
      }
    CHECK(not_double == 0);
    CHECK(too_far == 0);
    CHECK(r.stats.max_uv_bits <= 53 + 1 - r.stats.grid_exponent);  // numerator and 2^-exponent
    CHECK(certify_uv(igm, r.corner_uv).valid());
    IgmMesh rounded = igm;
    rounded.corner_uv = r.corner_uv;
    CHECK(igm_test::structure_difference(s, seamless_structure(rounded)) == "");
    check_doubles_file(igm, r.corner_uv);
  }
}

TEST_CASE("a sliver that rounding would flip keeps the exact map and says so") {
  // eps = 2^-70 / 3: far below the grid's spacing; the vertex rounds onto the diagonal.
  const Rational eps = make_rational(1, Integer(3) * (Integer(1) << 70));
  const IgmMesh igm = igm_test::sliver_torus(eps);
  REQUIRE(certify_uv(igm, igm.corner_uv).valid());  // the exact map is valid
  const DyadicResult r = round_to_dyadic(igm);
  CHECK_FALSE(r.stats.on_grid);
  CHECK(r.stats.nonpositive == 1);
  CHECK(r.stats.first_nonpositive == igm_test::kSliverFace);
  CHECK(r.stats.reason.find("non-positive") != std::string::npos);
  CHECK(igm_test::changed_corners(r.corner_uv, igm.corner_uv) == 0);
  CHECK(r.stats.max_uv_bits == bit_size(Rational(1, 2) + eps));
  CHECK(certify_uv(igm, r.corner_uv).valid());
  // A thicker sliver (eps = 2^-20) survives the rounding.
  const DyadicResult thick = round_to_dyadic(igm_test::sliver_torus(Rational(1, 1 << 20)));
  CHECK(thick.stats.on_grid);
  CHECK(thick.stats.nonpositive == 0);
}

TEST_CASE("check_map: a flipped triangle, and an angle that is not the structure's") {
  const SeamlessStructure s = seamless_structure(igm_test::square_torus(4));
  GridMap map = *round_to_grid(s);
  std::vector<std::array<Vec2d, 3>> corners;
  grid_corners(s, map, corners);
  CHECK(check_map(s, corners).valid());
  // A structure that claims vertex 6 is a cone of angle 2 pi: the map's angle there is 4.
  SeamlessStructure claimed = s;
  claimed.angle_index[6] = 8;
  const MapCheck angle = check_map(claimed, corners);
  CHECK_FALSE(angle.valid());
  CHECK(angle.nonpositive == 0);
  CHECK(angle.angles_changed == 1);
  CHECK(angle.first_angle_changed == 6);
  // Vertex (1, 1) moved across the diagonal from (1, 0) to (2, 1): kSliverFace flips (and the
  // angles are not counted).
  map.vertex_uv[5] = {1.5, 0.25};
  grid_corners(s, map, corners);
  const MapCheck flipped = check_map(s, corners);
  CHECK(flipped.nonpositive == 1);
  CHECK(flipped.first_nonpositive == igm_test::kSliverFace);
  CHECK(flipped.angles_changed == 0);
}

TEST_CASE("open IGMs on the grid: integers kept exactly, every boundary edge on its isoline") {
  // Thirds do not round: every free vertex moves, but cones, boundary corners and the isoline
  // coordinates of sliding vertices are integers, kept bit for bit.
  const IgmMesh inputs[] = {
      igm_test::perturbed(igm_test::lifted(certify_test::l_shape(2).igm, igm_test::bumped), 20, 3),
      igm_test::perturbed(igm_test::inflated_pillow_with_hole(3, 1, 1), 20, 4),
      igm_test::perturbed(igm_test::disk_and_torus(3, 3), 20, 5)};
  for (const IgmMesh& exact : inputs) {
    // Every vertex UV coordinate that is not an integer shifted by a third of 2^-10, every
    // corner following its vertex.
    const SeamlessStructure s0 = seamless_structure(exact);
    IgmMesh igm = exact;
    for (int c = 0; c < s0.mesh.num_halfedges(); ++c) {
      Point2q x = s0.vertex_uv[s0.mesh.origin(c)];
      if (x.x.get_den() != 1) x.x += Rational(1, 3 * 1024);
      if (x.y.get_den() != 1) x.y += Rational(1, 3 * 1024);
      igm.corner_uv[c / 3][c % 3] = apply(s0.corner_motion[c], x);
    }
    const certify::Options open = igm_test::open_options();
    REQUIRE(certify::certify_igm(certify_input(igm, igm.corner_uv), open).valid());
    const SeamlessStructure s = seamless_structure(igm);
    const DyadicResult r = round_to_dyadic(igm, s);
    REQUIRE(r.stats.on_grid);
    CHECK(r.stats.off_isoline == 0);
    int integers_changed = 0, thirds = 0;
    for (std::size_t f = 0; f < igm.corner_uv.size(); ++f)
      for (int i = 0; i < 3; ++i)
        for (const auto& [before, after] :
             {std::pair{&igm.corner_uv[f][i].x, &r.corner_uv[f][i].x},
              std::pair{&igm.corner_uv[f][i].y, &r.corner_uv[f][i].y}}) {
          if (before->get_den() == 1) integers_changed += *before != *after;
          thirds += before->get_den() % 3 == 0 && *before != *after;
        }
    CHECK(integers_changed == 0);
    CHECK(thirds > 0);
    CHECK(certify::certify_igm(certify_input(igm, r.corner_uv), open).valid());
    IgmMesh rounded = igm;
    rounded.corner_uv = r.corner_uv;
    CHECK(igm_test::structure_difference(s, seamless_structure(rounded)) == "");
    std::ostringstream text;
    write_igm_obj(text, rounded, false);
    CHECK(certify::certify_igm_text(text.str(), open).valid());
  }
}

TEST_CASE("check_map: a sliding vertex moved off its isoline") {
  // The square disk [0, 3]^2: vertex (1, 0) slides along v = 0; moved up by 1/8 its triangles stay
  // positive but its two boundary edges leave the isoline.
  const certify_test::GridPatch g = certify_test::square_disk(3);
  const SeamlessStructure s = seamless_structure(igm_test::lifted(g.igm, igm_test::bumped));
  GridMap map = *round_to_grid(s);
  std::vector<std::array<Vec2d, 3>> corners;
  grid_corners(s, map, corners);
  CHECK(check_map(s, corners).valid());
  const int v = g.id(1, 0);
  REQUIRE(s.isoline_axis[v] == 1);
  map.vertex_uv[v] = {1.25, 0.0};  // along the isoline: fine
  grid_corners(s, map, corners);
  CHECK(check_map(s, corners).valid());
  map.vertex_uv[v] = {1.0, 0.125};
  grid_corners(s, map, corners);
  const MapCheck off = check_map(s, corners);
  CHECK(off.nonpositive == 0);
  CHECK(off.off_isoline == 2);
  REQUIRE(off.first_off_isoline >= 0);
  CHECK((s.mesh.origin(off.first_off_isoline) == v || s.mesh.target(off.first_off_isoline) == v));
  CHECK_FALSE(off.valid());
}
