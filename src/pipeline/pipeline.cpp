#include "igm/pipeline/pipeline.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "igm/arrange/overlay.h"
#include "igm/arrange/quad_template.h"
#include "igm/core/error.h"
#include "igm/embed/polygon.h"
#include "igm/extract/quad_extract.h"
#include "igm/igm/quad_charts.h"
#include "igm/mesh/surface_point.h"
#include "pipeline_internal.h"

namespace igm {

namespace {

using Clock = StageReporter::Clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

Vec2d to_vec2d(const Point2q& p) { return {to_double(p.x), to_double(p.y)}; }

std::string format(const char* fmt, double a = 0, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

// This machine's physical memory in bytes, 0 if unknown.
std::uint64_t physical_memory() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
}

// The memory limit in bytes (PipelineOptions::memory_limit_bytes, or this machine's memory; 0 if
// unknown).
std::uint64_t memory_limit(const PipelineOptions& options) {
  return options.memory_limit_bytes > 0 ? options.memory_limit_bytes : physical_memory();
}

// The most arrangement triangles the memory limit allows the stages after it (kBytesPerIgmTriangle
// each); 0 (no cap) if the limit is unknown.
std::size_t triangle_cap(const PipelineOptions& options) {
  const std::uint64_t limit = memory_limit(options);
  return limit == 0 ? 0 : std::max<std::size_t>(1, static_cast<std::size_t>(static_cast<double>(limit) / kBytesPerIgmTriangle));
}

// The error for an arrangement stopped by the overlay at `cap` triangles (triangle_cap).
[[noreturn]] void memory_error(std::size_t cap, const PipelineOptions& options) {
  const double mb = static_cast<double>(memory_limit(options)) / (1024.0 * 1024.0);
  throw Error(ErrorKind::Unsupported,
              format("the arrangement would have more than %.0f triangles, the most that the ", static_cast<double>(cap)) +
                  (mb >= 1024 ? format("%.1f GB ", mb / 1024) : format("%.0f MB ", mb)) +
                  (options.memory_limit_bytes > 0 ? "memory limit" : "of this machine's memory") +
                  format(" allows the IGM, its quads and its certificate (%.0f bytes per triangle)", kBytesPerIgmTriangle) +
                  (options.normal_form ? "; without the normal form the topology stage grows the mesh far less" : ""));
}

}  // namespace

void StageReporter::done(const char* name, Clock::time_point t0, std::string detail) {
  StageEvent e{name, seconds_since(t0), std::move(detail)};
  stats.stages.push_back(e);
  if (options.progress) options.progress(e);
}

void certify_outputs(PipelineResult& result, int genus, const PipelineOptions& options) {
  const IgmMesh& igm = result.igm;
  const QuadMesh& quads = result.quads;
  certify::Options copt;
  copt.max_witnesses = options.max_witnesses;
  certify::IgmInput cin;
  cin.faces = igm.triangles;
  cin.num_vertices = static_cast<std::int64_t>(igm.positions.size());
  cin.corner_uv.reserve(3 * igm.corner_uv.size());
  for (const auto& tri : igm.corner_uv)
    for (const Point2q& uv : tri) cin.corner_uv.push_back({uv.x, uv.y});
  result.igm_report = certify::certify_igm(std::move(cin), copt);
  certify::QuadInput qin;
  qin.quads = quads.quads;
  qin.num_vertices = static_cast<std::int64_t>(quads.positions.size());
  certify::Options qopt = copt;
  qopt.expected_genus = genus;
  result.quad_report = certify::certify_quads(qin, qopt);
}

std::vector<SurfacePoint> take_locations(RefinedSurface& surface, std::size_t more) {
  std::vector<SurfacePoint> locations;
  locations.reserve(surface.mesh.num_vertices() + more);
  for (int v = 0; v < surface.num_input_vertices; ++v) locations.push_back(SurfacePoint::vertex(v));
  for (SurfacePoint& p : surface.constructed) locations.push_back(std::move(p));
  surface.constructed = {};
  return locations;
}

Vec3d position_in_triangle(const IgmMesh& igm, int triangle, const std::array<Rational, 3>& w,
                           const std::vector<Vec3d>& input_positions) {
  const std::array<int, 3>& t = igm.triangles[triangle];
  return evaluate(barycentric_point(igm.locations[t[0]], igm.locations[t[1]], igm.locations[t[2]], w), input_positions);
}

PipelineResult compute_igm(const ValidMesh& input, const PipelineOptions& options) {
  if (options.resolution < 1 || options.resolution > 1024)
    throw Error(ErrorKind::InvalidArgument, "resolution must be in 1..1024, got " + std::to_string(options.resolution));
  if (input.genus == 0) return compute_igm_sphere(input, options);  // sphere_pipeline.cpp
  if (!options.cones.empty())
    throw Error(ErrorKind::InvalidArgument, "cones: only a genus-0 mesh takes a cone list (this one has genus " +
                                                std::to_string(input.genus) + ")");
  PipelineResult result;
  PipelineStats& stats = result.stats;
  StageReporter stage{stats, options};
  stats.genus = input.genus;
  stats.input_vertices = input.mesh.num_vertices();
  stats.input_faces = input.mesh.num_faces();

  // --- topology: 2g loops through the root in normal form, the cut disk ---
  auto t0 = Clock::now();
  CutOptions cut_options;
  cut_options.root = options.root;
  cut_options.normal_form = options.normal_form;
  cut_options.restarts = options.restarts;
  CutResult cut = cut_to_canonical_disk(input.mesh, input.positions, cut_options);
  const int g = cut.genus;
  stats.cut = cut.stats;
  stats.refined_vertices = cut.surface.mesh.num_vertices();
  stats.refined_faces = cut.surface.mesh.num_faces();
  stage.done("topology", t0,
             format("genus %.0f, root %.0f, %.0f -> %.0f vertices", g, cut.root, stats.input_vertices,
                    stats.refined_vertices) +
                 (options.normal_form ? ", normal form in " + std::to_string(cut.stats.normal_form_rounds) + " rounds"
                                      : std::string()) +
                 (cut.stats.restarts > 0 ? ", run " + std::to_string(cut.stats.restart_kept) + " of " +
                                               std::to_string(cut.stats.restarts) + " restarts kept"
                                         : std::string()));

  // --- embed: rational convex 4g-gon, boundary at matched parameters, certified Tutte ---
  t0 = Clock::now();
  const std::vector<Point2q> corners = canonical_polygon(g);
  const Point2q centre = polygon_centre(corners);
  std::vector<int> side_counts;
  for (const BoundarySide& s : cut.sides) side_counts.push_back(static_cast<int>(s.disk_vertices.size()) - 1);
  if (static_cast<int>(cut.sides.size()) != 4 * g || cut.sides.empty() || cut.boundary.empty() ||
      cut.sides[0].disk_vertices.front() != cut.boundary.front())
    throw Error(ErrorKind::Internal, "topology returned a boundary that does not start at side 0");
  const std::vector<Point2q> boundary_uv = place_boundary(corners, side_counts);
  const int num_disk_vertices = static_cast<int>(cut.disk_to_surface.size());
  TutteResult tutte = tutte_embed(num_disk_vertices, cut.disk_triangles, cut.boundary, boundary_uv, options.tutte);
  stats.tutte = tutte.stats;
  stage.done("embed", t0,
             format("%.0f interior vertices, %.0f flips in double, %.0f refinement steps, %.0f bits max",
                    tutte.stats.interior_vertices, static_cast<double>(tutte.stats.flips_double),
                    tutte.stats.iterations, static_cast<double>(tutte.stats.max_bits)));

  // --- arrange: overlay the quad template exactly ---
  t0 = Clock::now();
  const QuadTemplate layout = make_quad_template(corners, centre);
  const std::vector<TemplateSegment> layout_segments = template_segments(layout);
  const std::vector<Segment2> segments = template_geometry(layout, layout_segments);
  PlanarTriangulation disk{std::move(tutte.uv), cut.disk_triangles};
  // The overlay stops as soon as it would pass what the memory allows the stages after it (its own
  // lower bound: a triangle per new point; its output at the end), instead of building all of it
  // first (cheese with the normal form: 36.7M triangles, 5.6 min and 14.5 GB).
  OverlayOptions overlay_options;
  overlay_options.max_triangles = triangle_cap(options);
  OverlayResult overlay;
  try {
    overlay = overlay_segments(disk, segments, overlay_options);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Unsupported || overlay_options.max_triangles == 0) throw;
    memory_error(overlay_options.max_triangles, options);
  }
  stage.done("arrange", t0,
             format("%.0f layout quads, %.0f crossings, %.0f -> %.0f triangles", static_cast<double>(layout.quads.size()),
                    static_cast<double>(overlay.stats.crossings), static_cast<double>(disk.triangles.size()),
                    static_cast<double>(overlay.mesh.triangles.size())));

