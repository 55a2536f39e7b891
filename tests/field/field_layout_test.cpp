// Tests of the separatrices' motorcycle graph (field/motorcycle.h) and the field layout built from
// it (field/field_layout.h): the cube's six faces, a torus without cones (seeded), generated
// surfaces of genus 0 to 20, open surfaces, the independent checks of both structures (and that
// they catch broken ones), determinism; every layout passes check_surface_layout.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/field/cross_field.h"
#include "igm/field/field_layout.h"
#include "igm/field/motorcycle.h"
#include "igm/layout/surface_layout.h"
#include "igm/mesh/scale.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"
#include "test_data.h"
#include "test_surfaces.h"
#include "../../src/field/motorcycle_internal.h"

using namespace igm;
using igm_test::Surface;
using igm_test::generated;

namespace {

std::vector<Vec3d> directions(const Surface& s, const CrossFieldOptions& o = {}) {
  const CrossField f = compute_cross_field(s.mesh, s.positions, o);
  std::vector<Vec3d> d(s.mesh.num_faces());
  for (int f_ = 0; f_ < s.mesh.num_faces(); ++f_) d[f_] = field_direction(f, f_, 0);
  return d;
}

// The vertices x = 0, z = 1 (the top face's middle line) of a subdivided cube at the given y, in
// order, and the field with the edges between consecutive ones as constraints (a wall's).
std::vector<int> top_line(const Surface& s, const std::vector<double>& ys) {
  std::vector<int> line;
  for (double y : ys)
    for (int v = 0; v < s.mesh.num_vertices(); ++v)
      if (s.positions[v].x == 0 && s.positions[v].y == y && s.positions[v].z == 1) line.push_back(v);
  return line;
}

std::vector<Vec3d> directions_along(const Surface& s, const std::vector<int>& wall) {
  CrossFieldOptions fo;
  fo.constrained_edges.assign(s.mesh.num_halfedges(), 0);
  for (std::size_t i = 0; i + 1 < wall.size(); ++i) {
    const int h = s.mesh.find_halfedge(wall[i], wall[i + 1]);
    fo.constrained_edges[h] = fo.constrained_edges[s.mesh.twin(h)] = 1;
  }
  return directions(s, fo);
}

// The snap length the pipeline uses for `quads` quads: half a quad's side.
double snap_for(const Surface& s, double quads) {
  double area = 0;
  for (int f = 0; f < s.mesh.num_faces(); ++f) {
    const auto v = s.mesh.face_vertices(f);
    const Vec3d a = s.positions[v[0]], b = s.positions[v[1]], c = s.positions[v[2]];
    const Vec3d u{b.x - a.x, b.y - a.y, b.z - a.z}, w{c.x - a.x, c.y - a.y, c.z - a.z};
    const Vec3d n{u.y * w.z - u.z * w.y, u.z * w.x - u.x * w.z, u.x * w.y - u.y * w.x};
    area += 0.5 * std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  }
  return 0.5 * std::sqrt(area / quads);
}

// The layout with the trace options the pipeline uses for `quads` quads: curves ending near a node
// snap to it within half a quad's side.
FieldLayoutResult layout(const Surface& s, const std::vector<Vec3d>& d, double quads = 2000) {
  FieldLayoutOptions o;
  o.trace.snap_length = snap_for(s, quads);
  return build_field_layout(s.mesh, s.positions, d, o);
}

// The layout's facts every test checks: the independent check, and every patch a four-sided disk
// whose sides are made of arcs of the layout.
void check_layout(const FieldLayoutResult& r, const std::string& what) {
  INFO(what << ": " << r.failure);
  REQUIRE(r.ok);
  CHECK(check_surface_layout(r.layout) == "");
  CHECK(r.stats.patches == static_cast<int>(r.layout.patches.size()));
  CHECK(r.layout.num_input_vertices > 0);
}

}  // namespace

