// Tests of the smoother (smooth/smooth.h): every accepted iterate a valid IGM, the energy never
// rising, transitions and cones untouched, the result certified (from memory and from the doubles
// file) and less distorted; the fallbacks; hostile geometry.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include "distortion.h"
#include "igm/core/error.h"
#include "igm/core/threads.h"
#include "igm/smooth/smooth.h"
#include "same_bits.h"
#include "open_igm.h"
#include "random_mesh.h"
#include "smooth_fixture.h"
#include "test_data.h"

using namespace igm;
using igm_test::certify_uv;

namespace {

// What the on_iterate callback saw: the energies, and how many iterates had a triangle that the
// exact orient2d (run here, on the doubles handed out) does not find strictly positive. With the
// input's structure (open surfaces): how many had a boundary edge off the input's isoline, a cone
// or boundary corner not bit for bit where it was, a sliding vertex off its isoline coordinate.
struct Iterates {
  std::vector<double> energy;
  int with_bad_triangle = 0;
  int with_off_isoline = 0, with_fixed_moved = 0, with_slide_off = 0;
};

// Exact comparison of a double with a rational.
bool same(double x, const Rational& q) { return to_rational(x) == q; }

void watch_boundary(const SeamlessStructure& s, const std::vector<std::array<Vec2d, 3>>& uv,
                    Iterates& seen) {
  auto corner = [&](int c) { return uv[c / 3][c % 3]; };
  bool off = false, moved = false, slid_off = false;
  for (const BoundaryIsoline& e : s.boundary_edges)
    for (const Vec2d& p : {corner(e.halfedge), corner(TriMesh::next(e.halfedge))})
      off = off || !same(e.axis == 0 ? p.x : p.y, Rational(e.value));
  for (int c = 0; c < s.mesh.num_halfedges(); ++c) {
    const int v = s.mesh.origin(c);
    if (s.is_cone(v)) {
      const Point2q exact = apply(s.corner_motion[c], s.vertex_uv[v]);
      moved = moved || !same(corner(c).x, exact.x) || !same(corner(c).y, exact.y);
    }
    if (s.slides(v) && c == s.reference_corner[v]) {
      const int a = s.isoline_axis[v];
      const Rational& fixed = a == 0 ? s.vertex_uv[v].x : s.vertex_uv[v].y;
      slid_off = slid_off || !same(a == 0 ? corner(c).x : corner(c).y, fixed);
    }
  }
  seen.with_off_isoline += off;
  seen.with_fixed_moved += moved;
  seen.with_slide_off += slid_off;
}

SmoothOptions watched(Iterates& seen, int iterations, const SeamlessStructure* open = nullptr) {
  SmoothOptions o;
  o.max_iterations = iterations;
  o.on_iterate = [&seen, open](const SmoothIterate& it) {
    CHECK(it.iteration == static_cast<int>(seen.energy.size()));
    seen.energy.push_back(it.energy);
    for (const auto& t : *it.corner_uv)
      if (orient2d(t[0], t[1], t[2]) != Sign::Positive) {
        ++seen.with_bad_triangle;
        break;
      }
    if (open) watch_boundary(*open, *it.corner_uv, seen);
  };
  return o;
}

// Everything a smoothing must keep: the energy never rises over the accepted iterates, each of
// them is flip-free, the result is certified (in memory, by the smoother's own report, and from
// the doubles file, read back exactly), and its transitions, angles and cones are the input's.
void check_smoothed(const IgmMesh& igm, const SmoothResult& r, const Iterates& seen,
                    const certify::Options& options = {}) {
  CHECK(r.stats.returned == SmoothReturned::Smoothed);
  CHECK(r.stats.dyadic.on_grid);
  REQUIRE(seen.energy.size() == static_cast<std::size_t>(r.stats.iterations) + 1);
  CHECK(seen.energy == r.stats.energy);
  for (std::size_t i = 1; i < seen.energy.size(); ++i) CHECK(seen.energy[i] <= seen.energy[i - 1]);
  for (double e : seen.energy) CHECK(std::isfinite(e));
  CHECK(seen.with_bad_triangle == 0);
  CHECK(seen.with_off_isoline == 0);
  CHECK(seen.with_fixed_moved == 0);
  CHECK(seen.with_slide_off == 0);
  CHECK(r.stats.certified);
  CHECK(r.report.valid());
  CHECK(certify::certify_igm(certify_input(igm, r.corner_uv), options).valid());
  IgmMesh out = igm;
  out.corner_uv = r.corner_uv;
  const SeamlessStructure before = seamless_structure(igm), after = seamless_structure(out);
  CHECK(igm_test::structure_difference(before, after) == "");
  int cone_corners_moved = 0;
  for (int c = 0; c < before.mesh.num_halfedges(); ++c)
    if (before.is_cone(before.mesh.origin(c))) {
      const Point2q &p = igm.corner_uv[c / 3][c % 3], &q = r.corner_uv[c / 3][c % 3];
      cone_corners_moved += p.x != q.x || p.y != q.y;
    }
  CHECK(cone_corners_moved == 0);
  std::ostringstream s;
  write_igm_obj(s, out, false);
  CHECK(certify::certify_igm_text(s.str(), options).valid());
}

}  // namespace

