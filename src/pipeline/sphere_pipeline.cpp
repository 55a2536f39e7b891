#include "pipeline_internal.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "igm/core/error.h"
#include "igm/embed/orbifold_tutte.h"
#include "igm/extract/orbifold_quads.h"
#include "igm/mesh/surface_point.h"
#include "igm/layout/sizing.h"
#include "igm/mesh/scale.h"
#include "igm/topology/sphere_cut.h"

namespace igm {

namespace {

using Clock = StageReporter::Clock;

Vec2d to_vec2d(const Point2q& p) { return {approximate(p.x), approximate(p.y)}; }  // for the picture

}  // namespace

PipelineResult compute_igm_sphere(const ValidMesh& input, const PipelineOptions& options) {
  PipelineResult result;
  PipelineStats& stats = result.stats;
  stats.genus = 0;
  stats.input_vertices = input.mesh.num_vertices();
  stats.input_faces = input.mesh.num_faces();
  StageReporter stage{stats, options};
  auto t0 = Clock::now();
  // Each stage runs from the end of the one before.
  auto done = [&](const char* name, std::string detail) {
    stage.done(name, t0, std::move(detail));
    t0 = Clock::now();
  };
  char line[256];

  // --- topology: four cones, one path through them, the cut disk ---
  SphereCutOptions cut_options;
  cut_options.cones = options.cones;
  SphereCut cut = cut_sphere(input.mesh, input.positions, cut_options);
  RefinedSurface& surface = cut.surface;
  stats.cones = cut.cones;
  stats.sphere_cut = cut.stats;
  stats.refined_vertices = surface.mesh.num_vertices();
  stats.refined_faces = surface.mesh.num_faces();
  std::snprintf(line, sizeof line, "genus 0, cones %d %d %d %d, path of %d edges, %d -> %d vertices (%d + %d splits)",
                cut.cones[0], cut.cones[1], cut.cones[2], cut.cones[3], cut.stats.path_edges, stats.input_vertices,
                stats.refined_vertices, cut.stats.cone_splits, cut.stats.chord_splits);
  done("topology", line);

  // --- embed: orbifold Tutte onto the pillowcase, certified ---
  RefinementOptions ro;
  ro.max_iterations = options.tutte.max_iterations;
  ro.min_iterations = options.tutte.min_iterations;
  ro.exact_fallback_max_unknowns = options.tutte.exact_fallback_max_interior;
  const double scale = unit_scale(input.positions);  // lengths and weights of hostile coordinates stay in range
  std::vector<Vec3d> surface_positions(surface.mesh.num_vertices());
  for (int v = 0; v < surface.mesh.num_vertices(); ++v) {
    const Vec3d p = surface.position(v);
    surface_positions[v] = {scale * p.x, scale * p.y, scale * p.z};
  }
  std::vector<std::array<int, 3>> surface_faces(surface.mesh.num_faces());
  for (int f = 0; f < surface.mesh.num_faces(); ++f) surface_faces[f] = surface.mesh.face_vertices(f);
  OrbifoldTutteResult embedding =
      orbifold_tutte_embed(cut, edge_weights(surface_positions, surface_faces, options.patch_weights), ro);
  const OrbifoldTutteStats& es = embedding.stats;
  stats.orbifold = es;
  stats.max_uv_bits = es.max_bits;
  std::snprintf(line, sizeof line, "%d free vertices, %lld flips in double, %d refinement steps, %zu bits max",
                es.free_vertices, static_cast<long long>(es.refinement.flips_double), es.refinement.iterations,
                es.max_bits);
  done("embed", line);

  // --- sizing: nx quads per unit of the pillowcase in x, ny in y ---
  // The mean 3D length of a unit step in x and in y over the domain (area 2): for each disk
  // triangle with UV edges (a, b), (c, d) and 3D edges P1, P2 the map's columns are
  // J e_x = (d P1 - b P2) / det and J e_y = (a P2 - c P1) / det, weighted by the UV area det / 2.
  double lx = 0, ly = 0;
  for (std::size_t f = 0; f < cut.disk_triangles.size(); ++f) {
    const auto& t = cut.disk_triangles[f];
    const Vec2d u0 = to_vec2d(embedding.uv[t[0]]), u1 = to_vec2d(embedding.uv[t[1]]), u2 = to_vec2d(embedding.uv[t[2]]);
    const Vec3d &p0 = surface_positions[surface_faces[f][0]], &p1 = surface_positions[surface_faces[f][1]],
                &p2 = surface_positions[surface_faces[f][2]];
    const double a = u1.x - u0.x, b = u1.y - u0.y, c = u2.x - u0.x, d = u2.y - u0.y;
    const Vec3d P1{p1.x - p0.x, p1.y - p0.y, p1.z - p0.z}, P2{p2.x - p0.x, p2.y - p0.y, p2.z - p0.z};
    auto norm = [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z); };
    lx += 0.5 * norm(d * P1.x - b * P2.x, d * P1.y - b * P2.y, d * P1.z - b * P2.z);
    ly += 0.5 * norm(a * P2.x - c * P1.x, a * P2.y - c * P1.y, a * P2.z - c * P1.z);
  }
  lx /= 2, ly /= 2;  // per unit of the domain's area 2
  if (!std::isfinite(lx) || !std::isfinite(ly)) lx = ly = 0;
  // Raw counts by H, and the grid: its floor (pillowcase_grid_floor), the nearest manifold grid.
  auto raw_counts = [&](double H) {
    auto c = [&](double l) { return static_cast<int>(std::min(4096.0, std::max(1.0, std::nearbyint(l / H)))); };
    return std::array<int, 2>{c(lx), c(ly)};
  };
  auto counts = [&](double H) { return pillowcase_grid_floor(raw_counts(H)); };
  std::array<int, 2> n{options.resolution, options.resolution};
  stats.floor_quads = 2;
  if (options.resolution <= 0) {
    double H = options.edge_length * scale;
    if (H <= 0) {
      const std::int64_t target = options.quads > 0 ? options.quads : kDefaultQuads;
      stats.quads_asked = target;
      const double hi = 2 * std::max(lx, ly);
      H = hi > 0 ? edge_length_for_quads(
                       [&](double h) {
                         const auto c = counts(h);
                         return std::int64_t(2) * c[0] * c[1];
                       },
                       hi / 8192, hi, target)
                 : 1;
    }
    n = counts(H);
    const std::array<int, 2> raw = raw_counts(H);
    stats.raised_chords = (n[0] > raw[0]) + (n[1] > raw[1]);
    stats.edge_length = H / scale;
  }
  stats.grid = n;

