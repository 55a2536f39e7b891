// Tests of the cross field and its singularities (field/cross_field.h): cones where the geometry
// puts them (cube corners, none on a torus of revolution), Poincare-Hopf on every shared and
// generated mesh, the integer valences against an independent floating-point index, boundary
// alignment, invariance under rigid motions, determinism, cone pair cancellation, typed errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "igm/core/error.h"
#include "igm/field/cross_field.h"
#include "igm/field/curvature.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"
#include "test_data.h"
#include "test_surfaces.h"

using namespace igm;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kQuarter = kPi / 2;

using igm_test::from;
using igm_test::subdivided_cube;
using igm_test::Surface;
using igm_test::generated;
using igm_test::surface_of;
using igm_test::torus;

Surface load(const std::filesystem::path& path) {
  const SurfaceSet set = validate_surfaces(read_soup(path));
  REQUIRE(set.components.size() == 1);
  return surface_of(set.components[0]);
}

std::vector<std::filesystem::path> sorted_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(const Vec3d& a) { return std::sqrt(dot(a, a)); }

// x - (nearest multiple of m).
double off_multiple(double x, double m) { return x - m * std::round(x / m); }

// The field's index at every vertex from floating-point geometry alone, independently of the
// integer formula: interior (K_v + sum delta) / (pi/2) = 4 - valence, boundary
// (interior angle - sum delta - delta_in + delta_out) / (pi/2) = k. Corner angles from the 3D
// positions; transport from the angles of the shared edge in the two faces' 3D frames; delta
// the field's deviation reduced to the nearest quarter turn. Returns the largest distance of the
// float index from the integer one.
double index_mismatch(const Surface& s, const CrossField& f) {
  const TriMesh& m = s.mesh;
  const auto& p = s.positions;
  auto angle_in = [&](int face, const Vec3d& d) {
    return std::atan2(dot(d, f.frames.axis_y[face]), dot(d, f.frames.axis_x[face]));
  };
  auto vec = [&](int h) { return sub(p[m.target(h)], p[m.origin(h)]); };
  auto delta = [&](int h) {  // across the edge of h, from face(h) into face(twin h)
    const int t = m.twin(h);
    const Vec3d e = vec(h);
    const double rho = angle_in(TriMesh::face(t), e) - angle_in(TriMesh::face(h), e);
    return off_multiple(f.theta[TriMesh::face(t)] - f.theta[TriMesh::face(h)] - rho, kQuarter);
  };
  auto boundary_delta = [&](int b) { return off_multiple(angle_in(TriMesh::face(b), vec(b)) - f.theta[TriMesh::face(b)], kQuarter); };
  double worst = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    const int first = m.vertex_halfedge(v);
    double angles = 0, deltas = 0;
    int o = first, b_in = -1;
    for (int step = 0; step < m.num_halfedges(); ++step) {
      const int pr = TriMesh::prev(o);
      angles += std::atan2(norm(cross(vec(o), vec(pr))), -dot(vec(o), vec(pr)));
      if (m.twin(pr) < 0) {
        b_in = pr;
        break;
      }
      deltas += delta(pr);
      o = m.twin(pr);
      if (o == first) break;
    }
    double value = 0;
    int expected = 0;
    if (b_in < 0) {
      value = (2 * kPi - angles + deltas) / kQuarter;
      expected = 4 - f.valence[v];
    } else {
      value = (angles - deltas - boundary_delta(b_in) + boundary_delta(first)) / kQuarter;
      expected = f.valence[v];
    }
    worst = std::max(worst, std::fabs(value - expected));
  }
  return worst;
}

// Every check that holds for any field: sizes, Poincare-Hopf (exact), matchings antisymmetric,
// the float index equal to the integer one, cones listed exactly.
void check_field(const Surface& s, const CrossField& f, const std::string& what) {
  INFO(what);
  const TriMesh& m = s.mesh;
  REQUIRE(f.theta.size() == static_cast<std::size_t>(m.num_faces()));
  REQUIRE(f.valence.size() == static_cast<std::size_t>(m.num_vertices()));
  CHECK(check_poincare_hopf(m, f) == "");
  int bad_theta = 0, bad_matching = 0;
  for (int fc = 0; fc < m.num_faces(); ++fc) bad_theta += !(f.theta[fc] >= 0 && f.theta[fc] < kQuarter);
  for (int h = 0; h < m.num_halfedges(); ++h) {
    const int t = m.twin(h);
    if (t < 0)
      bad_matching += f.matching[h] != 0;
    else
      bad_matching += (f.matching[h] + f.matching[t]) % 4 != 0 || f.period[h] != -f.period[t] ||
                      f.matching[h] != ((-f.period[h]) % 4 + 4) % 4;
  }
  CHECK(bad_theta == 0);
  CHECK(bad_matching == 0);
  CHECK(index_mismatch(s, f) < 1e-6);
  std::size_t cones = 0, corners = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (f.on_boundary[v])
      corners += f.valence[v] != 2;
    else
      cones += f.valence[v] != 4;
  }
  CHECK(f.cones.size() == cones);
  CHECK(f.corners.size() == corners);
}

