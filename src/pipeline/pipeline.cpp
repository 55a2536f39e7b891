#include "igm/pipeline/pipeline.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include <cmath>

#include "../core/parallel.h"
#include "igm/arrange/overlay.h"
#include "igm/core/error.h"
#include "igm/core/memory.h"
#include "igm/core/threads.h"
#include "igm/embed/polygon.h"
#include "igm/extract/isolines.h"
#include "igm/extract/patch_grid.h"
#include "igm/igm/layout_map.h"
#include "igm/extract/quad_defects.h"
#include "igm/igm/patch_mesh.h"
#include "igm/mesh/scale.h"
#include "igm/mesh/surface_point.h"
#include "igm/smooth/dyadic.h"
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

void check_sizes(const PipelineOptions& options) {
  if (options.resolution < 0 || options.resolution > 1024)
    throw Error(ErrorKind::InvalidArgument, "resolution must be in 1..1024 (or 0: none), got " +
                                                std::to_string(options.resolution));
  if (!(options.edge_length >= 0) || !std::isfinite(options.edge_length))
    throw Error(ErrorKind::InvalidArgument, "the edge length must be positive and finite (or 0: none)");
  if (options.quads < 0 || options.quads > (std::int64_t(1) << 31))
    throw Error(ErrorKind::InvalidArgument, "the quad count must be in 1..2^31 (or 0: none), got " +
                                                std::to_string(options.quads));
}

SizingOptions sizing_options(const PipelineOptions& options, double scale) {
  SizingOptions s;
  if (options.resolution > 0) s.resolution = options.resolution;
  else if (options.edge_length > 0) s.edge_length = options.edge_length * scale;
  else s.quads = options.quads > 0 ? options.quads : kDefaultQuads;
  return s;
}

std::string floor_note(const PipelineStats& stats) {
  if (!stats.raised_by_floor()) return "";
  if (stats.quads_asked > 0)
    return format("at the floor of %.0f quads (%.0f asked)", double(stats.floor_quads), double(stats.quads_asked));
  const bool grid = stats.genus == 0 && stats.boundary_loops == 0;
  return format("%.0f ", stats.raised_chords) + (grid ? "grid count" : "chord") + (stats.raised_chords == 1 ? "" : "s") +
         format(" raised to the floor (%.0f quads at least)", double(stats.floor_quads));
}

StageReporter::StageReporter(PipelineStats& s, const PipelineOptions& o)
    : stats(s), options(o), cpu(process_cpu_seconds()) {
  if (options.measure_stage_memory) peak_resident_mb(true);
}

void StageReporter::done(const char* name, Clock::time_point t0, std::string detail) {
  StageEvent e{name, seconds_since(t0), std::move(detail)};
  if (options.measure_stage_memory) e.peak_mb = peak_resident_mb(true);
  const double now = process_cpu_seconds();
  e.cpu_seconds = now - cpu;
  cpu = now;
  stats.stages.push_back(e);
  if (options.progress) options.progress(e);
}

void certify_outputs(PipelineResult& result, const PipelineOptions& options, bool igm_report_done) {
  const IgmMesh& igm = result.igm;
  const QuadMesh& quads = result.quads;
  const int genus = result.stats.genus;
  certify::Options copt;
  copt.max_witnesses = options.max_witnesses;
  copt.allow_boundary = result.stats.boundary_loops > 0;
  copt.threads = resolve_threads(options.threads);
  if (!igm_report_done) result.igm_report = certify::certify_igm(certify_input(igm, igm.corner_uv), copt);
  certify::QuadInput qin;
  qin.quads = quads.quads;
  qin.num_vertices = static_cast<std::int64_t>(quads.positions.size());
  certify::Options qopt = copt;
  qopt.expected_genus = genus;
  if (result.stats.boundary_loops > 0) qopt.expected_boundary_loops = result.stats.boundary_loops;
  result.quad_report = certify::certify_quads(qin, qopt);
}

