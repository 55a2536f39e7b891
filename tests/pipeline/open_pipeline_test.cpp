// The pipeline on open surfaces and on several components (issue 39): compute_igm on a
// SurfaceComponent with boundary loops (src/pipeline/open_pipeline.cpp) and compute_igms on a
// SurfaceSet (src/pipeline/surfaces.cpp). Every case ends with the certifier in boundary (and
// components) mode on what was written, and an independent exact check that the quad mesh's
// boundary is the input's boundary.
#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "certify/certify.h"
#include "igm/core/error.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/output/igm_mesh.h"
#include "igm/pipeline/pipeline.h"
#include "refinement_check.h"
#include "test_data.h"
#include "uv_area.h"

using namespace igm;
using igm_test::refinement_violation;
using igm_test::uv_area2;

namespace {

SurfaceSet generated_surfaces(int genus, int boundaries, std::int64_t faces, std::uint64_t seed = 1) {
  GenerateOptions g;
  g.genus = genus;
  g.boundaries = boundaries;
  g.faces = faces;
  g.seed = seed;
  return validate_surfaces(generate_mesh(g));
}

SurfaceComponent generated_open(int genus, int boundaries, std::int64_t faces, std::uint64_t seed = 1) {
  SurfaceSet set = generated_surfaces(genus, boundaries, faces, seed);
  REQUIRE(set.components.size() == 1);
  REQUIRE(set.components[0].genus == genus);
  REQUIRE(set.components[0].boundary_loops.size() == static_cast<std::size_t>(boundaries));
  return std::move(set.components[0]);
}

// Where a quad vertex lies on the input's boundary: (loop, edge index along the loop, parameter
// t in [0, 1) from the edge's first vertex), exactly; or nothing.
struct BoundaryPosition {
  int loop = -1, edge = -1;
  Rational t;
  bool operator<(const BoundaryPosition& o) const {
    return std::tie(loop, edge) != std::tie(o.loop, o.edge) ? std::tie(loop, edge) < std::tie(o.loop, o.edge) : t < o.t;
  }
};

// Independent exact check (issue 39) that the quad mesh's boundary is the input's boundary:
//  - a quad vertex is located on the input's boundary (at a boundary vertex, or inside a
//    boundary edge: its location's support is that edge's two vertices) exactly when it is on a
//    boundary edge of the quad mesh (an edge with one quad);
//  - every boundary quad edge a -> b (the quad on its left) joins a point of a loop to the NEXT
//    quad boundary point along that loop, in the loop's direction (the surface on its left too):
//    so the boundary quad edges walk every input loop once, in order, and nothing else.
// Returns "" or the first violation. Locations use `surface`'s local vertex ids.
std::string boundary_trace_violation(const std::vector<std::vector<int>>& loops, const QuadMesh& q) {
  std::map<int, std::pair<int, int>> at_vertex;                 // boundary vertex -> (loop, index)
  std::map<std::pair<int, int>, std::tuple<int, int, bool>> at_edge;  // {a, b} -> (loop, index, a is first)
  for (int l = 0; l < static_cast<int>(loops.size()); ++l)
    for (int i = 0; i < static_cast<int>(loops[l].size()); ++i) {
      const int a = loops[l][i], b = loops[l][(i + 1) % loops[l].size()];
      at_vertex[a] = {l, i};
      at_edge[std::minmax(a, b)] = {l, i, a < b};
    }
  const int nv = static_cast<int>(q.positions.size());
  if (static_cast<int>(q.locations.size()) != nv) return "quad locations missing";
  std::vector<std::optional<BoundaryPosition>> pos(nv);
  for (int v = 0; v < nv; ++v) {
    const SurfacePoint& p = q.locations[v];
    if (p.v[0] >= 0 && p.v[1] < 0) {
      if (auto it = at_vertex.find(p.v[0]); it != at_vertex.end()) pos[v] = BoundaryPosition{it->second.first, it->second.second, 0};
    } else if (p.v[1] >= 0 && p.v[2] < 0) {
      if (auto it = at_edge.find({p.v[0], p.v[1]}); it != at_edge.end()) {
        const auto [l, i, first_is_low] = it->second;
        // the weight of the edge's second vertex (in the loop's direction) is the parameter
        pos[v] = BoundaryPosition{l, i, first_is_low ? p.w[1] : p.w[0]};
      }
    }
  }
  std::map<std::pair<int, int>, int> sides;  // undirected quad edge -> quads
  std::vector<std::pair<int, int>> directed;
  for (const auto& quad : q.quads)
    for (int i = 0; i < 4; ++i) {
      const int a = quad[i], b = quad[(i + 1) % 4];
      ++sides[std::minmax(a, b)];
      directed.push_back({a, b});
    }
  std::vector<char> on_quad_boundary(nv, 0);
  std::vector<std::pair<int, int>> boundary;
  for (const auto& [a, b] : directed)
    if (sides[std::minmax(a, b)] == 1) {
      boundary.push_back({a, b});
      on_quad_boundary[a] = on_quad_boundary[b] = 1;
    }
  std::vector<std::vector<std::pair<BoundaryPosition, int>>> along(loops.size());
  for (int v = 0; v < nv; ++v) {
    if (static_cast<bool>(pos[v]) != static_cast<bool>(on_quad_boundary[v]))
      return "quad vertex " + std::to_string(v) + (pos[v] ? " on the input's boundary but inside the quad mesh"
                                                          : " on the quad mesh's boundary but not on the input's");
    if (pos[v]) along[pos[v]->loop].push_back({*pos[v], v});
  }
  std::vector<int> next(nv, -1);
  for (auto& points : along) {
    if (points.empty()) continue;
    std::sort(points.begin(), points.end());
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (k > 0 && !(points[k - 1].first < points[k].first)) return "two quad vertices at one boundary point";
      next[points[k].second] = points[(k + 1) % points.size()].second;
    }
  }
  for (std::size_t l = 0; l < loops.size(); ++l)
    if (along[l].empty()) return "input loop " + std::to_string(l) + " has no quad vertex";
  if (boundary.size() != static_cast<std::size_t>(std::count_if(pos.begin(), pos.end(), [](const auto& p) { return p.has_value(); })))
    return "boundary quad edges and boundary points differ in number";
  for (const auto& [a, b] : boundary)
    if (next[a] != b) return "boundary quad edge " + std::to_string(a) + " -> " + std::to_string(b) + " skips or reverses along the input's loop";
  return "";
}