// Boundary alignment: every face with a boundary edge has one as its frame's reference, the
// longest of its boundary edges, and theta exactly 0, so direction 0 runs along it (checked in
// 3D against the edge).
void check_boundary_alignment(const Surface& s, const CrossField& f) {
  const TriMesh& m = s.mesh;
  int constrained = 0, bad = 0;
  for (int fc = 0; fc < m.num_faces(); ++fc) {
    double longest = 0;
    int expected = -1;
    for (int i = 0; i < 3; ++i) {
      const int h = 3 * fc + i;
      const double len = norm(sub(s.positions[m.target(h)], s.positions[m.origin(h)]));
      if (m.twin(h) < 0 && len > longest) longest = len, expected = h;
    }
    if (expected < 0) continue;
    ++constrained;
    const int r = f.frames.reference[fc];
    const Vec3d e = sub(s.positions[m.target(r)], s.positions[m.origin(r)]);
    const Vec3d d = field_direction(f, fc, 0);
    bad += r != expected || f.theta[fc] != 0.0 || norm(cross(d, e)) > 1e-12 * norm(e) || !(dot(d, e) > 0);
  }
  CHECK(bad == 0);
  CHECK(constrained > 0);
  CHECK(f.stats.constrained_faces == constrained);
}

std::vector<std::pair<int, int>> cone_list(const CrossField& f) {
  std::vector<std::pair<int, int>> r;
  for (const Cone& c : f.cones) r.push_back({c.vertex, c.valence});
  for (const Cone& c : f.corners) r.push_back({c.vertex, -c.valence});
  return r;
}

}  // namespace

TEST_CASE("cross field: a cube has exactly 8 valence-3 cones, at its corners") {
  for (int n : {1, 2, 5}) {
    const Surface s = subdivided_cube(n);
    for (double w : {0.0, 10.0}) {
      CrossFieldOptions o;
      o.alignment = w;
      const CrossField f = compute_cross_field(s.mesh, s.positions, o);
      check_field(s, f, "cube " + std::to_string(n));
      REQUIRE(f.cones.size() == 8);
      for (const Cone& c : f.cones) {
        CHECK(c.valence == 3);
        const Vec3d& p = s.positions[c.vertex];
        CHECK((std::fabs(p.x) == 1 && std::fabs(p.y) == 1 && std::fabs(p.z) == 1));
      }
    }
  }
  IGM_REQUIRE_DATA(dir);
  const ValidMesh cube = load_mesh(dir / "meshes/clean/cube.off");
  const Surface s{cube.mesh, cube.positions};
  for (FieldSolver solver : {FieldSolver::InverseIteration, FieldSolver::ShiftInvertLanczos}) {
    CrossFieldOptions o;
    o.solver = solver;
    const CrossField f = compute_cross_field(s.mesh, s.positions, o);
    check_field(s, f, to_string(solver));
    CHECK(f.cones.size() == 8);  // every vertex of cube.off is a corner
    for (const Cone& c : f.cones) CHECK(c.valence == 3);
  }
}

TEST_CASE("cross field: a torus of revolution has no cone, and the aligned field follows its principal directions") {
  const Surface s = torus(3, 1, 48, 16);
  CrossFieldOptions smoothest;
  smoothest.alignment = 0;
  const CrossField smooth = compute_cross_field(s.mesh, s.positions, smoothest);
  check_field(s, smooth, "smoothest");
  CHECK(smooth.cones.empty());
  CrossFieldOptions o;
  o.alignment = 100;
  const CrossField aligned = compute_cross_field(s.mesh, s.positions, o);
  check_field(s, aligned, "aligned");
  CHECK(aligned.cones.empty());
  // Principal directions of the torus: the parallels (around the z axis) and the meridians. Every
  // face's field is within 3 degrees of the parallel through its centroid.
  double worst = 0;
  for (int fc = 0; fc < s.mesh.num_faces(); ++fc) {
    const auto v = s.mesh.face_vertices(fc);
    const Vec3d c{(s.positions[v[0]].x + s.positions[v[1]].x + s.positions[v[2]].x) / 3,
                  (s.positions[v[0]].y + s.positions[v[1]].y + s.positions[v[2]].y) / 3, 0};
    const Vec3d parallel{-c.y, c.x, 0};
    const Vec3d d = field_direction(aligned, fc, 0);
    const double a = std::acos(std::min(1.0, std::fabs(dot(d, parallel)) / norm(parallel)));
    worst = std::max(worst, std::min(a, kQuarter - a));
  }
  CHECK(worst < 3 * kPi / 180);
}

TEST_CASE("cross field: Poincare-Hopf and the float index on every shared closed mesh") {
  IGM_REQUIRE_DATA(dir);
  const std::vector<std::filesystem::path> files = sorted_files(dir / "meshes/clean");
  REQUIRE(files.size() >= 20);
  for (const auto& path : files) {
    if (igm_test::kSanitized && path.stem() == "armadillo") continue;  // 52k faces: Release only
    const Surface s = load(path);
    const CrossField f = compute_cross_field(s.mesh, s.positions);
    check_field(s, f, path.stem().string());
    CHECK(f.corners.empty());
    CHECK(f.stats.constrained_faces == 0);
  }
}