TEST_CASE("field layout: the cube's separatrices join its corners, six square patches") {
  for (int n : {1, 3}) {
    const Surface s = igm_test::subdivided_cube(n);
    const TraceGraph g = trace_motorcycles(s.mesh, s.positions, directions(s));
    CHECK(check_trace_graph(s.mesh, g) == "");
    CHECK(g.stats.cones == 8);
    // Every separatrix runs from a corner to the next one: 12 curves, all ending at cones.
    CHECK(g.curves.size() == 12);
    for (const TraceCurve& c : g.curves) CHECK(c.end == CurveEnd::Cone);
    const FieldLayoutResult r = build_field_layout(s.mesh, s.positions, directions(s));
    check_layout(r, "cube " + std::to_string(n));
    CHECK(r.layout.patches.size() == 6);
    CHECK(r.layout.arcs.size() == 12);
    for (const LayoutPatch& p : r.layout.patches)
      for (const auto& side : p.sides) CHECK(side.size() == 1);  // no T-junction
  }
}

TEST_CASE("field layout: a torus without cones gets a seed and a layout of disks") {
  const Surface s = igm_test::torus(3, 1, 48, 16);
  CrossFieldOptions o;
  o.alignment = 0;
  const std::vector<Vec3d> d = directions(s, o);
  const TraceGraph g = trace_motorcycles(s.mesh, s.positions, d);
  CHECK(g.stats.cones == 0);
  CHECK(g.curves.empty());
  const FieldLayoutResult r = build_field_layout(s.mesh, s.positions, d);
  check_layout(r, "torus");
  CHECK(r.stats.seeds >= 1);
  CHECK(r.stats.rounds >= 2);
  // Without seeding rounds the one patch is the whole torus: not a disk, and said so.
  FieldLayoutOptions none;
  none.max_seed_rounds = 0;
  const FieldLayoutResult bare = build_field_layout(s.mesh, s.positions, d, none);
  CHECK_FALSE(bare.ok);
  CHECK(bare.failure.find("no boundary") != std::string::npos);
  CHECK(bare.stats.non_disk_patches == 1);
}

TEST_CASE("field layout: generated closed surfaces of genus 0 to 20") {
  for (int genus : {0, 1, 3, 8, 20}) {
    const Surface s = generated(genus, 6000, 0, 7);
    const std::vector<Vec3d> d = directions(s);
    const TraceGraph g = trace_motorcycles(s.mesh, s.positions, d);
    CHECK(check_trace_graph(s.mesh, g) == "");
    // Poincare-Hopf on the tracing's own valences.
    int sum = 0;
    for (int v = 0; v < s.mesh.num_vertices(); ++v) sum += 4 - g.valence[v];
    CHECK(sum == 8 - 8 * genus);
    check_layout(layout(s, d), "genus " + std::to_string(genus));
  }
}

TEST_CASE("field layout: open surfaces, the boundary on arcs with no patch outside") {
  for (const auto& [genus, loops] : std::vector<std::pair<int, int>>{{0, 1}, {0, 3}, {1, 3}, {2, 1}}) {
    const Surface s = generated(genus, 4000, loops, 3);
    const FieldLayoutResult r = layout(s, directions(s));
    check_layout(r, "genus " + std::to_string(genus) + ", " + std::to_string(loops) + " loops");
    int boundary_arcs = 0;
    for (const LayoutArc& a : r.layout.arcs) boundary_arcs += a.patch[1] < 0;
    CHECK(boundary_arcs >= loops);
  }
  IGM_REQUIRE_DATA(dir);
  for (const char* name : {"plane.off", "head.off", "open_cube.off", "triangular_hole.off"}) {
    const SurfaceSet set = validate_surfaces(read_soup(dir / "meshes/open" / name));
    const SurfaceComponent& c = set.components[0];
    const Surface s{TriMesh::from_triangles(static_cast<int>(c.positions.size()), c.triangles, true), c.positions};
    check_layout(layout(s, directions(s)), name);
  }
}

TEST_CASE("field layout: the same input gives the same layout") {
  const Surface s = generated(3, 3000, 0, 11);
  const std::vector<Vec3d> d = directions(s);
  const FieldLayoutResult a = layout(s, d), b = layout(s, d);
  REQUIRE(a.ok);
  REQUIRE(b.ok);
  CHECK(a.layout.triangles == b.layout.triangles);
  CHECK(a.layout.triangle_patch == b.layout.triangle_patch);
  REQUIRE(a.layout.locations.size() == b.layout.locations.size());
  for (std::size_t v = 0; v < a.layout.locations.size(); ++v) {
    CHECK(a.layout.locations[v].v == b.layout.locations[v].v);
    CHECK(a.layout.locations[v].w == b.layout.locations[v].w);
  }
  REQUIRE(a.layout.arcs.size() == b.layout.arcs.size());
  for (std::size_t k = 0; k < a.layout.arcs.size(); ++k) CHECK(a.layout.arcs[k].vertices == b.layout.arcs[k].vertices);
}

