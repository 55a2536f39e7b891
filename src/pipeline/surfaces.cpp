#include <algorithm>
#include <cmath>
#include <string>

#include "igm/core/error.h"
#include "igm/core/threads.h"
#include "igm/mesh/scale.h"
#include "igm/pipeline/pipeline.h"
#include "pipeline_internal.h"

namespace igm {

PipelineResult compute_igm(const SurfaceComponent& surface, const PipelineOptions& options) {
  return compute_igm_surface(surface, options, nullptr);
}

PipelineResult compute_igm_surface(const SurfaceComponent& surface, const PipelineOptions& options,
                                   const FeatureEdges* features) {
  PipelineResult result;
  with_threads(options.threads, [&] {
    if (surface.boundary_loops.empty()) {
      // The surface's own mesh (to_valid_mesh keeps the vertex and face order): the features' ids hold.
      result = compute_igm_closed(to_valid_mesh(surface), options, features);
      return;
    }
    check_sizes(options);
    result = compute_igm_open(surface, options, features);  // open_pipeline.cpp
  });
  return result;
}

SurfacesResult compute_igms(const SurfaceSet& set, const PipelineOptions& options) {
  SurfacesResult result;
  with_threads(options.threads, [&] { result = compute_igms_here(set, options); });
  return result;
}

SurfacesResult compute_igms_here(const SurfaceSet& set, const PipelineOptions& options) {
  if (set.components.empty()) throw Error(ErrorKind::Empty, "compute_igms: no surface");
  SurfacesResult out;
  int loops = 0;
  std::vector<certify::ComponentTopology> expected;  // per component (genus, loops)
  // A quad count (given or the default) is shared among the surfaces by their 3D area.
  std::vector<double> area(set.components.size(), 0.0);
  double total_area = 0;
  for (std::size_t c = 0; c < set.components.size(); ++c) {
    const SurfaceComponent& comp = set.components[c];
    const double s = unit_scale(comp.positions);
    for (const auto& t : comp.triangles) {
      const Vec3d &a = comp.positions[t[0]], &b = comp.positions[t[1]], &d = comp.positions[t[2]];
      const double ux = s * b.x - s * a.x, uy = s * b.y - s * a.y, uz = s * b.z - s * a.z;
      const double vx = s * d.x - s * a.x, vy = s * d.y - s * a.y, vz = s * d.z - s * a.z;
      const double cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
      area[c] += 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz) / (s * s);
    }
    if (std::isfinite(area[c])) total_area += area[c];
  }
  // The features of every surface, first (a user's pair on no surface is an error before any work).
  std::vector<FeatureEdges> features;
  {
    std::vector<std::uint8_t> found;
    for (const SurfaceComponent& comp : set.components) {
      const TriMesh mesh = TriMesh::from_triangles(static_cast<int>(comp.positions.size()), comp.triangles, true);
      features.push_back(
          surface_features(mesh, comp.positions, comp.input_vertex, options, target_quad_size(options, total_area), found));
    }
    check_feature_edges_found(options.feature_edges, found);
  }
  const bool share_quads = options.resolution <= 0 && options.edge_length <= 0;
  const std::int64_t quads = options.quads > 0 ? options.quads : kDefaultQuads;
  if (share_quads) out.quads_asked = quads;
  for (std::size_t c = 0; c < set.components.size(); ++c) {
    const SurfaceComponent& comp = set.components[c];
    PipelineOptions o = options;
    if (share_quads && set.components.size() > 1) {
      const double share = total_area > 0 && std::isfinite(area[c]) ? area[c] / total_area : 1.0 / set.components.size();
      o.quads = std::max<std::int64_t>(1, std::llround(share * static_cast<double>(quads)));
    }
    if (options.progress && set.components.size() > 1)
      o.progress = [&, c](const StageEvent& e) {
        StageEvent tagged = e;
        tagged.detail = "surface " + std::to_string(c) + ": " + e.detail;
        options.progress(tagged);
      };
    out.components.push_back(compute_igm_surface(comp, o, &features[c]));
    out.components.back().features = std::move(features[c]);
    const PipelineResult& r = out.components.back();
    // Merge: the IGM (vertex ids and the locations' input ids offset), the quads.
    const int v0 = static_cast<int>(out.igm.positions.size());
    const int in0 = static_cast<int>(out.input_positions.size());
    for (const Vec3d& p : r.igm.positions) out.igm.positions.push_back(p);
    for (const auto& t : r.igm.triangles) out.igm.triangles.push_back({t[0] + v0, t[1] + v0, t[2] + v0});
    for (const auto& uv : r.igm.corner_uv) out.igm.corner_uv.push_back(uv);
    auto shifted = [&](SurfacePoint p) {
      for (int& v : p.v)
        if (v >= 0) v += in0;
      return p;
    };
    for (const SurfacePoint& p : r.igm.locations) out.igm.locations.push_back(shifted(p));
    const int q0 = static_cast<int>(out.quads.positions.size());
    for (const Vec3d& p : r.quads.positions) out.quads.positions.push_back(p);
    for (const SurfacePoint& p : r.quads.locations) out.quads.locations.push_back(shifted(p));
    for (const auto& q : r.quads.quads) out.quads.quads.push_back({q[0] + q0, q[1] + q0, q[2] + q0, q[3] + q0});
    for (const Vec3d& p : comp.positions) out.input_positions.push_back(p);
    out.quads_total += r.stats.quads;
    loops += static_cast<int>(comp.boundary_loops.size());
    expected.push_back({comp.genus, static_cast<std::int64_t>(comp.boundary_loops.size())});
  }
  certify::Options copt;
  copt.max_witnesses = options.max_witnesses;
  copt.allow_boundary = loops > 0;
  copt.allow_components = true;
  copt.threads = resolve_threads(options.threads);
  out.igm_report = certify::certify_igm(certify_input(out.igm, out.igm.corner_uv), copt);
  certify::QuadInput qin;
  qin.quads = out.quads.quads;
  qin.num_vertices = static_cast<std::int64_t>(out.quads.positions.size());
  copt.expected_boundary_loops = loops;
  copt.expected_components = expected;
  out.quad_report = certify::certify_quads(qin, copt);
  if (options.quality) {
    std::vector<std::array<Vec2d, 3>> uv(out.igm.corner_uv.size());
    for (std::size_t t = 0; t < uv.size(); ++t)
      for (int i = 0; i < 3; ++i) uv[t][i] = {approximate(out.igm.corner_uv[t][i].x), approximate(out.igm.corner_uv[t][i].y)};
    out.igm_quality = measure_igm(out.igm.positions, out.igm.triangles, uv);
    std::vector<std::array<int, 3>> input_triangles;
    int base = 0;
    for (const SurfaceComponent& comp : set.components) {
      for (const auto& t : comp.triangles) input_triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
      base += static_cast<int>(comp.positions.size());
    }
    QuadQualityOptions qo;
    qo.distance = options.quality_distance;
    out.quad_quality = measure_quads(out.quads.positions, out.quads.quads, out.input_positions, input_triangles, qo);
    std::vector<const FeatureEdges*> each;
    std::vector<int> bases;
    base = 0;
    for (std::size_t c = 0; c < set.components.size(); ++c) {
      each.push_back(&out.components[c].features);
      bases.push_back(base);
      base += static_cast<int>(set.components[c].positions.size());
    }
    out.feature_quality = feature_quality(each, bases, out.input_positions, out.quads);
  }
  return out;
}

}  // namespace igm