TEST_CASE("the torus from two starts converges to the same map, up to a translation") {
  // The 4 x 4 square torus (its seam triangles are long in 3D, so the map is not an isometry) as
  // it is and with vertex (1, 1) moved: both runs converge, to one map up to the translation of
  // every vertex at once (the energy does not see it).
  const IgmMesh plain = igm_test::square_torus(4);
  const IgmMesh moved = igm_test::moved_torus({Rational(5, 4), Rational(9, 8)});
  Iterates seen_plain, seen_moved;
  SmoothOptions oa = watched(seen_plain, 50), ob = watched(seen_moved, 50);
  oa.tolerance = ob.tolerance = 1e-14;  // Newton's quadratic convergence: a few more iterations
  const SmoothResult a = smooth_igm(plain, oa);
  const SmoothResult b = smooth_igm(moved, ob);
  check_smoothed(plain, a, seen_plain);
  check_smoothed(moved, b, seen_moved);
  CHECK(a.stats.stop == SmoothStop::Converged);
  CHECK(b.stats.stop == SmoothStop::Converged);
  CHECK(b.stats.energy.front() > a.stats.energy.front());
  CHECK(a.stats.energy.back() == doctest::Approx(b.stats.energy.back()).epsilon(1e-8));
  CHECK(a.stats.free_vertices == 16);
  CHECK(a.stats.cones == 0);
  const double dx = to_double(b.corner_uv[0][0].x - a.corner_uv[0][0].x);
  const double dy = to_double(b.corner_uv[0][0].y - a.corner_uv[0][0].y);
  double worst = 0;
  for (std::size_t f = 0; f < a.corner_uv.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      worst = std::max(worst, std::abs(to_double(b.corner_uv[f][i].x - a.corner_uv[f][i].x) - dx));
      worst = std::max(worst, std::abs(to_double(b.corner_uv[f][i].y - a.corner_uv[f][i].y) - dy));
    }
  CHECK(worst < 1e-6);
}

TEST_CASE(
    "generated meshes of genus 1-3: monotone, flip-free, structure kept, certified, less "
    "distorted") {
  for (int genus : {1, 2, 3}) {
    INFO("genus " << genus);
    const IgmMesh igm = igm_test::pipeline_igm(genus, 600 * genus, 7);
    Iterates seen;
    const SmoothResult r = smooth_igm(igm, watched(seen, 25));
    check_smoothed(igm, r, seen);
    const igm_test::Distortion before = igm_test::measure_distortion(igm, igm.corner_uv);
    const igm_test::Distortion after = igm_test::measure_distortion(igm, r.corner_uv);
    MESSAGE("genus " << genus << ": " << igm.triangles.size() << " triangles, "
                     << r.stats.iterations << " iterations, SD " << before.sd_energy << " -> "
                     << after.sd_energy << ", p99 s1/s2 " << before.p99_conformal << " -> "
                     << after.p99_conformal);
    CHECK(after.sd_energy < 0.5 * before.sd_energy);
    CHECK(after.p99_conformal < before.p99_conformal);
    CHECK(r.stats.energy.back() < r.stats.energy.front());
  }
}

