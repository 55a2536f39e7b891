#include "pipeline_internal.h"

#include <chrono>
#include <cstdio>
#include <string>

#include "igm/core/error.h"
#include "igm/embed/orbifold_tutte.h"
#include "igm/extract/orbifold_quads.h"
#include "igm/mesh/surface_point.h"
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
  OrbifoldTutteResult embedding = orbifold_tutte_embed(cut, ro);
  const OrbifoldTutteStats& es = embedding.stats;
  stats.orbifold = es;
  stats.max_uv_bits = es.max_bits;
  std::snprintf(line, sizeof line, "%d free vertices, %lld flips in double, %d refinement steps, %zu bits max",
                es.free_vertices, static_cast<long long>(es.refinement.flips_double), es.refinement.iterations,
                es.max_bits);
  done("embed", line);

  // --- igm: the embedding is the IGM (transitions x -> +-x + t, t integer; cones at integer points) ---
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
    for (int i = 0; i < 3; ++i) igm.corner_uv[f][i] = embedding.uv[cut.disk_triangles[f][i]];
  }
  stats.output_vertices = nv;
  stats.output_triangles = nf;
  stats.layout_quads = 2;
  std::snprintf(line, sizeof line, "%d triangles (%.2fx input), UV bits max %zu", nf,
                double(nf) / std::max(1, stats.input_faces), es.max_bits);
  done("igm", line);

  // --- extract: the 2 N^2 cells of the domain, vertices located exactly ---
  const OrbifoldQuadMesh grid = extract_orbifold_quads(cut.disk_triangles, embedding.uv, options.resolution);
  QuadMesh& quads = result.quads;
  quads.quads = grid.quads;
  quads.positions.reserve(grid.triangle.size());
  for (std::size_t v = 0; v < grid.triangle.size(); ++v)  // igm triangle f = disk triangle f, in output ids
    quads.positions.push_back(position_in_triangle(igm, grid.triangle[v], grid.barycentric[v], surface.input_positions));
  stats.quads = static_cast<int>(quads.quads.size());
  std::snprintf(line, sizeof line, "resolution %d: %d quads, %zu vertices", options.resolution, stats.quads,
                quads.positions.size());
  done("extract", line);

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
  const int N = options.resolution;
  for (int i = 0; i <= 2 * N; ++i) d.template_edges.push_back({Vec2d{double(i) / N, 0}, Vec2d{double(i) / N, 1}});
  for (int j = 0; j <= N; ++j) d.template_edges.push_back({Vec2d{0, double(j) / N}, Vec2d{2, double(j) / N}});
  d.cones = d.polygon;
  std::vector<Vec2d> uvd(embedding.uv.size());
  for (std::size_t v = 0; v < uvd.size(); ++v) uvd[v] = to_vec2d(embedding.uv[v]);
  for (const auto& t : cut.disk_triangles)
    for (int i = 0; i < 3; ++i)
      if (t[i] < t[(i + 1) % 3]) d.mesh_edges.push_back({uvd[t[i]], uvd[t[(i + 1) % 3]]});
  embedding = OrbifoldTutteResult{};

  // --- certify: the independent judge, on both outputs ---
  certify_outputs(result, 0, options);
  done("certify", "IGM: " + certify::summary(result.igm_report) + "; quads: " + certify::summary(result.quad_report));
  return result;
}

}  // namespace igm