  // --- igm: piecewise-affine map of every layout quad onto the unit square ---
  t0 = Clock::now();
  QuadCharts charts = compute_quad_charts(layout, overlay);
  stats.max_uv_bits = charts.max_uv_bits;
  // Output vertices: overlay vertices below num_disk_vertices are disk vertices, i.e. copies of
  // surface vertices (the disk boundary gets no new vertex: template segments meet it only at
  // polygon corners); the others are new interior points, each a vertex of its own. Output
  // vertex ids: the surface's (input vertices first, then its constructed ones), then the new points.
  RefinedSurface& surface = cut.surface;
  const int num_overlay_vertices = static_cast<int>(overlay.mesh.positions.size());
  IgmMesh& igm = result.igm;
  igm.locations = take_locations(surface, num_overlay_vertices - num_disk_vertices);  // surface.point() is not used below
  std::vector<SurfacePoint>& locations = igm.locations;
  std::vector<int> out_vertex(num_overlay_vertices);
  for (int v = 0; v < num_overlay_vertices; ++v) {
    const VertexOrigin& o = overlay.origin[v];
    if (v < num_disk_vertices) {
      out_vertex[v] = cut.disk_to_surface[v];
      continue;
    }
    if (o.input_vertex >= 0 || o.input_triangle < 0)
      throw Error(ErrorKind::Internal, "overlay vertex " + std::to_string(v) + " has no location in a disk triangle");
    const auto& tri = cut.disk_triangles[o.input_triangle];
    out_vertex[v] = static_cast<int>(locations.size());
    locations.push_back(barycentric_point(locations[cut.disk_to_surface[tri[0]]], locations[cut.disk_to_surface[tri[1]]],
                                          locations[cut.disk_to_surface[tri[2]]], o.barycentric));
  }
  igm.positions.reserve(locations.size());
  for (int v = 0; v < surface.num_input_vertices; ++v) igm.positions.push_back(surface.input_positions[v]);
  for (std::size_t v = surface.num_input_vertices; v < locations.size(); ++v)
    igm.positions.push_back(evaluate(locations[v], surface.input_positions));
  igm.triangles.reserve(overlay.mesh.triangles.size());
  for (const auto& t : overlay.mesh.triangles) igm.triangles.push_back({out_vertex[t[0]], out_vertex[t[1]], out_vertex[t[2]]});
  stats.output_vertices = static_cast<int>(igm.positions.size());
  stats.output_triangles = static_cast<int>(igm.triangles.size());
  stats.layout_quads = static_cast<int>(layout.quads.size());
  stage.done("igm", t0,
             format("%.0f triangles (%.2fx input), UV bits max %.0f", stats.output_triangles,
                    double(stats.output_triangles) / std::max(1, stats.input_faces), double(stats.max_uv_bits)));