TEST_CASE("any genus, both factorizations (simplicial for small systems, supernodal for large), the same iterates for any thread count") {
  for (const int genus : {2, 9}) {
    INFO("genus " << genus);
    const IgmMesh igm = igm_test::pipeline_igm(genus, 500 * genus, 3);
    Iterates seen;
    const SmoothResult r = smooth_igm(igm, watched(seen, 10));
    check_smoothed(igm, r, seen);
    CHECK(r.stats.energy.back() < 0.5 * r.stats.energy.front());
    CHECK(r.stats.factor_entries > 0);
    CHECK(r.stats.factorize_seconds > 0);
    for (int threads : {1, 3}) {
      CAPTURE(threads);
      SmoothResult t;
      Iterates again;
      igm::with_threads(threads, [&] { t = smooth_igm(igm, watched(again, 10)); });
      CHECK(t.stats.energy == r.stats.energy);
      CHECK(igm_test::same_uv(t.corner_uv, r.corner_uv));
    }
  }
  // An IGM whose Newton system is large enough for the supernodal factorization (CHOLMOD's rule).
  if (!igm_test::kSanitized) {
    const IgmMesh big = igm_test::pipeline_igm(3, 20000, 5);
    SmoothOptions o;
    o.max_iterations = 3;
    SmoothResult one, two;
    igm::with_threads(1, [&] { one = smooth_igm(big, o); });
    igm::with_threads(2, [&] { two = smooth_igm(big, o); });
    CHECK(one.stats.supernodal);
    CHECK(one.stats.certified);
    CHECK(two.stats.energy == one.stats.energy);
    CHECK(igm_test::same_uv(two.corner_uv, one.corner_uv));
  }
}

TEST_CASE("the elephant's IGM smooths: less distorted, certified") {
  IGM_REQUIRE_DATA(dir);
  const ValidMesh mesh = load_mesh(dir / "meshes" / "clean" / "elephant.off");
  const IgmMesh igm = compute_igm(mesh, igm_test::paper_affine_map()).igm;
  Iterates seen;
  const SmoothResult r = smooth_igm(igm, watched(seen, 40));
  check_smoothed(igm, r, seen);
  const igm_test::Distortion before = igm_test::measure_distortion(igm, igm.corner_uv);
  const igm_test::Distortion after = igm_test::measure_distortion(igm, r.corner_uv);
  MESSAGE("elephant: " << igm.triangles.size() << " triangles, " << r.stats.iterations
                       << " iterations, SD " << before.sd_energy << " -> " << after.sd_energy
                       << ", p99 s1/s2 " << before.p99_conformal << " -> " << after.p99_conformal);
  CHECK(after.sd_energy < 0.01 * before.sd_energy);
  CHECK(after.p99_conformal < before.p99_conformal);
}

TEST_CASE("a map that does not round onto the grid is returned exact and says so") {
  const Rational eps = make_rational(1, Integer(3) * (Integer(1) << 70));
  const IgmMesh igm = igm_test::sliver_torus(eps);
  const SmoothResult r = smooth_igm(igm);
  CHECK(r.stats.returned == SmoothReturned::InputExact);
  CHECK(r.stats.stop == SmoothStop::NotStarted);
  CHECK(r.stats.iterations == 0);
  CHECK_FALSE(r.stats.dyadic.on_grid);
  CHECK(r.stats.dyadic.nonpositive == 1);
  CHECK(r.stats.dyadic.first_nonpositive == igm_test::kSliverFace);
  CHECK(r.stats.reason.find("stays exact") != std::string::npos);
  CHECK(igm_test::changed_corners(r.corner_uv, igm.corner_uv) == 0);
  CHECK(r.stats.certified);
}

