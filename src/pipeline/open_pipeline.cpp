#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "igm/core/error.h"
#include "igm/topology/open_cut.h"
#include "pipeline_internal.h"

namespace igm {

PipelineResult compute_igm_open(const SurfaceComponent& input, const PipelineOptions& options, const FeatureEdges* features) {
  if (!options.cones.empty())
    throw Error(ErrorKind::InvalidArgument, "cones: only a closed genus-0 mesh takes a cone list (this one has " +
                                                std::to_string(input.boundary_loops.size()) + " boundary loops)");
  if (options.layout == LayoutKind::Field) {
    const TriMesh mesh = TriMesh::from_triangles(static_cast<int>(input.positions.size()), input.triangles, true);
    FieldSurface surface{&mesh, &input.positions, &input.triangles, input.genus,
                         static_cast<int>(input.boundary_loops.size()), features};
    PipelineStats attempt;
    if (std::optional<PipelineResult> r = compute_igm_field(surface, options, attempt)) return std::move(*r);
    PipelineOptions topological = options;
    topological.layout = LayoutKind::Spread;
    return with_fallback(std::move(attempt), compute_igm_open(input, topological));
  }
  PipelineResult result;
  PipelineStats& stats = result.stats;
  StageReporter stage{stats, options};
  stats.genus = input.genus;
  stats.boundary_loops = static_cast<int>(input.boundary_loops.size());
  stats.input_vertices = static_cast<int>(input.positions.size());
  stats.input_faces = static_cast<int>(input.triangles.size());

  // --- topology: the loops (genus >= 1) and a leg to every hole, the disk with free sides ---
  const auto t0 = StageReporter::Clock::now();
  OpenCutOptions co;
  co.root = options.root;
  OpenCut cut = cut_open_surface(input, co);
  stats.refined_vertices = cut.stats.vertices_after;
  stats.refined_faces = cut.stats.faces_after;
  int free_sides = 0;
  for (const OpenSide& side : cut.sides) free_sides += side.mate < 0;
  char line[256];
  std::snprintf(line, sizeof line, "genus %d, %d boundary loops, %d legs, %zu sides (%d free), %d -> %d disk vertices",
                cut.genus, cut.boundary_loops, cut.stats.legs, cut.sides.size(), free_sides, stats.input_vertices,
                cut.stats.disk_vertices);
  stage.done("topology", t0, line);

  // --- the disk's map, its quads, their certificates (as for a closed surface) ---
  CutDisk disk;
  disk.surface = std::move(cut.surface);
  disk.disk_triangles = std::move(cut.disk_triangles);
  disk.disk_to_surface = std::move(cut.disk_to_surface);
  disk.boundary = std::move(cut.boundary);
  for (OpenSide& side : cut.sides) {
    disk.corner_label.push_back(disk.disk_to_surface[side.disk_vertices.front()]);
    disk.sides.push_back({std::move(side.disk_vertices), side.mate});
  }
  map_disk(result, disk, options, stage, input.positions);
  measure_quality(result, input.positions, input.triangles, options, stage);
  return result;
}

}  // namespace igm