TEST_CASE("cross field: Poincare-Hopf on generated meshes of genus 0 to 20, closed and with boundaries") {
  for (int genus = 0; genus <= 20; ++genus) {
    const Surface s = generated(genus, 300 + 150 * genus, 0, 7 + genus);
    const CrossField f = compute_cross_field(s.mesh, s.positions);
    check_field(s, f, "closed genus " + std::to_string(genus));
    // The generator doubles a flat region: the field's cones must carry 4 chi = 8 - 8 g.
    int sum = 0;
    for (const Cone& c : f.cones) sum += 4 - c.valence;
    CHECK(sum == 8 - 8 * genus);
  }
  for (int genus : {0, 1, 3}) {
    for (int loops : {1, 2, 5}) {
      const Surface s = generated(genus, 3000, loops, 11 + genus);
      CrossFieldOptions o;
      o.alignment = 10;
      const CrossField f = compute_cross_field(s.mesh, s.positions, o);
      check_field(s, f, "open genus " + std::to_string(genus) + " loops " + std::to_string(loops));
      check_boundary_alignment(s, f);
    }
  }
}

TEST_CASE("cross field: the shared open meshes are aligned with every boundary edge") {
  IGM_REQUIRE_DATA(dir);
  const std::vector<std::filesystem::path> files = sorted_files(dir / "meshes/open");
  REQUIRE(files.size() >= 10);
  for (const auto& path : files) {
    const Surface s = load(path);
    for (double w : {0.0, 10.0}) {
      CrossFieldOptions o;
      o.alignment = w;
      const CrossField f = compute_cross_field(s.mesh, s.positions, o);
      check_field(s, f, path.stem().string() + " alignment " + std::to_string(w));
      check_boundary_alignment(s, f);
      CHECK(f.stats.linear);
    }
  }
  // plane.off: a flat square grid: the field is parallel, no cone, 4 convex corners (k = 1).
  const Surface plane = load(dir / "meshes/open/plane.off");
  const CrossField f = compute_cross_field(plane.mesh, plane.positions);
  CHECK(f.cones.empty());
  REQUIRE(f.corners.size() == 4);
  for (const Cone& c : f.corners) CHECK(c.valence == 1);
}

TEST_CASE("cross field: faces with two or three boundary edges") {
  // One triangle: three boundary edges, aligned with the longest; the field sees the other two
  // edges at their nearest quarter turns (Poincare-Hopf: sum (2 - k) = 4).
  const Surface tri = from({{0, 0, 0}, {3, 0, 0}, {0, 2, 0}}, {{0, 1, 2}}, true);
  const CrossField f1 = compute_cross_field(tri.mesh, tri.positions);
  check_field(tri, f1, "one triangle");
  check_boundary_alignment(tri, f1);
  CHECK(f1.frames.reference[0] == 1);  // (3,0) -> (0,2), length sqrt(13)
  // A fan of two triangles (a square with one diagonal): each face has two boundary edges.
  const Surface sq = from({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}, true);
  const CrossField f2 = compute_cross_field(sq.mesh, sq.positions);
  check_field(sq, f2, "square");
  check_boundary_alignment(sq, f2);
  CHECK(f2.cones.empty());
  REQUIRE(f2.corners.size() == 4);
  for (const Cone& c : f2.corners) CHECK(c.valence == 1);
}

TEST_CASE("cross field: rigid motions and scaling do not change the cones") {
  auto moved = [](const Surface& s, double a, double b, const Vec3d& t) {
    Surface r = s;
    for (Vec3d& p : r.positions) {
      const Vec3d q{p.x * std::cos(a) - p.y * std::sin(a), p.x * std::sin(a) + p.y * std::cos(a), p.z};
      p = {3 * q.x + t.x, 3 * (q.y * std::cos(b) - q.z * std::sin(b)) + t.y, 3 * (q.y * std::sin(b) + q.z * std::cos(b)) + t.z};
    }
    return r;
  };
  std::vector<Surface> meshes{generated(3, 2000, 0, 5), generated(1, 2000, 2, 6)};
  if (auto dir = igm_test::data_dir()) {
    meshes.push_back(load(*dir / "meshes/clean/elephant.off"));
    meshes.push_back(load(*dir / "meshes/open/nefertiti.off"));
  }
  for (std::size_t i = 0; i < meshes.size(); ++i)
    for (double w : {0.0, 10.0}) {
      const Surface& s = meshes[i];
      INFO("mesh " << i << " alignment " << w);
      CrossFieldOptions o;
      o.alignment = w;
      const CrossField f = compute_cross_field(s.mesh, s.positions, o);
      const auto base = cone_list(f);
      CHECK(!base.empty());
      for (const auto& [a, b, t] : {std::tuple{0.7, 0.3, Vec3d{5, -2, 1}}, std::tuple{2.1, -1.2, Vec3d{-100, 30, 7}}}) {
        const Surface r = moved(s, a, b, t);
        const CrossField g = compute_cross_field(r.mesh, r.positions, o);
        CHECK(cone_list(g) == base);
        CHECK(std::fabs(g.stats.energy - f.stats.energy) <= 1e-9 * f.stats.energy);
        CHECK(std::fabs(g.stats.mean_edge_length - 3 * f.stats.mean_edge_length) <= 1e-12 * g.stats.mean_edge_length);
      }
    }
}