TEST_CASE("hostile geometry: zero-area and extreme triangles, no NaN, certified") {
  using igm_test::Geometry;
  for (const Geometry geometry : {Geometry::Collapse, Geometry::Collinear, Geometry::Coincident,
                                  Geometry::Tiny, Geometry::Huge, Geometry::Mixed, Geometry::Extreme}) {
    igm_test::RandomMeshSpec spec;
    spec.genus = 2;
    spec.faces = 300;
    spec.seed = 11;
    spec.geometry = geometry;
    INFO(igm_test::describe(spec));
    const IgmMesh igm = compute_igm(validate(igm_test::random_closed_mesh(spec)), igm_test::paper_affine_map()).igm;
    // Zero-area triangles, counted on the positions scaled by a power of two to at most 1 (so
    // that tiny and huge coordinates neither underflow nor overflow here).
    double largest = 0;
    for (const Vec3d& p : igm.positions)
      largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    const double k = std::ldexp(1.0, -std::ilogb(largest) - 1);
    int zero_area = 0;
    for (const auto& t : igm.triangles) {
      const Vec3d &a = igm.positions[t[0]], &b = igm.positions[t[1]], &c = igm.positions[t[2]];
      const double u[3] = {k * b.x - k * a.x, k * b.y - k * a.y, k * b.z - k * a.z};
      const double v[3] = {k * c.x - k * a.x, k * c.y - k * a.y, k * c.z - k * a.z};
      const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                           u[0] * v[1] - u[1] * v[0]};
      zero_area += n[0] == 0 && n[1] == 0 && n[2] == 0;
    }
    if (geometry == Geometry::Collapse || geometry == Geometry::Collinear ||
        geometry == Geometry::Coincident)
      REQUIRE(zero_area > 0);
    Iterates seen;
    const SmoothResult r = smooth_igm(igm, watched(seen, 20));
    if (r.stats.returned == SmoothReturned::InputExact) {
      // Rounding onto a double grid would flip a triangle of this map: it stays exact, as given
      // (regression: the message below read the empty energy list).
      MESSAGE(std::string(igm_test::to_string(geometry)) << ": " << r.stats.reason);
      CHECK(r.stats.stop == SmoothStop::NotStarted);
      CHECK(r.stats.energy.empty());
      CHECK(igm_test::changed_corners(r.corner_uv, igm.corner_uv) == 0);
      CHECK(certify_uv(igm, r.corner_uv).valid());
      continue;
    }
    MESSAGE(std::string(igm_test::to_string(geometry))
            << ": " << zero_area << " zero-area triangles of " << igm.triangles.size()
            << "; references enlarged " << r.stats.enlarged_references << ", fattened "
            << r.stats.fattened_references << "; energy " << r.stats.energy.front() << " -> "
            << r.stats.energy.back() << " in " << r.stats.iterations << " iterations");
    CHECK(r.stats.enlarged_references + r.stats.fattened_references >= zero_area);
    check_smoothed(igm, r, seen);
  }
}