void measure_quality(PipelineResult& result, const ValidMesh& input, const PipelineOptions& options,
                     StageReporter& stage) {
  if (!options.quality) return;
  std::vector<std::array<int, 3>> input_triangles(input.mesh.num_faces());
  for (int f = 0; f < input.mesh.num_faces(); ++f) input_triangles[f] = input.mesh.face_vertices(f);
  measure_quality(result, input.positions, input_triangles, options, stage);
}

void measure_quality(PipelineResult& result, const std::vector<Vec3d>& input_positions,
                     const std::vector<std::array<int, 3>>& input_triangles, const PipelineOptions& options,
                     StageReporter& stage) {
  if (!options.quality) return;
  const auto t0 = Clock::now();
  std::vector<std::array<Vec2d, 3>> uv(result.igm.corner_uv.size());
  parallel::for_each_index(static_cast<std::int64_t>(uv.size()), 4096, [&](std::int64_t t) {
    for (int i = 0; i < 3; ++i) uv[t][i] = {approximate(result.igm.corner_uv[t][i].x), approximate(result.igm.corner_uv[t][i].y)};
  });
  result.igm_quality = measure_igm(result.igm.positions, result.igm.triangles, uv);
  QuadQualityOptions qo;
  qo.distance = options.quality_distance;
  result.quad_quality = measure_quads(result.quads.positions, result.quads.quads, input_positions, input_triangles, qo);
  stage.done("quality", t0, summary_line(result.igm_quality, result.quad_quality));
}