TEST_CASE("cross field: two runs give the same bytes") {
  std::vector<Surface> meshes{generated(2, 3000, 0, 9), generated(0, 3000, 3, 9)};
  if (auto dir = igm_test::data_dir()) meshes.push_back(load(*dir / "meshes/clean/hand.off"));
  for (const Surface& s : meshes)
    for (bool cleanup : {false, true}) {
      CrossFieldOptions o;
      o.remove_close_pairs = cleanup;
      const CrossField a = compute_cross_field(s.mesh, s.positions, o);
      const CrossField b = compute_cross_field(s.mesh, s.positions, o);
      CHECK(a.theta == b.theta);  // bitwise: doubles compared with ==
      CHECK(a.matching == b.matching);
      CHECK(a.valence == b.valence);
      CHECK(a.stats.iterations == b.stats.iterations);
    }
}

TEST_CASE("cross field: close pairs are cancelled without new cones outside valence 3..5") {
  IGM_REQUIRE_DATA(dir);
  for (const char* name : {"hand", "elephant", "cow"}) {
    const Surface s = load(dir / "meshes/clean" / (std::string(name) + ".off"));
    CrossFieldOptions o;
    o.remove_close_pairs = false;
    o.split_valence1 = false;
    o.split_valence2 = false;
    const CrossField before = compute_cross_field(s.mesh, s.positions, o);
    o.remove_close_pairs = true;
    const CrossField after = compute_cross_field(s.mesh, s.positions, o);
    INFO(name);
    check_field(s, after, name);
    REQUIRE(!before.close_pairs.empty());
    CHECK(after.stats.cones_before_cleanup == static_cast<int>(before.cones.size()));
    CHECK(after.stats.pairs_before_cleanup == static_cast<int>(before.close_pairs.size()));
    CHECK(after.cones.size() < before.cones.size());
    CHECK(after.close_pairs.size() < before.close_pairs.size());
    // Each kept round removes pairs; no vertex leaves 3..5 that was inside it before.
    for (int v = 0; v < s.mesh.num_vertices(); ++v)
      if (after.valence[v] < 3 || after.valence[v] > 5) CHECK(after.valence[v] == before.valence[v]);
    // The pairs reported are within the bound, closest first.
    for (std::size_t i = 0; i < before.close_pairs.size(); ++i) {
      const ConePair& p = before.close_pairs[i];
      CHECK(p.distance <= o.close_pair_distance);
      CHECK(before.valence[p.positive] + before.valence[p.negative] == 8);
      if (i > 0) CHECK(before.close_pairs[i - 1].distance <= p.distance);
    }
  }
}

TEST_CASE("cross field: cones of valence 2 and 6 are split in two") {
  // The generator doubles a flat region: the outer square's corners are vertices of angle pi
  // (index 1/2, valence 2), the square holes' corners of angle 3 pi (valence 6).
  for (int genus : {0, 2}) {
    const Surface s = generated(genus, 4000, 0, 21);
    CrossFieldOptions o;
    o.remove_close_pairs = false;
    o.split_valence2 = false;
    const CrossField raw = compute_cross_field(s.mesh, s.positions, o);
    CHECK(raw.stats.valence_count[2] == 4);
    CHECK(raw.stats.valence_count[6] == 4 * genus);
    o.split_valence2 = true;
    o.split_valence6 = true;
    const CrossField split = compute_cross_field(s.mesh, s.positions, o);
    check_field(s, split, "split genus " + std::to_string(genus));
    CHECK(split.stats.valence_count[2] == 0);
    CHECK(split.stats.valence_count[6] == 0);
    CHECK(split.stats.valence_count[3] == raw.stats.valence_count[3] + 8);
    CHECK(split.stats.valence_count[5] == raw.stats.valence_count[5] + 8 * genus);
    // The halves are at least split_distance mean edges apart: no two cones adjacent.
    for (const Cone& c : split.cones) {
      const int first = s.mesh.vertex_halfedge(c.vertex);
      int h = first;
      do {
        CHECK(split.valence[s.mesh.target(h)] == 4);
        h = s.mesh.next_around_origin(h);
      } while (h != first);
    }
  }
}

// The cleanup's outcome on a shared mesh whose first moves are refused: no cone of valence <= 2
// or >= 7 left, and at least one move refused on the way.
void check_cleanup_clears(const Surface& s, const CrossField& after, const std::string& name) {
  INFO(name);
  check_field(s, after, name);
  for (int v : {0, 1, 2, 7, 8}) CHECK(after.stats.valence_count[v] == 0);
  CHECK(after.stats.cleanup_rejected > 0);
}