TEST_CASE("options, budgets and callbacks") {
  const IgmMesh igm = igm_test::pipeline_igm(2, 400, 5);
  SUBCASE("bad options and positions are errors") {
    SmoothOptions o;
    o.step_fraction = 1;
    CHECK_THROWS_AS(smooth_igm(igm, o), Error);
    o = {};
    o.max_iterations = -1;
    CHECK_THROWS_AS(smooth_igm(igm, o), Error);
    o = {};
    o.tolerance = std::nan("");
    CHECK_THROWS_AS(smooth_igm(igm, o), Error);
    IgmMesh bad = igm;
    bad.positions[3].y = std::nan("");
    const auto e = igm_test::error_of([&] { smooth_igm(bad); });
    REQUIRE(e.has_value());
    CHECK(e->kind() == ErrorKind::NonFinite);
    CHECK(e->elements() == std::vector<std::int64_t>{3});
  }
  SUBCASE("no iteration: the input on the grid, certified") {
    SmoothOptions o;
    o.max_iterations = 0;
    const SmoothResult r = smooth_igm(igm, o);
    CHECK(r.stats.returned == SmoothReturned::InputOnGrid);
    CHECK(r.stats.stop == SmoothStop::IterationBudget);
    CHECK(r.stats.energy.size() == 1);
    CHECK(r.stats.certified);
  }
  SUBCASE("stall: stops after stall_iterations accepted steps in a row below stall_step, the same iterates") {
    SmoothOptions o;
    o.max_iterations = 30;
    std::vector<SmoothProgress> free_run;
    o.progress = [&free_run](const SmoothProgress& p) { free_run.push_back(p); };
    const SmoothResult a = smooth_igm(igm, o);
    REQUIRE(free_run.size() >= 3);
    // a threshold between the steps: the first two in a row below it end the stalled run there
    std::vector<double> steps;
    for (const SmoothProgress& p : free_run) steps.push_back(p.step);
    std::vector<double> sorted = steps;
    std::sort(sorted.begin(), sorted.end());
    const double threshold = std::min(0.999, std::nextafter(sorted[sorted.size() / 2], 2.0));
    std::size_t end = 0;  // iterations until two in a row below the threshold
    for (std::size_t k = 1; k < steps.size() && end == 0; ++k)
      if (steps[k - 1] < threshold && steps[k] < threshold) end = k + 1;
    REQUIRE(end > 0);
    o.stall_step = threshold;
    o.stall_iterations = 2;
    o.progress = nullptr;
    const SmoothResult b = smooth_igm(igm, o);
    CHECK(b.stats.stop == SmoothStop::Stalled);
    CHECK(b.stats.iterations == static_cast<int>(end));
    for (std::size_t i = 0; i < b.stats.energy.size(); ++i) CHECK(b.stats.energy[i] == a.stats.energy[i]);
    CHECK(b.stats.certified);
    o.stall_step = 1;
    CHECK_THROWS_AS(smooth_igm(igm, o), Error);
    o.stall_step = 0.5;
    o.stall_iterations = 0;
    CHECK_THROWS_AS(smooth_igm(igm, o), Error);
  }
  SUBCASE("a relative energy decrease below the threshold stops after that iteration, the same iterates up to it") {
    SmoothOptions o;
    o.max_iterations = 30;
    const SmoothResult a = smooth_igm(igm, o);
    const std::vector<double>& e = a.stats.energy;
    REQUIRE(e.size() >= 4);
    // a threshold between the decreases of iterations 2 and 3 (relative to the energy before)
    std::vector<double> rel;
    for (std::size_t k = 1; k < e.size(); ++k) rel.push_back((e[k - 1] - e[k]) / e[k - 1]);
    const double threshold = rel[2] * 1.0000001;
    std::size_t end = 0;
    for (std::size_t k = 0; k < rel.size() && end == 0; ++k)
      if (rel[k] < threshold) end = k + 1;
    REQUIRE(end > 0);
    o.min_relative_decrease = threshold;
    const SmoothResult b = smooth_igm(igm, o);
    CHECK(b.stats.stop == SmoothStop::SmallDecrease);
    CHECK(b.stats.iterations == static_cast<int>(end));
    for (std::size_t i = 0; i < b.stats.energy.size(); ++i) CHECK(b.stats.energy[i] == e[i]);
    CHECK(b.stats.certified);
    o.min_relative_decrease = 1;
    CHECK_THROWS_AS(smooth_igm(igm, o), Error);
  }
  SUBCASE("a time budget stops after the iteration that passes it; progress sees every iteration") {
    SmoothOptions o;
    o.time_budget_seconds = 1e-12;
    std::vector<SmoothProgress> progress;
    o.progress = [&progress](const SmoothProgress& p) { progress.push_back(p); };
    const SmoothResult r = smooth_igm(igm, o);
    CHECK(r.stats.stop == SmoothStop::TimeBudget);
    CHECK(r.stats.iterations == 1);
    REQUIRE(progress.size() == 1);
    CHECK(progress[0].iteration == 1);
    CHECK(progress[0].energy == r.stats.energy[1]);
    CHECK(progress[0].step > 0);
    CHECK(progress[0].step <= 1);
    CHECK(r.stats.certified);
  }
  SUBCASE("without the certifier: not certified, not claimed") {
    SmoothOptions o;
    o.max_iterations = 2;
    o.certify = false;
    const SmoothResult r = smooth_igm(igm, o);
    CHECK_FALSE(r.stats.certified);
    CHECK(certify_uv(igm, r.corner_uv).valid());
  }
}