TEST_CASE("field layout: check_trace_graph catches broken graphs") {
  const Surface s = generated(2, 3000, 0, 5);
  const TraceGraph good = trace_motorcycles(s.mesh, s.positions, directions(s));
  REQUIRE(check_trace_graph(s.mesh, good) == "");
  REQUIRE(!good.curves.empty());
  // A curve's point moved onto another face's interior: its segment leaves its face.
  {
    TraceGraph g = good;
    for (TracePoint& p : g.points)
      if (p.kind == TracePoint::Kind::Face) {
        p.element = (p.element + 1) % s.mesh.num_faces();
        break;
      }
    for (TracePoint& p : g.points)
      if (p.kind == TracePoint::Kind::Edge) {
        p.t = 0;
        break;
      }
    CHECK(check_trace_graph(s.mesh, g) != "");
  }
  // A curve given a ray its point does not have.
  {
    TraceGraph g = good;
    g.curves[0].ray_forward[0] = g.ray_count[g.curves[0].points[0]] + 3;
    CHECK(check_trace_graph(s.mesh, g).find("ray out of range") != std::string::npos);
  }
  // Two curves crossing without a point in common: one curve's crossing of an edge swapped with
  // the other's, by giving them the same parameter on one edge.
  {
    TraceGraph g = good;
    // A segment of zero length.
    TraceCurve& c = g.curves[0];
    c.points.insert(c.points.begin() + 1, c.points[1]);
    c.segment_face.insert(c.segment_face.begin() + 1, c.segment_face[0]);
    c.ray_back.insert(c.ray_back.begin() + 1, -1);
    c.ray_forward.insert(c.ray_forward.begin() + 1, -1);
    CHECK(check_trace_graph(s.mesh, g).find("zero length") != std::string::npos);
  }
}

TEST_CASE("field layout: sizes that do not match are typed errors") {
  const Surface s = igm_test::subdivided_cube(1);
  std::vector<Vec3d> d = directions(s);
  d.pop_back();
  CHECK_THROWS_AS(trace_motorcycles(s.mesh, s.positions, d), Error);
  CHECK_THROWS_AS(build_field_layout(s.mesh, s.positions, d), Error);
  TraceOptions bad;
  bad.parameter_bits = 60;
  CHECK_THROWS_AS(trace_motorcycles(s.mesh, s.positions, directions(s), bad), Error);
  TraceOptions seed;
  seed.seeds = {s.mesh.num_vertices()};
  CHECK_THROWS_AS(trace_motorcycles(s.mesh, s.positions, directions(s), seed), Error);
}

TEST_CASE("field layout: walls (issue 45 feature curves) are drawn whole and bound the patches") {
  const Surface s = igm_test::subdivided_cube(4);
  // The wall: x = 0 across the top face z = 1, from one crease to the other (no separatrix runs
  // there: without it no arc does).
  const std::vector<int> wall = top_line(s, {-1.0, -0.5, 0.0, 0.5, 1.0});
  REQUIRE(wall.size() == 5);
  const std::vector<Vec3d> d = directions_along(s, wall);
  // Every wall edge a pair of consecutive vertices of one arc.
  auto wall_on_arcs = [&](const FieldLayoutResult& r) {
    std::set<std::pair<int, int>> arc_edges;
    for (const LayoutArc& a : r.layout.arcs)
      for (std::size_t i = 0; i + 1 < a.vertices.size(); ++i)
        arc_edges.insert({std::min(a.vertices[i], a.vertices[i + 1]), std::max(a.vertices[i], a.vertices[i + 1])});
    int on = 0;
    for (std::size_t i = 0; i + 1 < wall.size(); ++i)
      on += arc_edges.count({std::min(wall[i], wall[i + 1]), std::max(wall[i], wall[i + 1])}) > 0;
    return on;
  };
  const FieldLayoutResult without = build_field_layout(s.mesh, s.positions, d);
  check_layout(without, "cube without the wall");
  CHECK(wall_on_arcs(without) == 0);
  TraceOptions t;
  t.walls = {wall};
  const TraceGraph g = trace_motorcycles(s.mesh, s.positions, d, t);
  CHECK(check_trace_graph(s.mesh, g) == "");
  CHECK(g.stats.walls == 1);
  CHECK(g.stuck_walls.empty());
  FieldLayoutOptions o;
  o.trace.walls = {wall};
  const FieldLayoutResult with = build_field_layout(s.mesh, s.positions, d, o);
  check_layout(with, "cube with the wall");
  CHECK(wall_on_arcs(with) == 4);
  CHECK(with.layout.patches.size() > without.layout.patches.size());
  // A wall whose vertices are not joined by an edge, or an edge in two walls: typed errors.
  t.walls = {{wall[0], wall[2]}};
  CHECK_THROWS_AS(trace_motorcycles(s.mesh, s.positions, d, t), Error);
  t.walls = {wall, {wall[1], wall[0]}};
  CHECK_THROWS_AS(trace_motorcycles(s.mesh, s.positions, d, t), Error);
}