TEST_CASE("cross field: a refused split tries the next partner, and a cone of valence 7 gives a quarter turn away") {
  IGM_REQUIRE_DATA(dir);
  // hand.off: vertex 1173 (valence 2) has a valence-6 cone a few edges away; its first split
  // re-solves into a valence 7 there (refused), and the same partner again would fail every round.
  const Surface hand = load(dir / "meshes/clean/hand.off");
  CrossFieldOptions o;
  o.split_valence2 = false;
  REQUIRE(compute_cross_field(hand.mesh, hand.positions, o).valence[1173] == 2);
  o.split_valence2 = true;
  const CrossField hand_after = compute_cross_field(hand.mesh, hand.positions, o);
  check_cleanup_clears(hand, hand_after, "hand");
  CHECK(hand_after.valence[1173] == 3);
  // bull.off: the aligned field has a valence-7 cone and two valence-2 cones; the first partner of
  // vertex 524's split likewise puts the quarter turn on a valence-6 cone next to it.
  const Surface bull = load(dir / "meshes/clean/bull.off");
  o.split_valence7 = false;
  const CrossField without = compute_cross_field(bull.mesh, bull.positions, o);
  REQUIRE(without.stats.valence_count[7] + without.stats.valence_count[8] > 0);
  o.split_valence7 = true;
  check_cleanup_clears(bull, compute_cross_field(bull.mesh, bull.positions, o), "bull");
}

TEST_CASE("cross field: a cone of angle 0 at a spike is raised to valence 1") {
  IGM_REQUIRE_DATA(dir);
  // mannequin-devil.off: vertex 11829 is a spike tip (corner angles summing to 116.5 degrees);
  // the curvature-aligned field turns once more around it (valence 0: no seamless map).
  const Surface s = load(dir / "meshes/open/mannequin-devil.off");
  CrossFieldOptions o;
  o.remove_close_pairs = false;
  o.split_valence1 = false;
  o.split_valence2 = false;
  const CrossField before = compute_cross_field(s.mesh, s.positions, o);
  REQUIRE(before.valence[11829] == 0);
  CHECK(seamless_obstruction(s.mesh, before).find("vertex 11829") != std::string::npos);
  o.remove_close_pairs = true;
  const CrossField after = compute_cross_field(s.mesh, s.positions, o);
  check_field(s, after, "mannequin-devil");
  CHECK(after.valence[11829] == 1);
  CHECK(seamless_obstruction(s.mesh, after) == "");
}

TEST_CASE("cross field: a cone of valence 1 at a sharp tip is split into three of valence 3") {
  const Surface s = igm_test::pencil(12, 6, 3.5);
  const int apex = 0;
  CrossFieldOptions o;
  o.split_valence1 = false;
  const CrossField before = compute_cross_field(s.mesh, s.positions, o);
  check_field(s, before, "pencil without the split");
  REQUIRE(before.valence[apex] == 1);
  o.split_valence1 = true;
  const CrossField after = compute_cross_field(s.mesh, s.positions, o);
  check_field(s, after, "pencil");
  CHECK(after.valence[apex] == 3);
  // The three quarter turns of the tip now sit on three vertices of valence 3: the pencil's
  // cones are eight of valence 3 (as a cube's), in at least the two rounds a split of a valence
  // 1 takes.
  CHECK(after.stats.valence_count[3] == 8);
  CHECK(after.cones.size() == 8);
  CHECK(after.stats.cleanup_rounds >= 2);
}

TEST_CASE("cross field: the rotation along a loop of faces") {
  const Surface s = generated(2, 2000, 0, 3);
  const CrossField f = compute_cross_field(s.mesh, s.positions);
  REQUIRE(!f.cones.empty());
  for (int v = 0; v < s.mesh.num_vertices(); ++v) {
    // Around v counter-clockwise: from the face of each outgoing half-edge o over prev(o).
    std::vector<int> crossed;
    const int first = s.mesh.vertex_halfedge(v);
    int o = first;
    do {
      crossed.push_back(TriMesh::prev(o));
      o = s.mesh.twin(TriMesh::prev(o));
    } while (o != first);
    CHECK(field_rotation(s.mesh, f, crossed) == ((4 - f.valence[v]) % 4 + 4) % 4);
  }
  const int h = s.mesh.vertex_halfedge(0);
  CHECK_THROWS_AS(field_rotation(s.mesh, f, {TriMesh::prev(h), TriMesh::next(h)}), Error);
}