certify::Options boundary_options(std::int64_t genus, std::int64_t loops) {
  certify::Options o;
  o.allow_boundary = true;
  o.expected_genus = genus;
  o.expected_boundary_loops = loops;
  return o;
}

// Everything a run on an open surface promises, re-checked independently.
PipelineResult check_open_run(const SurfaceComponent& s, const PipelineOptions& options) {
  const int g = s.genus, b = static_cast<int>(s.boundary_loops.size());
  INFO("genus " << g << ", " << b << " loops, " << s.triangles.size() << " faces");
  PipelineResult r = compute_igm(s, options);
  CHECK(r.stats.genus == g);
  CHECK(r.stats.boundary_loops == b);
  CHECK(r.igm_report.valid());
  CHECK(r.quad_report.valid());
  REQUIRE(r.igm_report.boundary_loops.has_value());
  CHECK(*r.igm_report.boundary_loops == b);
  CHECK(*r.igm_report.genus == g);
  REQUIRE(r.quad_report.boundary_loops.has_value());
  CHECK(*r.quad_report.boundary_loops == b);
  CHECK(*r.quad_report.genus == g);
  CHECK(r.quads.quads.size() >= static_cast<std::size_t>(r.stats.layout_quads));
  CHECK(uv_area2(r.igm) == Rational(2 * static_cast<long>(r.quads.quads.size())));
  CHECK(refinement_violation(s.triangles, s.positions, r.igm, true) == "");
  CHECK(boundary_trace_violation(s.boundary_loops, r.quads) == "");
  // The written files through the certifier's reader, in boundary mode.
  std::ostringstream exact, quads;
  write_igm_obj(exact, r.igm, true);
  write_quad_obj(quads, r.quads);
  CHECK(certify::certify_igm_text(exact.str(), boundary_options(g, b)).valid());
  CHECK(certify::certify_quads_text(quads.str(), boundary_options(g, b)).valid());
  // The boundary rule is needed: without boundary mode the same files are refused.
  CHECK_FALSE(certify::certify_igm_text(exact.str()).valid());
  if (r.stats.uv_doubles) {
    std::ostringstream doubles;
    write_igm_obj(doubles, r.igm, false);
    CHECK(certify::certify_igm_text(doubles.str(), boundary_options(g, b)).valid());
  }
  return r;
}

PipelineOptions unsmoothed(int resolution = 3) {
  PipelineOptions o;
  o.layout = LayoutKind::Spread;  // the topological layout (the field one has its own tests)
  o.smooth = false;
  o.resolution = resolution;
  return o;
}

}  // namespace