TEST_CASE("field layout: stop_at_stuck_wall returns after the walls when one cannot be drawn") {
  // On the subdivided cube (its field along the grid), a two-edge wall that turns by 45 degrees on
  // the top face: the edge it leaves by is as near the ray it came in by as any other, so some such
  // wall is stuck (the first found, in vertex order, is used).
  const Surface s = igm_test::subdivided_cube(4);
  const std::vector<Vec3d> d = directions(s);
  std::vector<int> stuck;
  for (int a = 0; a < s.mesh.num_vertices() && stuck.empty(); ++a) {
    if (s.positions[a].z != 1) continue;
    for (int b = 0; b < s.mesh.num_vertices() && stuck.empty(); ++b) {
      if (b == a || s.positions[b].z != 1 || s.mesh.find_halfedge(a, b) < 0) continue;
      for (int c = 0; c < s.mesh.num_vertices() && stuck.empty(); ++c) {
        if (c == a || c == b || s.positions[c].z != 1 || s.mesh.find_halfedge(b, c) < 0) continue;
        TraceOptions t;
        t.walls = {{a, b, c}};
        if (!trace_motorcycles(s.mesh, s.positions, d, t).stuck_walls.empty()) stuck = {a, b, c};
      }
    }
  }
  REQUIRE(stuck.size() == 3);
  TraceOptions t;
  t.walls = {stuck};
  const TraceGraph all = trace_motorcycles(s.mesh, s.positions, d, t);
  t.stop_at_stuck_wall = true;
  const TraceGraph early = trace_motorcycles(s.mesh, s.positions, d, t);
  CHECK(early.stuck_walls == all.stuck_walls);
  CHECK(early.stats.walls == 1);
  CHECK(early.curves.size() <= 1);  // the wall's own curve, as far as it got
  CHECK(all.curves.size() > 8);     // the cube's separatrices too
  FieldLayoutOptions o;
  o.trace = t;
  const FieldLayoutResult r = build_field_layout(s.mesh, s.positions, d, o);
  CHECK_FALSE(r.ok);
  CHECK(r.stats.rounds == 1);
  CHECK(r.failure.find("could not be drawn") != std::string::npos);
  CHECK(r.graph.stuck_walls.size() == 1);
}