  // --- igm: the embedding scaled by (nx, ny) is the IGM (transitions x -> +-x + t, t integer; cones
  // at integer points): one UV unit per quad ---
  // Output vertices are the surface's: the input vertices, then its constructed ones.
  IgmMesh& igm = result.igm;
  const int nv = surface.mesh.num_vertices(), nf = surface.mesh.num_faces();
  igm.positions.reserve(nv);
  for (int v = 0; v < nv; ++v) igm.positions.push_back(surface.position(v));
  igm.locations = take_locations(surface);  // surface.point() is not used below
  igm.triangles.resize(nf);
  igm.corner_uv.resize(nf);
  for (int f = 0; f < nf; ++f) {
    igm.triangles[f] = surface.mesh.face_vertices(f);
    for (int i = 0; i < 3; ++i) {
      const Point2q& p = embedding.uv[cut.disk_triangles[f][i]];
      igm.corner_uv[f][i] = {Rational(p.x * n[0]), Rational(p.y * n[1])};
    }
  }
  stats.max_uv_bits = 0;
  for (const auto& tri : igm.corner_uv)
    for (const Point2q& p : tri) stats.max_uv_bits = std::max({stats.max_uv_bits, bit_size(p.x), bit_size(p.y)});
  stats.output_vertices = nv;
  stats.output_triangles = nf;
  stats.layout_quads = 2;
  stats.layout = "orbifold";
  std::snprintf(line, sizeof line, "%d triangles (%.2fx input), %d x %d quads per unit (%lld quads)%s, UV bits max %zu", nf,
                double(nf) / std::max(1, stats.input_faces), n[0], n[1], 2LL * n[0] * n[1],
                stats.raised_by_floor() ? (", " + floor_note(stats)).c_str() : "", stats.max_uv_bits);
  done("igm", line);