TEST_CASE("cross field: the cone sets no seamless map has") {
  const Surface t = torus(3, 1, 24, 8);
  CrossFieldOptions o;
  o.alignment = 0;
  CrossField f = compute_cross_field(t.mesh, t.positions, o);
  CHECK(seamless_obstruction(t.mesh, f) == "");
  // One +-1/4 pair on the torus (valences set by hand: the check reads only the integers).
  f.valence[3] = 3;
  f.valence[40] = 5;
  f.cones = {{3, 3}, {40, 5}};
  CHECK(check_poincare_hopf(t.mesh, f) == "");
  CHECK(seamless_obstruction(t.mesh, f).find("torus") != std::string::npos);
  // Two pairs are fine.
  f.valence[60] = 3;
  f.valence[90] = 5;
  f.cones = {{3, 3}, {40, 5}, {60, 3}, {90, 5}};
  CHECK(seamless_obstruction(t.mesh, f) == "");
  // A cone of valence 0 (angle 0).
  const Surface c = subdivided_cube(2);
  CrossField g = compute_cross_field(c.mesh, c.positions);
  CHECK(seamless_obstruction(c.mesh, g) == "");
  const int v = g.cones.front().vertex;
  g.valence[v] = 0;
  CHECK(seamless_obstruction(c.mesh, g).find("vertex " + std::to_string(v)) != std::string::npos);
  // Every shared mesh's field passes.
  IGM_REQUIRE_DATA(dir);
  for (const char* name : {"clean/elephant", "clean/knot", "clean/pipe", "open/head", "open/plane"}) {
    const Surface s = load(dir / "meshes" / (std::string(name) + ".off"));
    CHECK_MESSAGE(seamless_obstruction(s.mesh, compute_cross_field(s.mesh, s.positions)) == "", name);
  }
}

TEST_CASE("cross field: Poincare-Hopf check can fail") {
  const Surface s = subdivided_cube(2);
  CrossField f = compute_cross_field(s.mesh, s.positions);
  REQUIRE(check_poincare_hopf(s.mesh, f) == "");
  f.valence[f.cones.front().vertex] = 4;
  CHECK(check_poincare_hopf(s.mesh, f).find("Poincare-Hopf") != std::string::npos);
}

TEST_CASE("cross field: degenerate faces take a fallback frame and keep exact indices") {
  // A cube with extra vertices: one coincident with a corner's neighbour, one on an edge
  // (collinear triangles), one face of three coincident points.
  Surface s = subdivided_cube(3);
  // Collapse: move vertex a onto vertex b (zero-length edge, zero-area faces).
  const int a = s.mesh.origin(0), b = s.mesh.target(0);
  s.positions[a] = s.positions[b];
  // Flatten: put the third corner of face 5 on the line of its first two.
  const auto v = s.mesh.face_vertices(5);
  s.positions[v[2]] = {(s.positions[v[0]].x + s.positions[v[1]].x) / 2, (s.positions[v[0]].y + s.positions[v[1]].y) / 2,
                       (s.positions[v[0]].z + s.positions[v[1]].z) / 2};
  const CrossField f = compute_cross_field(s.mesh, s.positions);
  CHECK(f.stats.degenerate_faces >= 2);
  CHECK(check_poincare_hopf(s.mesh, f) == "");
  for (double t : f.theta) CHECK(std::isfinite(t));
  // All three corners of a face at one point.
  Surface z = subdivided_cube(2);
  const auto w = z.mesh.face_vertices(0);
  z.positions[w[1]] = z.positions[w[0]];
  z.positions[w[2]] = z.positions[w[0]];
  const CrossField g = compute_cross_field(z.mesh, z.positions);
  CHECK(check_poincare_hopf(z.mesh, g) == "");
}

TEST_CASE("cross field: zero-length edges and flat geometry still factorize (regression)") {
  // Regression: with w_e = |e| / d_e a zero-length edge had weight 0, so on coincident or
  // collinear geometry the dual graph fell apart and CHOLMOD met a zero or negative pivot
  // ("sparse factorization failed", 13 of the random suite's 40 hostile meshes). Weights are now
  // at least 1e-3 mean edge / d_e and every factorized matrix strictly diagonally dominant.
  auto check = [](const Surface& s, const char* what) {
    INFO(std::string(what));
    for (double alignment : {0.0, 100.0}) {
      CrossFieldOptions o;
      o.alignment = alignment;
      CrossField f;
      CHECK_NOTHROW(f = compute_cross_field(s.mesh, s.positions, o));
      if (f.theta.size() != static_cast<std::size_t>(s.mesh.num_faces())) continue;
      for (double t : f.theta) CHECK((t >= 0 && t < std::numbers::pi / 2));
      CHECK(check_poincare_hopf(s.mesh, f) == "");
    }
  };
  // The smallest: a tetrahedron with its four vertices at one point (closed: A = 0, the shift
  // was 0 too).
  const std::vector<std::array<int, 3>> tet = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  check(from(std::vector<Vec3d>(4, Vec3d{1, 2, 3}), tet), "coincident tetrahedron");
  // An open octahedron (one face removed) at one point: the free face has only zero-length edges.
  const std::vector<std::array<int, 3>> oct = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                               {2, 0, 5}, {1, 2, 5}, {3, 1, 5}};
  check(from(std::vector<Vec3d>(6, Vec3d{1, 2, 3}), oct, true), "coincident open octahedron");
  // Every vertex on one line at two parameters (random suite's "collinear") and every vertex on a
  // cube corner (its "extreme"): weights 10^3 times the mean next to weight-floor edges.
  Surface line = subdivided_cube(3), corners = subdivided_cube(3);
  for (std::size_t i = 0; i < line.positions.size(); ++i) {
    const double t = static_cast<double>(i % 2);
    line.positions[i] = {t, 2 * t, -3 * t};
    corners.positions[i] = {i % 2 ? 1e308 : -1e308, i % 3 ? 1e308 : -1e308, i % 5 ? 1e308 : -1e308};
  }
  check(line, "collinear cube");
  check(corners, "cube on the corners of a huge cube");
}