TEST_CASE(
    "open surfaces and two components: monotone, flip-free, boundary on its isolines, corners and "
    "cones fixed, sliding along the isolines, certified, less distorted") {
  struct Case {
    const char* name;
    IgmMesh igm;
  };
  const Case cases[] = {
      {"disk 5", igm_test::lifted(certify_test::square_disk(5).igm, igm_test::bumped)},
      {"cylinder 8 x 4", igm_test::tube(8, 4)},
      {"L-shape 3", igm_test::lifted(certify_test::l_shape(3).igm, igm_test::bumped)},
      {"slit 6", igm_test::lifted(certify_test::slit_square(6, 3, 3).igm, igm_test::bumped)},
      {"pillow 4 with a hole", igm_test::inflated_pillow_with_hole(4, 1, 2)},
      {"disk 4 and torus 4", igm_test::disk_and_torus(4, 4)},
  };
  std::uint32_t seed = 1;
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const IgmMesh igm = igm_test::perturbed(c.igm, 20, seed++);
    const certify::Options open = igm_test::open_options();
    REQUIRE(certify::certify_igm(certify_input(igm, igm.corner_uv), open).valid());
    const SeamlessStructure s = seamless_structure(igm);
    Iterates seen;
    const SmoothResult r = smooth_igm(igm, watched(seen, 30, &s));
    check_smoothed(igm, r, seen, open);
    // The smoother's own report judged the open surface as such.
    CHECK(r.report.check(4)->count("boundary_vertices") > 0);
    int interior = 0, sliding = 0, cones = 0, corners = 0, slid = 0;
    for (int v = 0; v < s.num_vertices(); ++v) {
      if (!s.boundary[v]) ++(s.is_cone(v) ? cones : interior);
      if (s.boundary[v]) ++(s.is_cone(v) ? corners : sliding);
    }
    CHECK(r.stats.free_vertices == interior);
    CHECK(r.stats.sliding_vertices == sliding);
    CHECK(r.stats.cones == cones);
    CHECK(r.stats.boundary_corners == corners);
    for (int v = 0; v < s.num_vertices(); ++v)  // the sliding coordinate moves
      if (s.slides(v)) {
        const int h = s.reference_corner[v], a = 1 - s.isoline_axis[v];
        const Point2q &p = igm.corner_uv[h / 3][h % 3], &q = r.corner_uv[h / 3][h % 3];
        slid += (a == 0 ? p.x != q.x : p.y != q.y);
      }
    if (sliding > 0) CHECK(slid * 2 > sliding);
    const igm_test::Distortion before = igm_test::measure_distortion(igm, igm.corner_uv);
    const igm_test::Distortion after = igm_test::measure_distortion(igm, r.corner_uv);
    MESSAGE(std::string(c.name) << ": " << igm.triangles.size() << " triangles, "
                                << r.stats.iterations << " iterations ("
                                << std::string(to_string(r.stats.stop)) << "), " << sliding
                   << " sliding, SD " << before.sd_energy << " -> " << after.sd_energy
                   << ", p99 s1/s2 " << before.p99_conformal << " -> " << after.p99_conformal);
    CHECK(after.sd_energy < before.sd_energy);
    CHECK(r.stats.energy.back() < r.stats.energy.front());
  }
}