  // --- extract: N x N quads per layout quad, 3D positions by exact location ---
  t0 = Clock::now();
  // Sides are glued as the cut says (any one-vertex word: every side is a whole edge of one
  // layout quad, so the gluing is rigid with an integer translation whatever the word).
  SidePairing pairing;
  for (const BoundarySide& s : cut.sides) {
    pairing.partner.push_back(s.mate);
    pairing.reversed.push_back(1);
  }
  PlanarQuadMesh planar = extract_quads(layout, overlay, charts, options.resolution, pairing);
  QuadMesh& quads = result.quads;
  quads.quads = planar.quads;
  quads.positions.reserve(planar.vertices.size());
  for (const QuadVertexLocation& loc : planar.vertices)  // igm triangle i = overlay triangle i, in output ids
    quads.positions.push_back(position_in_triangle(igm, loc.triangle, loc.barycentric, surface.input_positions));
  stats.quads = static_cast<int>(quads.quads.size());
  igm.corner_uv = std::move(charts.uv);  // charts are not needed after extraction
  stage.done("extract", t0,
             format("resolution %.0f: %.0f quads, %.0f vertices", options.resolution, stats.quads,
                    double(quads.positions.size())));

  // --- the picture ---
  SchemaDrawing& d = result.schema;
  for (const Point2q& c : corners) d.polygon.push_back(to_vec2d(c));
  for (const BoundarySide& s : cut.sides) d.side_pair.push_back(s.mate);
  for (std::size_t i = 0; i < segments.size(); ++i)
    (layout_segments[i].diagonal ? d.diagonals : d.template_edges)
        .push_back({to_vec2d(segments[i].a), to_vec2d(segments[i].b)});
  for (const Point2q& p : layout.points) d.cones.push_back(to_vec2d(p));
  for (const auto& t : overlay.mesh.triangles)
    for (int i = 0; i < 3; ++i)
      if (t[i] < t[(i + 1) % 3])
        d.mesh_edges.push_back({to_vec2d(overlay.mesh.positions[t[i]]), to_vec2d(overlay.mesh.positions[t[(i + 1) % 3]])});
  // Release the stages' data before the certifier makes its own copy of the mesh.
  overlay = OverlayResult{};
  disk = PlanarTriangulation{};

  // --- certify: the independent judge, on both outputs ---
  t0 = Clock::now();
  certify_outputs(result, g, options);
  stage.done("certify", t0, "IGM: " + certify::summary(result.igm_report) + "; quads: " + certify::summary(result.quad_report));

  return result;
}

}  // namespace igm