void smooth_extract_certify(PipelineResult& result, const PipelineOptions& options, StageReporter& stage,
                            const std::vector<Vec3d>& input_positions, const std::function<std::string()>& structured,
                            const std::vector<std::pair<int, int>>& isoline_edges) {
  IgmMesh& igm = result.igm;
  PipelineStats& stats = result.stats;
  auto t0 = Clock::now();
  std::string how;
  const bool smoothing = options.smooth;
  if (smoothing) {
    SmoothOptions so;
    so.max_iterations = options.smooth_iterations;
    const std::int64_t triangles = static_cast<std::int64_t>(igm.triangles.size());
    if (options.smooth_work > 0 && triangles > 0)
      so.max_iterations = static_cast<int>(std::min<std::int64_t>(
          so.max_iterations, std::max<std::int64_t>(5, options.smooth_work / triangles)));
    so.min_relative_decrease = options.smooth_min_decrease;
    so.time_budget_seconds = options.smooth_seconds;
    so.stall_step = options.smooth_stall_step;
    so.certify = false;  // the isolines' extraction runs the certifier on the result below
    so.progress = options.smooth_progress;
    so.threads = resolve_threads(options.threads);
    so.isoline_edges = isoline_edges;
    SmoothResult smoothed = smooth_igm_releasing(igm, so);
    igm.corner_uv = std::move(smoothed.corner_uv);
    stats.smooth = std::move(smoothed.stats);
    stats.uv_doubles = stats.smooth.returned != SmoothReturned::InputExact;
    const SmoothStats& ss = stats.smooth;
    stage.done("smooth", t0,
               format("%.0f iterations, energy %.4g -> %.4g, ", ss.iterations, ss.energy.empty() ? 0.0 : ss.energy.front(),
                      ss.energy.empty() ? 0.0 : ss.energy.back()) +
                   to_string(ss.stop) + (stats.uv_doubles ? ", UVs in doubles" : ", UVs exact rationals"));
    t0 = Clock::now();
  } else {
    DyadicResult rounded = round_to_dyadic(igm);
    if (rounded.stats.on_grid) igm.corner_uv = std::move(rounded.corner_uv);
    stats.dyadic = std::move(rounded.stats);
    stats.uv_doubles = stats.dyadic.on_grid;
  }
  const bool isolines = smoothing || !options.structured_extraction || !structured;
  // What find_quad_defects needs if the certifier refuses the quads (kept slim: the located
  // vertices are released with the extraction; per vertex its valence and boundary flag).
  IsolineQuads slim;
  std::vector<std::pair<int, bool>> valence;
  if (isolines) {
    IsolineInput in;  // the map lent to the extraction (it reads it only), not copied
    in.triangles = std::move(igm.triangles);
    in.corner_uv = std::move(igm.corner_uv);
    IsolineOptions io;
    io.max_witnesses = options.max_witnesses;
    io.allow_boundary = stats.boundary_loops > 0;
    io.threads = resolve_threads(options.threads);
    if (!isoline_edges.empty()) {  // the field layout's feature edges: certified on their isolines
      io.feature_edges.emplace();
      for (const auto& [a, b] : isoline_edges) io.feature_edges->push_back({a, b, 0});
    }
    IsolineResult x = extract_isolines(in, io);
    igm.triangles = std::move(in.triangles);
    igm.corner_uv = std::move(in.corner_uv);
    result.igm_report = std::move(x.report);
    if (x.quads) {
      QuadMesh& quads = result.quads;
      quads.quads = x.quads->quads;
      slim.quad_edges = std::move(x.quads->quad_edges);
      slim.num_edges = x.quads->num_edges;
      valence.reserve(x.quads->vertices.size());
      for (const IsolineQuadVertex& v : x.quads->vertices) valence.emplace_back(v.valence, v.boundary);
      quads.positions.reserve(x.quads->vertices.size());
      quads.locations.reserve(x.quads->vertices.size());
      for (const IsolineQuadVertex& v : x.quads->vertices) add_quad_vertex(quads, igm, v.triangle, v.barycentric, input_positions);
    }
    how = "the integer isolines";
  } else {
    how = structured();
  }
  stats.max_uv_bits = max_uv_bits(igm.corner_uv);
  stats.quads = static_cast<int>(result.quads.quads.size());
  stage.done("extract", t0,
             format("%.0f quads, %.0f vertices from ", stats.quads, double(result.quads.positions.size())) + how);
  t0 = Clock::now();
  certify_outputs(result, options, /*igm_report_done=*/isolines);
  if (isolines && result.igm_report.valid() && !result.quad_report.valid()) {
    slim.quads = result.quads.quads;
    slim.vertices.resize(valence.size());
    for (std::size_t v = 0; v < valence.size(); ++v) slim.vertices[v].valence = valence[v].first, slim.vertices[v].boundary = valence[v].second;
    stats.quad_defects = describe_quad_defects(slim, find_quad_defects(slim, 20));
  }
  stage.done("certify", t0, "IGM: " + certify::summary(result.igm_report) + "; quads: " + certify::summary(result.quad_report) +
                                (stats.quad_defects.empty() ? std::string() : "; " + stats.quad_defects));
}

std::vector<SurfacePoint> take_locations(RefinedSurface& surface, std::size_t more) {
  std::vector<SurfacePoint> locations;
  locations.reserve(surface.mesh.num_vertices() + more);
  for (int v = 0; v < surface.num_input_vertices; ++v) locations.push_back(SurfacePoint::vertex(v));
  for (SurfacePoint& p : surface.constructed) locations.push_back(std::move(p));
  surface.constructed = {};
  return locations;
}

void add_quad_vertex(QuadMesh& quads, const IgmMesh& igm, int triangle, const std::array<Rational, 3>& w,
                     const std::vector<Vec3d>& input_positions) {
  const std::array<int, 3>& t = igm.triangles[triangle];
  quads.locations.push_back(barycentric_point(igm.locations[t[0]], igm.locations[t[1]], igm.locations[t[2]], w));
  quads.positions.push_back(evaluate(quads.locations.back(), input_positions));
}