TEST_CASE("field layout: the rounds' reuse (frames, rays, solo pre-pass) traces the same graph as a fresh trace") {
  // build_field_layout's rounds trace with one TraceReuse; each round's graph must be the one a
  // fresh trace_motorcycles gives for its options: bans alone keep the solo results, a seed
  // changes the traced vertices (the kept results are dropped), and back again.
  const Surface s = generated(0, 3000, 0, 5);
  const std::vector<Vec3d> d = directions(s);
  const field_detail::FieldFrames frames(s.mesh, scaled_positions(s.positions, unit_scale(s.positions)), d);
  field_detail::TraceReuse reuse;
  TraceOptions base;
  base.snap_length = snap_for(s, 2000);
  const TraceGraph first = trace_motorcycles(s.mesh, s.positions, d, base);
  REQUIRE(first.curves.size() >= 4);
  REQUIRE(first.stats.steers > 0);  // the steering count must be carried over with the solo results
  std::vector<TraceOptions> rounds(4, base);
  const auto& c0 = first.curves[0];
  rounds[1].banned_rays = {{first.points[c0.points.front()].element, c0.ray_forward.front()}};
  rounds[2] = rounds[1];
  int seed = 0;
  while (first.valence[seed] != 4) ++seed;
  rounds[2].seeds = {seed};
  int checked = 0;
  for (const TraceOptions& o : rounds) {
    const TraceGraph a = field_detail::trace_motorcycles_reusing(s.mesh, s.positions, d, o, frames, reuse);
    const TraceGraph b = trace_motorcycles(s.mesh, s.positions, d, o);
    REQUIRE(a.curves.size() == b.curves.size());
    REQUIRE(a.points.size() == b.points.size());
    for (std::size_t c = 0; c < a.curves.size(); ++c) {
      CHECK(a.curves[c].points == b.curves[c].points);
      CHECK(a.curves[c].ray_back == b.curves[c].ray_back);
      CHECK(a.curves[c].ray_forward == b.curves[c].ray_forward);
      CHECK(a.curves[c].end == b.curves[c].end);
    }
    for (std::size_t p = 0; p < a.points.size(); ++p) {
      CHECK(a.points[p].element == b.points[p].element);
      CHECK(a.points[p].t == b.points[p].t);
    }
    CHECK(a.stats.steers == b.stats.steers);
    CHECK(a.stats.cone_pairs == b.stats.cone_pairs);
    CHECK(a.stats.segments == b.stats.segments);
    ++checked;
  }
  CHECK(checked == 4);
}

TEST_CASE("field layout: a wall's end traces only the ray continuing it, unless that ray is banned") {
  // On the subdivided cube, a two-edge wall x = 0, y in [-0.5, 0.5] inside the top face: both
  // ends at regular vertices. By default each end continues the wall (one curve each); with
  // wall_side_rays each end also traces its two side rays (four curves more), which run beside
  // the wall. Where the continuing ray is banned, the end traces its side rays instead.
  const Surface s = igm_test::subdivided_cube(4);
  const std::vector<int> wall = top_line(s, {-0.5, 0.0, 0.5});
  REQUIRE(wall.size() == 3);
  const std::vector<Vec3d> d = directions_along(s, wall);
  TraceOptions t;
  t.walls = {wall};
  const TraceGraph plain = trace_motorcycles(s.mesh, s.positions, d, t);
  CHECK(check_trace_graph(s.mesh, plain) == "");
  CHECK(plain.stats.cones == 8);
  // Curves other than the wall (drawn first: curve 0) that start at vertex v.
  auto starting_at = [](const TraceGraph& g, int v) {
    int n = 0;
    for (std::size_t c = 1; c < g.curves.size(); ++c) {
      const TracePoint& p = g.points[g.curves[c].points.front()];
      n += p.kind == TracePoint::Kind::Vertex && p.element == v;
    }
    return n;
  };
  CHECK(starting_at(plain, wall.front()) == 1);
  CHECK(starting_at(plain, wall.back()) == 1);
  CHECK(starting_at(plain, wall[1]) == 0);
  t.wall_side_rays = true;
  const TraceGraph sides = trace_motorcycles(s.mesh, s.positions, d, t);
  CHECK(check_trace_graph(s.mesh, sides) == "");
  CHECK(starting_at(sides, wall.front()) == 3);
  CHECK(starting_at(sides, wall.back()) == 3);
  t.wall_side_rays = false;
  // Banning each ray of the first end in turn: only banning the continuing one changes what starts
  // there (its side rays instead); the wall's own ray is never traced from it.
  int changed = 0;
  for (int k = 0; k < 4; ++k) {
    t.banned_rays = {{wall.front(), k}};
    const TraceGraph g = trace_motorcycles(s.mesh, s.positions, d, t);
    CHECK(check_trace_graph(s.mesh, g) == "");
    if (starting_at(g, wall.front()) != 1) {
      CHECK(starting_at(g, wall.front()) >= 2);
      ++changed;
    }
  }
  CHECK(changed == 1);
  // Both layouts are valid; continuing the wall alone makes fewer patches.
  FieldLayoutOptions o;
  o.trace.walls = {wall};
  const FieldLayoutResult a = build_field_layout(s.mesh, s.positions, d, o);
  check_layout(a, "cube with a wall inside a face");
  o.trace.wall_side_rays = true;
  const FieldLayoutResult b = build_field_layout(s.mesh, s.positions, d, o);
  check_layout(b, "cube with a wall inside a face, side rays");
  CHECK(a.layout.patches.size() < b.layout.patches.size());
}