TEST_CASE("the boundary trace check fails on a quad mesh whose boundary is not the input's") {
  // A 2 x 1 strip of quads over the unit square's two triangles (input loop 0 1 2 3).
  const std::vector<std::vector<int>> loops{{0, 1, 2, 3}};
  QuadMesh q;
  auto vertex = [](int a) { SurfacePoint p; p.v = {a, -1, -1}; p.w = {1, 0, 0}; return p; };
  auto on_edge = [](int a, int b, Rational wb) { SurfacePoint p; p.v = {a, b, -1}; p.w = {1 - wb, wb, 0}; return p; };
  q.locations = {vertex(0), on_edge(0, 1, Rational(1, 2)), vertex(1), vertex(2), on_edge(2, 3, Rational(1, 2)), vertex(3)};
  q.positions.resize(6);
  q.quads = {{0, 1, 4, 5}, {1, 2, 3, 4}};
  CHECK(boundary_trace_violation(loops, q) == "");
  SUBCASE("reversed") {
    q.quads = {{5, 4, 1, 0}, {4, 3, 2, 1}};
    CHECK(boundary_trace_violation(loops, q) != "");
  }
  SUBCASE("a boundary point left inside") {
    q.locations[1] = on_edge(0, 2, Rational(1, 2));  // not a boundary edge
    CHECK(boundary_trace_violation(loops, q) != "");
  }
  SUBCASE("a loop the quads do not reach") {
    CHECK(boundary_trace_violation({{0, 1, 2, 3}, {7, 8, 9}}, q) != "");
  }
}

TEST_CASE("the disk is one a x b rectangle with four boundary corners, the annulus a strip without corners") {
  const SurfaceComponent disk = generated_open(0, 1, 800);
  for (int n : {3, 5}) {
    const PipelineResult r = check_open_run(disk, unsmoothed(n));
    CHECK(r.stats.layout_quads == 1);
    CHECK(r.quads.quads.size() == static_cast<std::size_t>(n * n));
    const certify::CheckResult* cones = r.igm_report.check(4);
    REQUIRE(cones != nullptr);
    CHECK(cones->boundary_histogram.count(1) == 1);
    CHECK(cones->boundary_histogram.at(1) == 4);  // the rectangle's corners
    for (const auto& [k, count] : cones->boundary_histogram) CHECK((k == 1 || k == 2));
    for (const auto& [k, count] : cones->histogram) CHECK(k == 4);
  }
  const SurfaceComponent annulus = generated_open(0, 2, 800);
  const PipelineResult r = check_open_run(annulus, unsmoothed(4));
  CHECK(r.stats.layout_quads == 1);
  CHECK(r.quads.quads.size() == 16);
  const certify::CheckResult* cones = r.igm_report.check(4);
  REQUIRE(cones != nullptr);
  for (const auto& [k, count] : cones->boundary_histogram) CHECK(k == 2);
  for (const auto& [k, count] : cones->histogram) CHECK(k == 4);
}

TEST_CASE("generated open meshes of genus 0..6 with 1..10 boundary loops are certified, their boundary traced") {
  for (int g : {0, 1, 2, 3, 6})
    for (int b : {1, 2, 3, 5, 10}) {
      if (igm_test::kSanitized && g * b > 12) continue;  // the larger ones in the Release run
      const SurfaceComponent s = generated_open(g, b, 600 + 300 * g + 100 * b, 7 * g + b);
      check_open_run(s, unsmoothed(3));
    }
}

TEST_CASE("open meshes smoothed (the default): certified doubles, boundary still traced, better than unsmoothed") {
  for (auto [g, b] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{2, 3}}) {
    const SurfaceComponent s = generated_open(g, b, 3000, 11);
    PipelineOptions o;
    o.layout = LayoutKind::Spread;  // the topological layout (the field one has its own tests)
    o.quads = 1500;
    o.smooth_iterations = igm_test::kSanitized ? 5 : 40;
    o.smooth_seconds = 0;  // iterations only: deterministic
    const PipelineResult smoothed = check_open_run(s, o);
    CHECK(smoothed.stats.uv_doubles);
    o.smooth = false;
    const PipelineResult plain = check_open_run(s, o);
    CHECK(smoothed.quads.quads.size() == plain.quads.quads.size());
    CHECK(smoothed.igm_quality.symmetric_dirichlet <= plain.igm_quality.symmetric_dirichlet);
  }
}

TEST_CASE("open surfaces: bad options are typed errors") {
  const SurfaceComponent s = generated_open(0, 2, 600);
  // Below the annulus's floor (3 around it, else two edges join the loop's vertices): raised to it.
  PipelineOptions o = unsmoothed(2);
  const PipelineResult floor = check_open_run(s, o);
  CHECK(floor.stats.raised_chords == 1);
  CHECK(floor.stats.quads == 2 * 3);
  o = unsmoothed(3);
  o.cones = {0, 1, 2, 3};  // cones are for closed spheres only
  try {
    compute_igm(s, o);
    FAIL("a cone list was accepted on an open surface");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::InvalidArgument);
  }
}