void map_disk(PipelineResult& result, CutDisk& cut, const PipelineOptions& options, StageReporter& stage,
              const std::vector<Vec3d>& input_positions) {
  PipelineStats& stats = result.stats;
  // --- embed: rational convex 4g-gon, boundary at matched parameters, certified Tutte ---
  auto t0 = Clock::now();
  const int num_sides = static_cast<int>(cut.sides.size());
  if (num_sides < 3 || cut.boundary.empty() || cut.sides[0].disk_vertices.front() != cut.boundary.front())
    throw Error(ErrorKind::Internal, "topology returned a boundary that does not start at side 0");
  const std::vector<Point2q> corners = schema_polygon(num_sides);
  const Point2q centre = polygon_centre(corners);
  RefinedSurface& surface = cut.surface;
  const int num_disk_vertices = static_cast<int>(cut.disk_to_surface.size());
  const double scale = unit_scale(input_positions);  // lengths and weights of hostile coordinates stay in range
  std::vector<Vec3d> disk_positions(num_disk_vertices);
  for (int v = 0; v < num_disk_vertices; ++v) {
    const Vec3d p = surface.position(cut.disk_to_surface[v]);
    disk_positions[v] = {scale * p.x, scale * p.y, scale * p.z};
  }
  std::vector<Point2q> boundary_uv;
  {
    // Paired sides carry the same surface vertices in opposite orders: the parameters of a side
    // are computed once and mirrored onto its mate, so both copies of a vertex sit at t and 1 - t.
    std::vector<std::vector<Rational>> params(cut.sides.size());
    for (std::size_t s = 0; s < cut.sides.size(); ++s) {
      const DiskSide& side = cut.sides[s];
      const std::size_t n = side.disk_vertices.size() - 1;
      if (side.mate >= 0 && side.mate < static_cast<int>(s)) {
        const auto& mp = params[side.mate];
        if (mp.size() != n) throw Error(ErrorKind::Internal, "paired sides have different lengths", {static_cast<std::int64_t>(s)});
        params[s].resize(n);
        params[s][0] = 0;
        for (std::size_t i = 1; i < n; ++i) params[s][i] = 1 - mp[n - i];
        continue;
      }
      std::vector<double> len(n);
      for (std::size_t i = 0; i < n; ++i)
        len[i] = options.disk_arc_length
                     ? scaled_distance(disk_positions[side.disk_vertices[i]], disk_positions[side.disk_vertices[i + 1]], 1)
                     : 1.0;
      std::vector<Rational> t = arc_length_parameters(len, 32);
      t.pop_back();  // the side's last vertex is the next side's corner
      params[s] = std::move(t);
    }
    boundary_uv = place_boundary_at(corners, params);
  }
  const std::vector<int> disk_weights = edge_weights(disk_positions, cut.disk_triangles, options.disk_weights);
  TutteResult tutte = tutte_embed(num_disk_vertices, cut.disk_triangles, cut.boundary, boundary_uv, disk_weights, options.tutte);
  stats.tutte = tutte.stats;
  stage.done("embed", t0,
             format("%.0f interior vertices, %.0f flips in double, %.0f refinement steps, %.0f bits max",
                    tutte.stats.interior_vertices, static_cast<double>(tutte.stats.flips_double),
                    tutte.stats.iterations, static_cast<double>(tutte.stats.max_bits)) +
                 ", " + to_string(options.disk_weights) + " weights" +
                 (options.disk_arc_length ? ", sides by arc length" : ""));

  // --- arrange: the layout overlaid exactly ---
  t0 = Clock::now();
  std::vector<int> mates(cut.sides.size());
  for (std::size_t s = 0; s < cut.sides.size(); ++s) mates[s] = cut.sides[s].mate;
  LayoutOptions layout_options;
  layout_options.kind = options.layout;
  layout_options.rows = options.layout_rows;
  layout_options.ring_depth = options.layout_ring_depth;
  const QuadLayout layout = make_layout(corners, centre, mates, layout_options, cut.corner_label);
  std::vector<Segment2> segments;
  segments.reserve(layout.edges.size() + layout.quads.size());
  for (const LayoutEdge& e : layout.edges) segments.push_back({layout.points[e.a], layout.points[e.b]});
  const bool affine = options.patch_map == PatchMapKind::Affine;
  std::vector<int> diagonals;
  if (affine) {
    diagonals = quad_diagonals(layout);
    for (std::size_t q = 0; q < layout.quads.size(); ++q)
      if (diagonals[q] >= 0)
        segments.push_back({layout.points[layout.quads[q][diagonals[q]]], layout.points[layout.quads[q][diagonals[q] + 2]]});
  }
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
  stats.layout_quads = static_cast<int>(layout.quads.size());
  stats.layout = to_string(options.layout);
  stats.chords = layout.num_chords;
  stats.layout_edges = layout.num_surface_edges;
  stage.done("arrange", t0,
             format("%.0f layout quads, %.0f crossings, %.0f -> %.0f triangles", static_cast<double>(layout.quads.size()),
                    static_cast<double>(overlay.stats.crossings), static_cast<double>(disk.triangles.size()),
                    static_cast<double>(overlay.mesh.triangles.size())) +
                 " (" + to_string(options.layout) + " layout, " + std::to_string(layout.num_chords) + " chords)");

  // --- igm: the patches glued back into the surface, sized, each mapped onto its rectangle ---
  t0 = Clock::now();
  PatchMeshInput pin;
  pin.layout = &layout;
  pin.overlay = &overlay;
  pin.num_disk_vertices = num_disk_vertices;
  pin.disk_to_surface = &cut.disk_to_surface;
  pin.disk_triangles = &cut.disk_triangles;
  pin.surface_locations = take_locations(surface, overlay.mesh.positions.size() - num_disk_vertices);
  pin.input_positions = &surface.input_positions;
  PatchMesh patches = build_patch_mesh(std::move(pin));
  const std::vector<double> lengths = layout_edge_lengths(layout, patches, scale);
  const SizingOptions size_options = sizing_options(options, scale);
  const Sizing sizing = size_layout(layout, lengths, size_options);
  stats.edge_length = sizing.edge_length / scale;
  stats.floor_quads = sizing.floor_quads;
  stats.quads_asked = size_options.quads;
  stats.raised_chords = sizing.raised_chords;
  IgmMesh& igm = result.igm;
  PatchMapStats map_stats;
  if (!affine) {
    // Every layout takes the one back end: the patch mesh as a surface layout, its arcs sized by the
    // chords' counts, mapped by map_layout. Its triangles and vertices are the patch mesh's, with
    // any edge split for the Tutte maps' pre-conditions appended (none on the shared meshes: the
    // overlay's segments cut the triangles they cross).
    LayoutMapOptions map_options;
    map_options.weights = options.patch_weights;
    map_options.tutte = options.tutte;
    map_options.length_scale = scale;
    LayoutMap map = map_layout(to_surface_layout(layout, patches, static_cast<int>(input_positions.size())),
                               sizing.edge_count, map_options);
    map_stats = map.stats;
    igm = std::move(map.igm);
  } else {
    PatchMaps maps = map_patches(layout, patches, sizing, overlay.mesh.positions);
    map_stats = maps.stats;
    igm.triangles.reserve(patches.triangles.size());
    for (const auto& t : patches.triangles)
      igm.triangles.push_back({patches.vertex_of[t[0]], patches.vertex_of[t[1]], patches.vertex_of[t[2]]});
    igm.positions = std::move(patches.positions);
    igm.locations = std::move(patches.locations);
    igm.corner_uv = std::move(maps.corner_uv);
    // Vertices no triangle uses (an open surface's filling: its hole vertices and the points inside
    // its fans, topology/open_cut.h) are dropped; the others keep their order (the input vertices
    // first). A closed surface uses every vertex.
    std::vector<int> id(igm.positions.size(), -1);
    for (const auto& t : igm.triangles)
      for (int v : t) id[v] = 0;
    int next = 0;
    for (int& x : id)
      if (x == 0) x = next++;
    if (next != static_cast<int>(id.size())) {
      for (auto& t : igm.triangles)
        for (int& v : t) v = id[v];
      std::vector<Vec3d> positions(next);
      std::vector<SurfacePoint> locations(next);
      for (std::size_t v = 0; v < id.size(); ++v)
        if (id[v] >= 0) positions[id[v]] = igm.positions[v], locations[id[v]] = std::move(igm.locations[v]);
      igm.positions = std::move(positions);
      igm.locations = std::move(locations);
    }
  }
  stats.patch_maps = map_stats;
  stats.max_uv_bits = map_stats.max_uv_bits;
  stats.output_vertices = static_cast<int>(igm.positions.size());
  stats.output_triangles = static_cast<int>(igm.triangles.size());
  stage.done("igm", t0,
             format("%.0f triangles (%.2fx input), %.0f quads ", stats.output_triangles,
                    double(stats.output_triangles) / std::max(1, stats.input_faces), double(sizing.quads)) +
                 (options.resolution > 0 ? format("at resolution %.0f", double(options.resolution))
                                         : format("of edge length %.3g", stats.edge_length)) +
                 (stats.raised_by_floor() ? ", " + floor_note(stats) : std::string()) +
                 ", " + to_string(options.patch_map) + " maps" +
                 format(", %.0f patches refined, UV bits max %.0f", double(map_stats.patches_refined),
                        double(stats.max_uv_bits)));

  // --- the picture ---
  SchemaDrawing& d = result.schema;
  for (const Point2q& c : corners) d.polygon.push_back(to_vec2d(c));
  for (const DiskSide& s : cut.sides) d.side_pair.push_back(s.mate);
  for (const LayoutEdge& e : layout.edges) d.template_edges.push_back({to_vec2d(layout.points[e.a]), to_vec2d(layout.points[e.b])});
  for (std::size_t q = 0; q < diagonals.size(); ++q)
    if (diagonals[q] >= 0)
      d.diagonals.push_back({to_vec2d(layout.points[layout.quads[q][diagonals[q]]]),
                             to_vec2d(layout.points[layout.quads[q][diagonals[q] + 2]])});
  {
    const std::vector<int> valence = layout.valences();
    for (std::size_t p = 0; p < layout.points.size(); ++p)
      if (valence[layout.layout_vertex[p]] != 4) d.cones.push_back(to_vec2d(layout.points[p]));
  }
  for (const auto& t : overlay.mesh.triangles)
    for (int i = 0; i < 3; ++i)
      if (t[i] < t[(i + 1) % 3])
        d.mesh_edges.push_back({to_vec2d(overlay.mesh.positions[t[i]]), to_vec2d(overlay.mesh.positions[t[(i + 1) % 3]])});
  // Release the stages' data before the certifier makes its own copy of the mesh (and before
  // smoothing: the patch mesh serves only the rectangles' extraction).
  overlay = OverlayResult{};
  disk = PlanarTriangulation{};
  if (options.smooth || !options.structured_extraction) patches = PatchMesh{};

  // --- smooth, extract (the a x b grid of every layout quad, or the smoothed map's isolines),
  // certify ---
  IgmMesh& igm_out = result.igm;
  // The rectangles' grids are found in the patch mesh's triangles: not after map_layout split some.
  std::function<std::string()> rectangles;
  if (map_stats.splits == 0) rectangles = [&] {
    const PatchGrid grid = extract_patch_grids(layout, patches, sizing, igm_out.corner_uv);
    QuadMesh& quads = result.quads;
    quads.quads = grid.quads;
    quads.positions.reserve(grid.vertices.size());
    quads.locations.reserve(grid.vertices.size());
    for (const GridVertex& v : grid.vertices) add_quad_vertex(quads, igm_out, v.triangle, v.barycentric, surface.input_positions);
    return std::string("the layout's rectangles");
  };
  smooth_extract_certify(result, options, stage, surface.input_positions, rectangles);
}

