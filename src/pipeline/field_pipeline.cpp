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

FieldFeatures field_features(const TriMesh& mesh, const FeatureEdges* features) {
  FieldFeatures out;
  if (!features || features->edges.empty()) return out;
  const int nh = mesh.num_halfedges();
  if (static_cast<int>(features->halfedge.size()) != nh)
    throw Error(ErrorKind::Internal, "field layout: the features do not match the surface");
  out.constrained.assign(nh, 0);
  for (const FeatureCurve& c : features->curves) {
    std::vector<int> wall;
    auto flush = [&] {
      if (wall.size() >= 2) out.walls.push_back(std::move(wall));
      wall.clear();
    };
    for (std::size_t i = 0; i < c.halfedges.size(); ++i) {
      const int h = c.halfedges[i], t = mesh.twin(h);
      if (t < 0 || (!features->follow.empty() && !features->follow[h])) {  // boundary, or too short: no wall
        flush();
        continue;
      }
      out.constrained[h] = out.constrained[t] = 1;
      if (wall.empty()) wall.push_back(c.vertices[i]);
      wall.push_back(c.vertices[i + 1]);
    }
    flush();
  }
  return out;
}

std::vector<std::pair<int, int>> igm_edges_on(const TriMesh& input, const std::vector<char>& constrained, const IgmMesh& igm) {
  std::vector<std::pair<int, int>> out;
  if (constrained.empty()) return out;
  // The input edge (i < j) a location lies on, as the pair of its used vertices (-1 for a point
  // inside a face); a vertex gives (v, -1).
  auto support = [&](int x) {
    const SurfacePoint& p = igm.locations[x];
    return std::array<int, 3>{p.v[0], p.v[1], p.v[2]};
  };
  for (std::size_t t = 0; t < igm.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int a = igm.triangles[t][i], b = igm.triangles[t][(i + 1) % 3];
      if (a > b) continue;  // each interior edge once (from the triangle where it runs up)
      const std::array<int, 3> sa = support(a), sb = support(b);
      if (sa[2] >= 0 || sb[2] >= 0) continue;  // inside a face
      int u = -1, w = -1;  // the union of the two supports, at most two vertices
      bool fits = true;
      for (const int v : {sa[0], sa[1], sb[0], sb[1]}) {
        if (v < 0 || v == u || v == w) continue;
        if (u < 0) u = v;
        else if (w < 0) w = v;
        else fits = false;
      }
      if (!fits || u < 0 || w < 0) continue;
      const int h = input.find_halfedge(u, w);
      if (h >= 0 && constrained[h]) out.push_back({a, b});
    }
  return out;
}

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
  FieldFeatures features = field_features(*input.mesh, input.features);

  // The quad size the sizing aims at (for the tracing's snapping); 0 with a resolution (then the
  // tracing's own default).
  const double quad_size = target_quad_size(options, surface_area(*input.mesh, positions));

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
  // Fields computed so far with the current features (each attempt's own with
  // features.constrained as its constraints; cleared whenever the features change).
  std::vector<std::pair<CrossFieldOptions, CrossField>> fields;
  FieldLayoutResult traced;
  std::string first_failure;
  std::vector<int> drop_walls;  // the walls run_attempts asks to leave out
  // The walls (ascending) with a vertex among `marked` input vertices, or with whole_edge an edge
  // whose two ends are both marked (the walls' chains are input vertices).
  auto walls_marked = [&](const std::vector<char>& marked, bool whole_edge) {
    std::vector<int> out;
    for (std::size_t w = 0; w < features.walls.size(); ++w) {
      const std::vector<int>& chain = features.walls[w];
      for (std::size_t i = 0; i < chain.size(); ++i)
        if (marked[chain[i]] && (!whole_edge || (i + 1 < chain.size() && marked[chain[i + 1]]))) {
          out.push_back(static_cast<int>(w));
          break;
        }
    }
    return out;
  };
  // The walls through one of `vertices` or a neighbour of one.
  auto walls_near = [&](const std::vector<int>& vertices) {
    std::vector<char> near(static_cast<std::size_t>(input.mesh->num_vertices()), 0);
    for (int v : vertices) {
      near[v] = 1;
      const int h0 = input.mesh->vertex_halfedge(v);
      int h = h0;
      for (int guard = 0; h >= 0 && guard <= input.mesh->num_halfedges(); ++guard) {  // bound: v's fan
        near[input.mesh->target(h)] = 1;
        h = input.mesh->next_around_origin(h);
        if (h == h0) break;
      }
    }
    return walls_marked(near, false);
  };
  // Every attempt in order until one gives a layout; true when `may_drop` and it stopped at walls
  // that could not be drawn, at a cone of valence <= 2 next to walls (the walls force it: the
  // attempts' alignments do not move it), at a patch corner of a wrong angle next to walls, or at
  // contradicting side lengths along walls; drop_walls then lists those walls (the caller leaves
  // them out and calls again).
  auto field_cache = std::make_unique<CrossFieldCache>();  // the field system's analysis, kept over the rounds and attempts
  auto run_attempts = [&](bool may_drop) {
    drop_walls.clear();
    // With walls, the attempts after the first cost F each: as many as field_wall_work allows.
    std::size_t with_walls = attempts.size();
    if (!features.walls.empty() && options.field_wall_work > 0)
      with_walls = static_cast<std::size_t>(std::clamp<std::int64_t>(
          options.field_wall_work / std::max(1, input.mesh->num_faces()), 1, static_cast<std::int64_t>(attempts.size())));
    for (std::size_t k = 0; k < with_walls; ++k) {
      const std::string attempt_name = attempts.size() > 1 ? " (attempt " + std::to_string(k + 1) + ")" : "";
      auto t0 = Clock::now();
      CrossFieldOptions fo = attempts[k].field;
      fo.constrained_edges = features.constrained;
      const CrossField* known = nullptr;
      for (const auto& [o, f] : fields)
        if (o.alignment == fo.alignment && o.remove_close_pairs == fo.remove_close_pairs) known = &f;
      if (!known) {
        try {
          fields.emplace_back(fo, compute_cross_field(*input.mesh, positions, fo, field_cache.get()));
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
      // would close on itself around it. With feature walls, a cone of valence 2 (which the
      // constraints kept from being split) is refused too: the walls are then left out rather
      // than bought with a valence-2 vertex.
      int bad_valence = 0;  // the last such cone's, the one named
      std::vector<int> bad_cones;
      const int lowest = features.constrained.empty() ? 1 : 2;
      for (const Cone& cone : field.cones)
        if (cone.valence <= lowest) bad_valence = cone.valence, bad_cones.push_back(cone.vertex);
      if (!bad_cones.empty()) {
        const std::string what = "a cone of valence " + std::to_string(std::max(bad_valence, 1)) + " at vertex " +
                                 std::to_string(bad_cones.back()) + (bad_valence == 2 ? " (with the feature walls)" : "") +
                                 (bad_cones.size() > 1 ? " and " + std::to_string(bad_cones.size() - 1) + " more" : "");
        if (may_drop && !features.walls.empty()) {
          // The walls next to every such cone at once (one round, not one a cone).
          drop_walls = walls_near(bad_cones);
          if (!drop_walls.empty()) {
            stage.done("field", t0, what + ": its " + std::to_string(drop_walls.size()) +
                                        " feature walls left out, the field again" + attempt_name);
            return true;
          }
        }
        stage.done("field", t0, what + attempt_name);
        if (first_failure.empty()) first_failure = "field: " + what;
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
      lo.trace.walls = features.walls;
      // Where walls that cannot be drawn are left out (may_drop), nothing after them is needed.
      lo.trace.stop_at_stuck_wall = may_drop;
      if (attempts[k].snap > 0 && quad_size > 0) lo.trace.snap_length = attempts[k].snap * quad_size;
      try {
        traced = build_field_layout(*input.mesh, positions, direction, lo);
      } catch (const std::exception& e) {
        // A broken invariant of the tracing is a bug; the surface still gets a certified output.
        traced = FieldLayoutResult{};
        traced.failure = std::string("internal error: ") + e.what();
      }
      stats.field_layout = traced.stats;
      // A wall not drawn whole leaves its feature off the arcs (the layout may still close without it).
      if (!traced.graph.stuck_walls.empty()) {
        if (may_drop) {
          stage.done("trace", t0, std::to_string(traced.graph.stuck_walls.size()) +
                                      " feature walls could not be drawn: left out, the field again" + attempt_name);
          drop_walls = traced.graph.stuck_walls;
          return true;
        }
        traced.ok = false;
        traced.failure = std::to_string(traced.graph.stuck_walls.size()) + " feature walls could not be drawn (wall " +
                         std::to_string(traced.graph.stuck_walls.front()) + ")";
      }
      // A patch corner of a wrong angle (three quarter turns: a concave corner) next to walls:
      // those walls are left out and the field computed again.
      if (!traced.ok && may_drop && !features.walls.empty() && !traced.bad_angle_vertices.empty()) {
        drop_walls = walls_near(traced.bad_angle_vertices);
        if (!drop_walls.empty()) {
          stage.done("trace", t0, "no layout: " + traced.failure + ": " + std::to_string(drop_walls.size()) +
                                      " feature walls next to it left out, the field again" + attempt_name);
          return true;
        }
      }
      // Contradicting side lengths with walls on the contradicting patches' sides: those walls are
      // left out and the field computed again (the other attempts' alignments hardly move walls).
      if (!traced.ok && may_drop && !traced.contradicting_vertices.empty()) {
        std::vector<char> on(static_cast<std::size_t>(input.mesh->num_vertices()), 0);
        for (int v : traced.contradicting_vertices) on[v] = 1;
        drop_walls = walls_marked(on, true);
        if (!drop_walls.empty()) {
          stage.done("trace", t0, "no layout: " + traced.failure + ": " + std::to_string(drop_walls.size()) +
                                      " feature walls on their sides left out, the field again" + attempt_name);
          return true;
        }
      }
      stage.done("trace", t0,
                 traced.ok ? std::to_string(traced.stats.trace.curves) + " curves, " + std::to_string(traced.stats.patches) +
                                 " patches, " + std::to_string(traced.stats.t_junctions) + " T-junctions, " +
                                 (traced.stats.pattern_patches > 0
                                      ? std::to_string(traced.stats.pattern_patches) + " with 3, 5 or 6 corners filled by a pattern, "
                                      : std::string()) +
                                 (traced.stats.reflex_cuts > 0
                                      ? std::to_string(traced.stats.reflex_cuts) + " with a reflex corner cut, "
                                      : std::string()) +
                                 std::to_string(traced.stats.rounds) + " rounds" +
                                 (features.walls.empty() ? std::string()
                                                         : ", " + std::to_string(features.walls.size()) + " feature walls")
                           : "no layout: " + traced.failure);
      if (traced.ok) return false;
      if (first_failure.empty()) first_failure = "trace: " + traced.failure;
    }
    return false;
  };
  // Feature walls that cannot be drawn (their field rays taken: a sharp turn of a crease), and
  // those run_attempts blames (next to a cone of valence <= 2 or a corner of a wrong angle, on
  // contradicting patches' sides), are left out with their constraints and the field computed again, at most kFeatureRounds times
  // (each removes at least one wall); the rest of the walls then still hold. Where no attempt
  // gives a layout with the walls, every attempt is tried once more without any feature (the
  // features are then only measured): one more round, the last.
  constexpr int kFeatureRounds = 4;
  bool without_features = features.constrained.empty();
  for (int feature_round = 0; feature_round <= kFeatureRounds + 1; ++feature_round) {
    if (!run_attempts(feature_round < kFeatureRounds && !without_features)) {
      if (traced.ok || without_features) break;
      // No layout with the walls: all of them left out, every attempt again.
      stage.done("features", Clock::now(), "no field layout follows the " + std::to_string(features.walls.size()) +
                                               " feature walls: every attempt again without them");
      stats.features_dropped += static_cast<int>(features.walls.size());
      stats.features_failure = first_failure;
      features = FieldFeatures{};
      first_failure.clear();
      without_features = true;
    } else {
      // Leave out the walls run_attempts named and their constraints.
      std::vector<char> drop(features.walls.size(), 0);
      for (int w : drop_walls) drop[w] = 1;
      std::vector<std::vector<int>> kept;
      for (std::size_t w = 0; w < features.walls.size(); ++w) {
        if (!drop[w]) {
          kept.push_back(std::move(features.walls[w]));
          continue;
        }
        const std::vector<int>& chain = features.walls[w];
        for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
          const int h = input.mesh->find_halfedge(chain[i], chain[i + 1]);
          features.constrained[h] = features.constrained[input.mesh->twin(h)] = 0;
        }
        ++stats.features_dropped;
      }
      features.walls = std::move(kept);
    }
    fields.clear();  // the features changed: every field again
  }
  field_cache.reset();  // the fields are no longer needed: their memory back before the maps
  std::vector<std::pair<CrossFieldOptions, CrossField>>().swap(fields);
  if (!traced.ok) return fail(first_failure);
  stats.feature_walls = static_cast<int>(features.walls.size());
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
  const std::vector<std::pair<int, int>> held = igm_edges_on(*input.mesh, features.constrained, result.igm);
  try {
    smooth_extract_certify(result, opts, stage, positions, [] { return std::string("the integer isolines"); }, held);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::InvalidArgument) throw;
    return fail(std::string("smooth: internal error: ") + e.what());
  }
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