  // --- the picture: the disk in UV, its 6 sides coloured by pair, the domain's grid, the cones ---
  SchemaDrawing& d = result.schema;
  for (int c = 0; c < 6; ++c) {
    const auto p = pillowcase_corner(c);
    d.polygon.push_back({double(p[0]), double(p[1])});
  }
  d.side_pair = {5, 4, 3, 2, 1, 0};
  const int nb = static_cast<int>(cut.boundary.size());
  for (int s = 0; s < 6; ++s) {
    std::vector<Vec2d> path;
    const int end = s == 5 ? nb : cut.corners[s + 1];
    for (int i = cut.corners[s]; i <= end; ++i) path.push_back(to_vec2d(embedding.uv[cut.boundary[i % nb]]));
    d.side_paths.push_back(std::move(path));
  }
  for (int i = 0; i <= 2 * n[0]; ++i) d.template_edges.push_back({Vec2d{double(i) / n[0], 0}, Vec2d{double(i) / n[0], 1}});
  for (int j = 0; j <= n[1]; ++j) d.template_edges.push_back({Vec2d{0, double(j) / n[1]}, Vec2d{2, double(j) / n[1]}});
  d.cones = d.polygon;
  std::vector<Vec2d> uvd(embedding.uv.size());
  for (std::size_t v = 0; v < uvd.size(); ++v) uvd[v] = to_vec2d(embedding.uv[v]);
  for (const auto& t : cut.disk_triangles)
    for (int i = 0; i < 3; ++i)
      if (t[i] < t[(i + 1) % 3]) d.mesh_edges.push_back({uvd[t[i]], uvd[t[(i + 1) % 3]]});
  embedding = OrbifoldTutteResult{};

  // --- smooth, extract (the 2 a b cells of the domain, or the smoothed map's isolines), certify ---
  smooth_extract_certify(result, options, stage, surface.input_positions, [&] {
    // The cells of the domain, located in the disk's map: its vertices' UVs back from the IGM's
    // corners (put on a double grid, they may differ from the embedding's), unscaled.
    std::vector<Point2q> disk_uv(cut.disk_to_surface.size());
    const Rational sx = make_rational(Integer(1), Integer(n[0])), sy = make_rational(Integer(1), Integer(n[1]));
    for (int f = 0; f < nf; ++f)
      for (int i = 0; i < 3; ++i)
        disk_uv[cut.disk_triangles[f][i]] = {Rational(igm.corner_uv[f][i].x * sx), Rational(igm.corner_uv[f][i].y * sy)};
    const OrbifoldQuadMesh grid = extract_orbifold_quads(cut.disk_triangles, disk_uv, n[0], n[1]);
    QuadMesh& quads = result.quads;
    quads.quads = grid.quads;
    quads.positions.reserve(grid.triangle.size());
    quads.locations.reserve(grid.triangle.size());
    for (std::size_t v = 0; v < grid.triangle.size(); ++v)  // igm triangle f = disk triangle f, in output ids
      add_quad_vertex(quads, igm, grid.triangle[v], grid.barycentric[v], surface.input_positions);
    return std::to_string(n[0]) + " x " + std::to_string(n[1]) + " cells per unit of the pillowcase";
  });
  measure_quality(result, input, options, stage);
  return result;
}

}  // namespace igm