double surface_area(const TriMesh& mesh, const std::vector<Vec3d>& positions) {
  double area = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto fv = mesh.face_vertices(f);
    const Vec3d &p0 = positions[fv[0]], &p1 = positions[fv[1]], &p2 = positions[fv[2]];
    const Vec3d u{p1.x - p0.x, p1.y - p0.y, p1.z - p0.z}, v{p2.x - p0.x, p2.y - p0.y, p2.z - p0.z};
    const Vec3d n{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
    area += 0.5 * std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  }
  return area;
}

double target_quad_size(const PipelineOptions& options, double area) {
  if (options.resolution > 0) return 0;
  const double h = options.edge_length > 0
                       ? options.edge_length
                       : std::sqrt(area / static_cast<double>(options.quads > 0 ? options.quads : kDefaultQuads));
  return std::isfinite(h) ? h : 0;
}

FeatureEdges surface_features(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                              const std::vector<std::int64_t>& input_vertex, const PipelineOptions& options,
                              double quad_size, std::vector<std::uint8_t>& found) {
  FeatureOptions fo = options.features;
  if (!(fo.quad_size > 0)) fo.quad_size = quad_size;
  return detect_features(mesh, positions, input_feature_edges(mesh, input_vertex, options.feature_edges, found), fo);
}