TEST_CASE("cross field: bad input gets a typed error naming the element") {
  // The error's kind and elements, or Internal with no element if nothing is thrown (no case
  // below expects that).
  auto error_of = [](const TriMesh& mesh, const std::vector<Vec3d>& positions, const CrossFieldOptions& o = {}) {
    try {
      compute_cross_field(mesh, positions, o);
    } catch (const Error& e) {
      return std::pair{e.kind(), e.elements()};
    }
    return std::pair{ErrorKind::Internal, std::vector<std::int64_t>{}};
  };
  using Elements = std::vector<std::int64_t>;
  const Surface cube = subdivided_cube(1);
  CHECK(error_of(TriMesh{}, {}).first == ErrorKind::Empty);
  CHECK(error_of(TriMesh::from_triangles(3, {}), std::vector<Vec3d>(3)).first == ErrorKind::NoFaces);
  CHECK(error_of(cube.mesh, std::vector<Vec3d>(3)).first == ErrorKind::InvalidArgument);
  Surface nan = cube;
  nan.positions[5].y = std::nan("");
  CHECK(error_of(nan.mesh, nan.positions) == std::pair{ErrorKind::NonFinite, Elements{5}});
  CrossFieldOptions bad;
  bad.alignment = -1;
  CHECK(error_of(cube.mesh, cube.positions, bad).first == ErrorKind::InvalidArgument);
  bad = {};
  bad.max_iterations = 0;
  CHECK(error_of(cube.mesh, cube.positions, bad).first == ErrorKind::InvalidArgument);
  bad = {};
  bad.split_distance = 9;
  CHECK(error_of(cube.mesh, cube.positions, bad).first == ErrorKind::InvalidArgument);
  // Two triangles sharing only vertex 0: two fans at one vertex.
  const Surface bow = from({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}, true);
  CHECK(error_of(bow.mesh, bow.positions) == std::pair{ErrorKind::NonManifoldVertex, Elements{0}});
  // Two separate triangles (face 1 is not connected to face 0); an unused vertex.
  const Surface two =
      from({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}}, {{0, 1, 2}, {3, 4, 5}}, true);
  CHECK(error_of(two.mesh, two.positions) == std::pair{ErrorKind::SeveralComponents, Elements{1}});
  const Surface extra = from({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}}, {{0, 1, 2}}, true);
  CHECK(error_of(extra.mesh, extra.positions) == std::pair{ErrorKind::SeveralComponents, Elements{3}});
}

namespace {

// Both half-edges of every edge of `s` whose two ends satisfy `on` (the test's chain of edges).
std::vector<char> flag_edges(const Surface& s, const std::function<bool(const Vec3d&)>& on) {
  std::vector<char> flags(s.mesh.num_halfedges(), 0);
  for (int h = 0; h < s.mesh.num_halfedges(); ++h)
    if (on(s.positions[s.mesh.origin(h)]) && on(s.positions[s.mesh.target(h)])) flags[h] = 1;
  return flags;
}

// How many faces with a flagged edge have no field direction along one of their flagged edges
// (the sine of the angle above 1e-9).
int misaligned_faces(const Surface& s, const CrossField& f, const std::vector<char>& flags) {
  int bad = 0;
  for (int face = 0; face < s.mesh.num_faces(); ++face) {
    bool any = false, aligned = false;
    for (int i = 0; i < 3; ++i) {
      const int h = 3 * face + i;
      if (!flags[h]) continue;
      any = true;
      const Vec3d a = s.positions[s.mesh.origin(h)], b = s.positions[s.mesh.target(h)];
      Vec3d e{b.x - a.x, b.y - a.y, b.z - a.z};
      const double l = std::sqrt(e.x * e.x + e.y * e.y + e.z * e.z);
      e = {e.x / l, e.y / l, e.z / l};
      const Vec3d d = field_direction(f, face, 0), c = cross(d, e);
      if (std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z) <= 1e-9) aligned = true;
    }
    if (any && !aligned) ++bad;
  }
  return bad;
}

}  // namespace

