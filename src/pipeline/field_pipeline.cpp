// The field-driven layout through the common back end (pipeline.h, LayoutKind::Field): cross field,
// traced layout, quantization, per-patch maps, then smoothing, extraction and the certifier as for
// every layout. Any stage that cannot finish returns nothing and says why; the caller falls back.
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include "igm/core/error.h"
#include "igm/igm/layout_map.h"
#include "igm/mesh/scale.h"
#include "pipeline_internal.h"

namespace igm {

namespace {

using Clock = StageReporter::Clock;

std::string cones_summary(const CrossFieldStats& s) {
  std::string out;
  for (int v = 0; v < 9; ++v) {
    if (v == 4 || s.valence_count[v] == 0) continue;
    if (!out.empty()) out += ", ";
    out += std::to_string(s.valence_count[v]) + " of valence " + std::to_string(v);
  }
  return out.empty() ? "no cones" : out;
}

}  // namespace

std::optional<PipelineResult> compute_igm_field(const FieldSurface& input, const PipelineOptions& options,
                                                PipelineStats& attempt) {
  PipelineResult result;
  PipelineStats& stats = result.stats;
  PipelineOptions opts = options;
  opts.structured_extraction = false;  // the field layout's quads come from the isolines
  // The attempt's stages are reported as they happen and kept for the caller (a fallback keeps
  // them too, so the time spent shows).
  StageReporter stage{stats, opts};
  stats.layout = "field";
  stats.genus = input.genus;
  stats.boundary_loops = input.boundary_loops;
  stats.input_vertices = input.mesh->num_vertices();
  stats.input_faces = input.mesh->num_faces();
  auto fail = [&](const std::string& reason) -> std::optional<PipelineResult> {
    stage.done("fallback", Clock::now(), reason + "; the topological layout instead");
    stats.layout_fallback = reason;
    attempt = std::move(stats);
    return std::nullopt;
  };
  const std::vector<Vec3d>& positions = *input.positions;

  // --- field: the smoothest cross field and its cones ---
  auto t0 = Clock::now();
  CrossField field;
  try {
    field = compute_cross_field(*input.mesh, positions, options.field);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Internal) throw;
    return fail(std::string("field: ") + e.what());
  }
  stats.cross_field = field.stats;
  stage.done("field", t0,
             std::to_string(field.cones.size()) + " cones (" + cones_summary(field.stats) + "), " +
                 std::to_string(field.stats.iterations) + " iterations");

  // --- trace: the separatrices, the patches ---
  t0 = Clock::now();
  std::vector<Vec3d> direction(input.mesh->num_faces());
  for (int f = 0; f < input.mesh->num_faces(); ++f) direction[f] = field_direction(field, f, 0);
  FieldLayoutResult traced;
  try {
    traced = build_field_layout(*input.mesh, positions, direction, options.field_layout);
  } catch (const std::exception& e) {
    // A broken invariant of the tracing is a bug; the surface still gets a certified output.
    return fail(std::string("trace: internal error: ") + e.what());
  }
  stats.field_layout = traced.stats;
  if (!traced.ok) return fail("trace: " + traced.failure);
  stats.refined_vertices = traced.stats.refined_vertices;
  stats.refined_faces = traced.stats.refined_triangles;
  stats.layout_quads = traced.stats.patches;
  stage.done("trace", t0,
             std::to_string(traced.stats.trace.curves) + " curves, " + std::to_string(traced.stats.patches) +
                 " patches, " + std::to_string(traced.stats.t_junctions) + " T-junctions, " +
                 std::to_string(traced.stats.rounds) + " rounds");

  // --- quantize: integer arc lengths ---
  t0 = Clock::now();
  const double scale = unit_scale(positions);
  QuantizeOptions qo;
  const SizingOptions sizing = sizing_options(options, scale);
  qo.resolution = sizing.resolution;
  qo.edge_length = sizing.edge_length;
  qo.quads = sizing.quads;
  qo.length_scale = scale;
  Quantization q;
  try {
    q = quantize_layout(traced.layout, qo);
  } catch (const std::exception& e) {
    return fail(std::string("quantize: internal error: ") + e.what());
  }
  stats.quantize = q.stats;
  if (q.status != QuantizeStatus::Optimal && q.status != QuantizeStatus::Feasible)
    return fail(std::string("quantize: ") + to_string(q.status) + (q.reason.empty() ? "" : ": " + q.reason));
  stats.edge_length = q.edge_length / scale;
  stats.chords = static_cast<int>(traced.layout.arcs.size());
  stage.done("quantize", t0,
             std::to_string(q.quads) + " quads, " + std::to_string(traced.layout.arcs.size()) + " arcs, " +
                 to_string(q.status));

  // --- igm: every patch onto its rectangle ---
  t0 = Clock::now();
  LayoutMapOptions mo;
  mo.weights = options.patch_weights;
  mo.length_scale = scale;
  mo.tutte = options.tutte;
  LayoutMap map;
  try {
    map = map_layout(std::move(traced.layout), q.arc_length, mo);
  } catch (const std::exception& e) {
    return fail(std::string("igm: internal error: ") + e.what());
  }
  stats.patch_maps = map.stats;
  stats.max_uv_bits = map.stats.max_uv_bits;
  result.igm = std::move(map.igm);
  stats.output_vertices = static_cast<int>(result.igm.positions.size());
  stats.output_triangles = static_cast<int>(result.igm.triangles.size());
  {
    char line[160];
    std::snprintf(line, sizeof line, "%d triangles (%.2fx input), %d patches refined, UV bits max %zu",
                  stats.output_triangles, double(stats.output_triangles) / std::max(1, stats.input_faces),
                  map.stats.patches_refined, map.stats.max_uv_bits);
    stage.done("igm", t0, line);
  }

  // --- smooth, extract, certify: as for every layout ---
  smooth_extract_certify(result, opts, stage, positions, [] { return std::string("the integer isolines"); });
  if (!result.certified())
    return fail("certify: IGM " + certify::summary(result.igm_report) + "; quads " + certify::summary(result.quad_report));
  measure_quality(result, positions, *input.triangles, options, stage);
  return result;
}

PipelineResult with_fallback(PipelineStats attempt, PipelineResult result) {
  PipelineStats& s = result.stats;
  s.layout_fallback = std::move(attempt.layout_fallback);
  s.cross_field = attempt.cross_field;
  s.field_layout = std::move(attempt.field_layout);
  s.quantize = attempt.quantize;
  attempt.stages.insert(attempt.stages.end(), s.stages.begin(), s.stages.end());
  s.stages = std::move(attempt.stages);
  return result;
}

}  // namespace igm