FeatureQuality feature_quality(const std::vector<const FeatureEdges*>& features, const std::vector<int>& base,
                               const std::vector<Vec3d>& input_positions, const QuadMesh& quads) {
  std::vector<std::array<int, 2>> edges;
  int curves = 0, corners = 0, short_edges = 0;
  for (std::size_t i = 0; i < features.size(); ++i) {
    for (const FeatureCurve& c : features[i]->curves)
      for (std::size_t k = 0; k + 1 < c.vertices.size(); ++k) edges.push_back({c.vertices[k] + base[i], c.vertices[k + 1] + base[i]});
    curves += features[i]->stats.curves;
    corners += features[i]->stats.corners;
    short_edges += features[i]->stats.short_edges;
  }
  FeatureQuality q = measure_features(input_positions, edges, quads.positions, quads.quads);
  q.curves = curves;
  q.corners = corners;
  q.short_edges = short_edges;
  return q;
}

PipelineResult compute_igm(const ValidMesh& input, const PipelineOptions& options) {
  PipelineResult result;
  std::vector<std::uint8_t> found;
  FeatureEdges features = surface_features(input.mesh, input.positions, input.input_vertex, options,
                                           target_quad_size(options, surface_area(input.mesh, input.positions)), found);
  check_feature_edges_found(options.feature_edges, found);
  with_threads(options.threads, [&] {
    result = compute_igm_closed(input, options, &features);
    if (options.quality) result.feature_quality = feature_quality({&features}, {0}, input.positions, result.quads);
  });
  result.features = std::move(features);
  return result;
}