TEST_CASE("an open surface with nothing to move: the square disk of one cell, four corners") {
  const IgmMesh igm = igm_test::lifted(certify_test::square_disk(1).igm, igm_test::bumped);
  const SmoothResult r = smooth_igm(igm);
  CHECK(r.stats.stop == SmoothStop::NothingToMove);
  CHECK(r.stats.returned == SmoothReturned::InputOnGrid);
  CHECK(r.stats.boundary_corners == 4);
  CHECK(r.stats.free_vertices + r.stats.sliding_vertices + r.stats.cones == 0);
  CHECK(igm_test::changed_corners(r.corner_uv, igm.corner_uv) == 0);
  CHECK(r.stats.certified);
}

namespace {

// The edges (a < b) of `igm` whose two corner UVs in a face share an integer u or v, neither end
// a cone or on the boundary: the edges of the layout's arcs.
std::vector<std::pair<int, int>> isoline_edges_of(const igm::IgmMesh& igm) {
  const igm::SeamlessStructure s = igm::seamless_structure(igm);
  std::set<std::pair<int, int>> out;
  for (std::size_t t = 0; t < igm.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int a = igm.triangles[t][i], b = igm.triangles[t][(i + 1) % 3];
      const igm::Point2q &p = igm.corner_uv[t][i], &q = igm.corner_uv[t][(i + 1) % 3];
      const bool on = (p.x == q.x && p.x.get_den() == 1) || (p.y == q.y && p.y.get_den() == 1);
      if (on && !s.is_cone(a) && !s.is_cone(b)) out.insert({std::min(a, b), std::max(a, b)});
    }
  return {out.begin(), out.end()};
}

// How many of `edges` are off every integer isoline in some face beside them.
int off_isolines(const igm::IgmMesh& igm, const std::vector<std::array<igm::Point2q, 3>>& uv,
                 const std::vector<std::pair<int, int>>& edges) {
  const std::set<std::pair<int, int>> wanted(edges.begin(), edges.end());
  std::set<std::pair<int, int>> off;
  for (std::size_t t = 0; t < igm.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int a = igm.triangles[t][i], b = igm.triangles[t][(i + 1) % 3];
      if (!wanted.count({std::min(a, b), std::max(a, b)})) continue;
      const igm::Point2q &p = uv[t][i], &q = uv[t][(i + 1) % 3];
      if (!((p.x == q.x && p.x.get_den() == 1) || (p.y == q.y && p.y.get_den() == 1)))
        off.insert({std::min(a, b), std::max(a, b)});
    }
  return static_cast<int>(off.size());
}

}  // namespace

TEST_CASE("held edges stay on their integer isolines while smoothing (issue 45: feature edges)") {
  const igm::IgmMesh igm = igm_test::pipeline_igm(2, 1500, 3);
  const std::vector<std::pair<int, int>> edges = isoline_edges_of(igm);
  REQUIRE(edges.size() >= 20);
  igm::SmoothOptions o;
  o.max_iterations = 4;
  // Without holding them, smoothing moves some of them off (the test can fail).
  const igm::SmoothResult free = igm::smooth_igm(igm, o);
  REQUIRE(free.stats.iterations >= 1);
  CHECK(off_isolines(igm, free.corner_uv, edges) > 0);
  o.isoline_edges = edges;
  const igm::SmoothResult held = igm::smooth_igm(igm, o);
  REQUIRE(held.stats.iterations >= 1);
  CHECK(held.stats.energy.back() < held.stats.energy.front());
  CHECK(off_isolines(igm, held.corner_uv, edges) == 0);
  CHECK(igm_test::certify_uv(igm, held.corner_uv).valid());
  // An edge that is not one, or one off every integer isoline: typed errors naming it.
  o.isoline_edges = {{0, 0}};
  CHECK_THROWS_AS(igm::smooth_igm(igm, o), igm::Error);
  const int a = igm.triangles[0][0], b = igm.triangles[0][1];
  const igm::Point2q &p = igm.corner_uv[0][0], &q = igm.corner_uv[0][1];
  if (!((p.x == q.x && p.x.get_den() == 1) || (p.y == q.y && p.y.get_den() == 1))) {
    o.isoline_edges = {{a, b}};
    CHECK_THROWS_AS(igm::smooth_igm(igm, o), igm::Error);
  }
}