TEST_CASE("cross field: feature edges are hard constraints (issue 45)") {
  const Surface s = subdivided_cube(4);
  // A chain across the top face (x = 0 on z = 1, not a crease) and the diagonal of the face
  // y = -1 where its triangles have one: neither is where the free field runs, so without the
  // constraint the faces beside them are not aligned (checked), with it they are.
  const std::vector<char> middle = flag_edges(s, [](const Vec3d& p) { return p.z == 1 && p.x == 0; });
  const std::vector<char> diagonal = flag_edges(s, [](const Vec3d& p) { return p.y == -1 && p.x == p.z; });
  std::vector<char> flags(middle.size());
  for (std::size_t h = 0; h < flags.size(); ++h) flags[h] = middle[h] || diagonal[h];
  REQUIRE(std::count(middle.begin(), middle.end(), 1) == 8);
  REQUIRE(std::count(diagonal.begin(), diagonal.end(), 1) > 0);
  for (double w : {0.0, 100.0}) {
    CrossFieldOptions o;
    o.alignment = w;
    const CrossField free = compute_cross_field(s.mesh, s.positions, o);
    o.constrained_edges = flags;
    const CrossField held = compute_cross_field(s.mesh, s.positions, o);
    check_field(s, held, "constrained, alignment " + std::to_string(w));
    CHECK(held.stats.constrained_faces >= 8);
    CHECK(misaligned_faces(s, held, flags) == 0);
    CHECK(misaligned_faces(s, free, diagonal) > 0);
  }
  // The cube's creases as constraints: the eight corners stay its only cones, every crease face aligned.
  const std::vector<char> creases = flag_edges(s, [](const Vec3d& p) {
    return (std::fabs(p.x) == 1) + (std::fabs(p.y) == 1) + (std::fabs(p.z) == 1) >= 2;
  });
  CrossFieldOptions o;
  o.constrained_edges = creases;
  const CrossField f = compute_cross_field(s.mesh, s.positions, o);
  CHECK(misaligned_faces(s, f, creases) == 0);
  REQUIRE(f.cones.size() == 8);
  for (const Cone& c : f.cones) CHECK(c.valence == 3);
  // Flags of the wrong size, or on one half of an edge only: typed errors.
  o.constrained_edges.pop_back();
  CHECK_THROWS_AS(compute_cross_field(s.mesh, s.positions, o), Error);
  o.constrained_edges = std::vector<char>(s.mesh.num_halfedges(), 0);
  o.constrained_edges[0] = 1;
  CHECK_THROWS_AS(compute_cross_field(s.mesh, s.positions, o), Error);
}

TEST_CASE("cross field: the real form on every face agrees with the complex factorization, and a cache keeps its analysis (issue 44)") {
  // Forced onto small surfaces by real_form_above = 0: a closed genus 2 (the smallest eigenvector
  // and the aligned field), an open genus 0 with three loops (boundary faces fixed: decoupled in
  // the real form, eliminated in the complex one) and the cube with its creases as constraints.
  const Surface cube = subdivided_cube(4);
  const std::vector<char> creases = flag_edges(cube, [](const Vec3d& p) {
    return (std::fabs(p.x) == 1) + (std::fabs(p.y) == 1) + (std::fabs(p.z) == 1) >= 2;
  });
  struct Case {
    Surface s;
    std::vector<char> constrained;
  };
  std::vector<Case> cases{{generated(2, 3000, 0, 9), {}}, {generated(0, 3000, 3, 9), {}}, {cube, creases}};
  for (const Case& c : cases)
    for (double w : {0.0, 100.0}) {
      CAPTURE(w);
      CrossFieldOptions o;
      o.alignment = w;
      o.constrained_edges = c.constrained;
      const CrossField complex = compute_cross_field(c.s.mesh, c.s.positions, o);
      CHECK(complex.stats.iterations >= 1);
      o.real_form_above = 0;
      const CrossField real = compute_cross_field(c.s.mesh, c.s.positions, o);
      // The same field to rounding: every face's cross within 1e-6 rad, hence the same matchings,
      // valences and cones.
      double worst = 0;
      for (std::size_t f = 0; f < real.theta.size(); ++f)
        worst = std::max(worst, std::fabs(std::remainder(real.theta[f] - complex.theta[f], kQuarter)));
      CHECK(worst < 1e-6);
      CHECK(real.valence == complex.valence);
      CHECK(real.matching == complex.matching);
      CHECK(real.stats.iterations == complex.stats.iterations);
      // With a cache: one analysis for every call on the mesh, the same bytes as without.
      CrossFieldCache cache;
      const CrossField a = compute_cross_field(c.s.mesh, c.s.positions, o, &cache);
      CrossFieldOptions o2 = o;
      o2.alignment = w > 0 ? 0.0 : 100.0;
      o2.constrained_edges.clear();
      const CrossField b = compute_cross_field(c.s.mesh, c.s.positions, o2, &cache);
      const CrossField again = compute_cross_field(c.s.mesh, c.s.positions, o, &cache);
      CHECK(cache.analyses() == 1);
      CHECK(a.theta == real.theta);  // bitwise
      CHECK(again.theta == real.theta);
      CHECK(b.theta == compute_cross_field(c.s.mesh, c.s.positions, o2).theta);
    }
  // Another mesh through the same cache is analyzed again; the default leaves small meshes to
  // CHOLMOD (no analysis kept).
  CrossFieldCache cache;
  CrossFieldOptions o;
  o.real_form_above = 0;
  compute_cross_field(cases[0].s.mesh, cases[0].s.positions, o, &cache);
  compute_cross_field(cube.mesh, cube.positions, o, &cache);
  CHECK(cache.analyses() == 2);
  CrossFieldCache unused;
  compute_cross_field(cube.mesh, cube.positions, CrossFieldOptions{}, &unused);
  CHECK(unused.analyses() == 0);
  o.real_form_above = -1;
  CHECK_THROWS_AS(compute_cross_field(cube.mesh, cube.positions, o), Error);
}
