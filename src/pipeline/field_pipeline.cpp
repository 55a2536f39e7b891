// The field-driven layout through the common back end (pipeline.h, LayoutKind::Field): cross field,
// traced layout, quantization, per-patch maps, then smoothing, extraction and the certifier as for
// every layout. Any stage that cannot finish returns nothing and says why; the caller falls back.
#include <algorithm>
#include <chrono>
#include <cmath>
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

  // The quad size the sizing aims at (for the tracing's snapping): from the area and the quad
  // count, or the edge length; 0 with a resolution (then the tracing's own default).
  double quad_size = 0;
  {
    double area = 0;
    for (const auto& t : *input.triangles) {
      const Vec3d &p0 = positions[t[0]], &p1 = positions[t[1]], &p2 = positions[t[2]];
      const Vec3d u{p1.x - p0.x, p1.y - p0.y, p1.z - p0.z}, v{p2.x - p0.x, p2.y - p0.y, p2.z - p0.z};
      const Vec3d n{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
      area += 0.5 * std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    }
    if (options.resolution <= 0) {
      if (options.edge_length > 0) quad_size = options.edge_length;
      else quad_size = std::sqrt(area / static_cast<double>(options.quads > 0 ? options.quads : kDefaultQuads));
    }
    if (!std::isfinite(quad_size)) quad_size = 0;
  }

  // --- field and trace, for each attempt's curvature alignment until a layout is built ---
  // The attempts: the options' own, then field_attempts (the same field computed once).
  struct Attempt {
    CrossFieldOptions field;
    double snap;  // in quad sizes; <= 0: the trace options' own snap length
  };
  std::vector<Attempt> attempts{{options.field, options.field_layout.trace.snap_length > 0 ? 0.0 : 0.5}};
  for (const PipelineOptions::FieldAttempt& a : options.field_attempts) {
    CrossFieldOptions fo = options.field;
    fo.alignment = a.alignment;
    fo.remove_close_pairs = a.cleanup;
    attempts.push_back({fo, a.snap});
  }
  std::vector<std::pair<CrossFieldOptions, CrossField>> fields;  // computed so far
  FieldLayoutResult traced;
  std::string first_failure;
  for (std::size_t k = 0; k < attempts.size(); ++k) {
    const std::string attempt_name = attempts.size() > 1 ? " (attempt " + std::to_string(k + 1) + ")" : "";
    auto t0 = Clock::now();
    const CrossFieldOptions& fo = attempts[k].field;
    const CrossField* known = nullptr;
    for (const auto& [o, f] : fields)
      if (o.alignment == fo.alignment && o.remove_close_pairs == fo.remove_close_pairs) known = &f;
    if (!known) {
      try {
        fields.emplace_back(fo, compute_cross_field(*input.mesh, positions, fo));
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::Internal) throw;
        if (first_failure.empty()) first_failure = std::string("field: ") + e.what();
        continue;
      }
      known = &fields.back().second;
    }
    const CrossField& field = *known;
    stats.cross_field = field.stats;
    // A cone of valence 1 (a quarter turn of angle) gives a valid IGM but no quad mesh: a quad
    // would close on itself around it.
    int bad_cone = -1;
    for (const Cone& cone : field.cones)
      if (cone.valence <= 1) bad_cone = cone.vertex;
    if (bad_cone >= 0) {
      stage.done("field", t0, "a cone of valence 1 at vertex " + std::to_string(bad_cone) + attempt_name);
      if (first_failure.empty()) first_failure = "field: a cone of valence 1 at vertex " + std::to_string(bad_cone);
      continue;
    }
    stage.done("field", t0,
               std::to_string(field.cones.size()) + " cones (" + cones_summary(field.stats) + "), alignment " +
                   std::to_string(static_cast<int>(fo.alignment)) + (fo.remove_close_pairs ? "" : ", close pairs kept") +
                   attempt_name);
    t0 = Clock::now();
    std::vector<Vec3d> direction(input.mesh->num_faces());
    for (int f = 0; f < input.mesh->num_faces(); ++f) direction[f] = field_direction(field, f, 0);
    FieldLayoutOptions lo = options.field_layout;
    if (attempts[k].snap > 0 && quad_size > 0) lo.trace.snap_length = attempts[k].snap * quad_size;
    try {
      traced = build_field_layout(*input.mesh, positions, direction, lo);
    } catch (const std::exception& e) {
      // A broken invariant of the tracing is a bug; the surface still gets a certified output.
      traced = FieldLayoutResult{};
      traced.failure = std::string("internal error: ") + e.what();
    }
    stats.field_layout = traced.stats;
    stage.done("trace", t0,
               traced.ok ? std::to_string(traced.stats.trace.curves) + " curves, " + std::to_string(traced.stats.patches) +
                               " patches, " + std::to_string(traced.stats.t_junctions) + " T-junctions, " +
                               std::to_string(traced.stats.rounds) + " rounds"
                         : "no layout: " + traced.failure);
    if (traced.ok) break;
    if (first_failure.empty()) first_failure = "trace: " + traced.failure;
  }
  if (!traced.ok) return fail(first_failure);
  stats.refined_vertices = traced.stats.refined_vertices;
  stats.refined_faces = traced.stats.refined_triangles;
  stats.layout_quads = traced.stats.patches;

  // --- quantize: integer arc lengths ---
  auto t0 = Clock::now();
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