PipelineResult compute_igm_closed(const ValidMesh& input, const PipelineOptions& options, const FeatureEdges* features) {
  check_sizes(options);
  if (options.layout == LayoutKind::Field) {
    PipelineOptions topological = options;
    topological.layout = LayoutKind::Spread;
    // Cones or the normal form are requests for the topological layout (the field chooses its cones).
    if (!options.cones.empty() || options.normal_form) return compute_igm_closed(input, topological, features);
    std::vector<std::array<int, 3>> triangles(input.mesh.num_faces());
    for (int f = 0; f < input.mesh.num_faces(); ++f) triangles[f] = input.mesh.face_vertices(f);
    FieldSurface surface{&input.mesh, &input.positions, &triangles, input.genus, 0, features};
    PipelineStats attempt;
    if (std::optional<PipelineResult> r = compute_igm_field(surface, options, attempt)) return std::move(*r);
    return with_fallback(std::move(attempt), compute_igm_closed(input, topological));
  }
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

  // --- the disk's map, its quads, their certificates ---
  CutDisk disk;
  disk.surface = std::move(cut.surface);
  disk.disk_triangles = std::move(cut.disk_triangles);
  disk.disk_to_surface = std::move(cut.disk_to_surface);
  disk.boundary = std::move(cut.boundary);
  for (BoundarySide& side : cut.sides) disk.sides.push_back({std::move(side.disk_vertices), side.mate});
  map_disk(result, disk, options, stage, input.positions);
  measure_quality(result, input, options, stage);
  return result;
}

}  // namespace igm