TEST_CASE("several components: each certified, merged and certified in components mode, quads shared by area") {
  // A torus, a sphere and a genus-2 surface with three holes, as one soup.
  PolygonSoup soup;
  auto append = [&soup](const PolygonSoup& part, double shift) {
    const auto base = static_cast<std::int64_t>(soup.positions.size());
    for (Vec3d p : part.positions) soup.positions.push_back({p.x + shift, p.y, p.z});
    for (std::int64_t c : part.corners) soup.corners.push_back(c + base);
    for (std::size_t f = 0; f < part.num_faces(); ++f) soup.face_begin.push_back(soup.face_begin.back() + part.face_size(f));
  };
  GenerateOptions g;
  g.faces = 800;
  g.genus = 1;
  append(generate_mesh(g), 0);
  g.genus = 0;
  append(generate_mesh(g), 10);
  g.genus = 2;
  g.boundaries = 3;
  append(generate_mesh(g), 20);
  const SurfaceSet set = validate_surfaces(soup);
  REQUIRE(set.components.size() == 3);
  PipelineOptions o;
  o.layout = LayoutKind::Spread;  // the topological layout (the field one has its own tests)
  o.smooth = false;
  o.quads = 3000;
  const SurfacesResult r = compute_igms(set, o);
  REQUIRE(r.components.size() == 3);
  CHECK(r.certified());
  std::size_t quads = 0;
  for (const PipelineResult& c : r.components) {
    CHECK(c.certified());
    quads += c.quads.quads.size();
  }
  CHECK(r.quads.quads.size() == quads);
  CHECK(quads > 3000 * 3 / 4);
  CHECK(quads < 3000 * 5 / 4);
  REQUIRE(r.igm_report.components.size() == 3);
  REQUIRE(r.quad_report.components.size() == 3);
  std::multiset<std::pair<std::int64_t, std::int64_t>> topo;
  for (const auto& c : r.quad_report.components) topo.insert({c.genus.value_or(-1), c.boundary_loops.value_or(-1)});
  CHECK(topo == std::multiset<std::pair<std::int64_t, std::int64_t>>{{1, 0}, {0, 0}, {2, 3}});
  // the merged files through the certifier's reader
  std::ostringstream exact;
  write_igm_obj(exact, r.igm, true);
  certify::Options co;
  co.allow_boundary = co.allow_components = true;
  CHECK(certify::certify_igm_text(exact.str(), co).valid());
  co.allow_components = false;
  CHECK_FALSE(certify::certify_igm_text(exact.str(), co).valid());
}

TEST_CASE("shared open meshes, meshes with several components, and non-manifold ones split: all certified") {
  IGM_REQUIRE_DATA(dir);
  struct Case {
    std::string path;
    bool split;
  };
  std::vector<Case> cases;
  for (const auto& e : std::filesystem::directory_iterator(dir / "meshes" / "open")) cases.push_back({e.path().string(), false});
  for (const char* name : {"blobby_3cc.off", "knot2.off", "double-torus-3-holes.off"})
    cases.push_back({(dir / "meshes" / "invalid" / name).string(), false});
  cases.push_back({(dir / "meshes" / "invalid" / "pig.stl").string(), true});
  if (!igm_test::kSanitized) cases.push_back({(dir / "meshes" / "invalid" / "polygon_mesh.off").string(), true});
  std::sort(cases.begin(), cases.end(), [](const Case& a, const Case& b) { return a.path < b.path; });
  for (const Case& c : cases) {
    INFO(c.path);
    SurfaceOptions so;
    so.split_nonmanifold = c.split;
    const SurfaceSet set = validate_surfaces(read_soup(std::filesystem::path(c.path)), so);
    PipelineOptions o;
    o.layout = LayoutKind::Spread;  // the topological layout (the field one has its own tests)
    o.quads = 2000;
    o.smooth = !igm_test::kSanitized;
    o.smooth_iterations = 10;
    o.smooth_seconds = 0;
    o.quality_distance = false;
    const SurfacesResult r = compute_igms(set, o);
    CHECK(r.certified());
    for (std::size_t k = 0; k < set.components.size(); ++k) {
      const PipelineResult& p = r.components[k];
      CHECK(p.certified());
      CHECK(boundary_trace_violation(set.components[k].boundary_loops, p.quads) == "");
      CHECK(refinement_violation(set.components[k].triangles, set.components[k].positions, p.igm, true) == "");
    }
    if (c.split) CHECK_FALSE(set.warnings.empty());  // every cut named
  }
}
