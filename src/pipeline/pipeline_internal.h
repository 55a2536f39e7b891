#pragma once
// Internal to the pipeline (pipeline.h): the genus-0 branch of compute_igm (sphere_pipeline.cpp)
// and the certification of a run's outputs shared by both branches (pipeline.cpp).
#include <array>
#include <chrono>
#include <functional>
#include <optional>
#include <cstddef>
#include <string>
#include <vector>

#include "igm/mesh/surface_point.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/topology/cut_to_canonical_disk.h"
#include "igm/pipeline/pipeline.h"

namespace igm {

/// Reports the pipeline's stages (both branches): done() appends a StageEvent to stats.stages and
/// passes it to options.progress if set. The library itself never prints.
struct StageReporter {
  using Clock = std::chrono::steady_clock;
  PipelineStats& stats;
  const PipelineOptions& options;
  double cpu = 0;  // process CPU seconds at the end of the last stage
  /// Starts the memory measurement of the first stage (options.measure_stage_memory).
  StageReporter(PipelineStats& s, const PipelineOptions& o);
  /// The stage `name` ran from t0 until now (with its peak memory when measured; the next stage's
  /// measurement starts here).
  void done(const char* name, Clock::time_point t0, std::string detail);
};

/// The sum of the faces' 3D areas (doubles, faces in order). O(F).
double surface_area(const TriMesh& mesh, const std::vector<Vec3d>& positions);

/// The quad edge length the sizing aims at (the field layout's snapping, the features' resolution
/// rule): 0 with a resolution; the edge length if given; else sqrt(area / Q), Q = options.quads
/// or kDefaultQuads, `area` the 3D area the quads cover (all surfaces: a shared quad count gives
/// each surface the same H); 0 if that is not finite.
double target_quad_size(const PipelineOptions& options, double area);

/// The features of one input surface (PipelineOptions::features, its quad_size if set or else
/// `quad_size`, and the user's pairs that are edges of this surface, marked in `found`).
FeatureEdges surface_features(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                              const std::vector<std::int64_t>& input_vertex, const PipelineOptions& options,
                              double quad_size, std::vector<std::uint8_t>& found);

/// measure_features of the curves of features[i] (vertex ids into input_positions offset by
/// base[i]) against `quads`, with the curve and corner counts.
FeatureQuality feature_quality(const std::vector<const FeatureEdges*>& features, const std::vector<int>& base,
                               const std::vector<Vec3d>& input_positions, const QuadMesh& quads);

/// Throws igm::Error(InvalidArgument) for a resolution, edge length or quad count out of range.
void check_sizes(const PipelineOptions& options);

/// The sizing that the options ask for (PipelineOptions: resolution, else edge length, else the quad
/// count, else kDefaultQuads), for lengths measured on positions multiplied by `scale`.
SizingOptions sizing_options(const PipelineOptions& options, double scale);

/// A side of the topology stage's disk: its vertices from the corner where it starts to the next
/// one (counter-clockwise), and the side it is glued to (reversed), or -1 for a free side (a piece
/// of the surface's boundary).
struct DiskSide {
  std::vector<int> disk_vertices;
  int mate = -1;
};

/// The topology stage's disk, of a closed surface (topology/cut_to_canonical_disk.h) or an open one:
/// disk triangle f is surface face f; the sides cover `boundary` in order from its first vertex.
struct CutDisk {
  RefinedSurface surface;
  std::vector<std::array<int, 3>> disk_triangles;
  std::vector<int> disk_to_surface;
  std::vector<int> boundary;
  std::vector<DiskSide> sides;
  std::vector<int> corner_label;  // per corner: equal labels are one vertex (empty: all the root)
};

/// The stages after the cut, shared by closed surfaces of genus >= 1 and open ones: embed (the
/// disk on a convex polygon with one corner per side), arrange (the layout overlaid), igm (patches,
/// sizing, per-patch maps), then smooth_extract_certify. Fills result.igm, quads, reports, schema
/// and stats (layout, sizing, maps). Moves the surface's data out of `cut`.
void map_disk(PipelineResult& result, CutDisk& cut, const PipelineOptions& options, StageReporter& stage,
              const std::vector<Vec3d>& input_positions);

/// A surface as the field layout takes it: its mesh (with boundary half-edges where it is open),
/// positions and triangles (the same as the mesh's faces), genus and boundary loops.
struct FieldSurface {
  const TriMesh* mesh = nullptr;
  const std::vector<Vec3d>* positions = nullptr;
  const std::vector<std::array<int, 3>>* triangles = nullptr;
  int genus = 0, boundary_loops = 0;
  /// The surface's features (features/feature_edges.h, on `mesh`'s vertex ids) or none: the field
  /// layout follows them (docs/field.md, section 8).
  const FeatureEdges* features = nullptr;
};

/// The edges of `igm` that lie on the input edges flagged in `constrained` (one flag per half-edge
/// of the input mesh, the IGM's input vertices first): both ends' exact locations on one flagged
/// input edge. The field layout's walls map them onto integer isolines; smoothing holds them
/// there. O(F) plus O(1) per edge.
std::vector<std::pair<int, int>> igm_edges_on(const TriMesh& input, const std::vector<char>& constrained, const IgmMesh& igm);

/// Feature edges for the field layout (issue 45): the cross field's constraint flags (per
/// half-edge, both halves of each interior feature edge; empty when none) and the walls to trace
/// (the feature curves, split where they run along the boundary, which is on isolines anyway;
/// field/motorcycle.h). `features` may be null. O(H).
struct FieldFeatures {
  std::vector<char> constrained;
  std::vector<std::vector<int>> walls;
};
FieldFeatures field_features(const TriMesh& mesh, const FeatureEdges* features);

/// The field layout's IGM of a surface (field_pipeline.cpp): field, trace, quantize, igm, then
/// smooth_extract_certify and the quality. Nothing where a stage cannot finish or the certifier
/// rejects the output: then `attempt` holds the attempt's statistics (its stages, the field's, the
/// layout's) and attempt.layout_fallback "stage: reason". Options range-checked by the caller.
std::optional<PipelineResult> compute_igm_field(const FieldSurface& input, const PipelineOptions& options,
                                                PipelineStats& attempt);

/// `result` (of a topological layout) after a failed field attempt: the attempt's stages first,
/// its field statistics and its layout_fallback kept.
PipelineResult with_fallback(PipelineStats attempt, PipelineResult result);

/// compute_igm in the caller's thread arena (compute_igm sets it up from options.threads).
PipelineResult compute_igm_closed(const ValidMesh& input, const PipelineOptions& options,
                                  const FeatureEdges* features = nullptr);

/// compute_igms in the caller's thread arena.
SurfacesResult compute_igms_here(const SurfaceSet& set, const PipelineOptions& options);

/// compute_igm for input.genus == 0 (options already range-checked by compute_igm).
PipelineResult compute_igm_sphere(const ValidMesh& input, const PipelineOptions& options);

/// With options.quality, measures result.igm and result.quads against the input (quality.h) and
/// reports a "quality" stage.
void measure_quality(PipelineResult& result, const ValidMesh& input, const PipelineOptions& options,
                     StageReporter& stage);
/// The same against an input given by its positions and triangles.
void measure_quality(PipelineResult& result, const std::vector<Vec3d>& input_positions,
                     const std::vector<std::array<int, 3>>& input_triangles, const PipelineOptions& options,
                     StageReporter& stage);

/// compute_igm for an open surface (boundary loops; open_pipeline.cpp). Options range-checked.
PipelineResult compute_igm_open(const SurfaceComponent& input, const PipelineOptions& options,
                                const FeatureEdges* features = nullptr);

/// compute_igm of one surface whose features (or none) are known: the field layout follows them.
PipelineResult compute_igm_surface(const SurfaceComponent& surface, const PipelineOptions& options,
                                   const FeatureEdges* features);

/// The stages after the map, shared by both branches: with options.smooth, "smooth" (smooth_igm on
/// result.igm, its UVs replaced by the smoothed ones) then "extract" by the integer isolines
/// (extract/isolines.h, whose certifier report becomes result.igm_report); without it, the map put
/// on a double grid where that keeps it valid (round_to_dyadic), then "extract" by `structured`,
/// which fills result.quads from the map's own structure (the layout's rectangles, the
/// pillowcase's cells; an empty function: by the isolines), and the certifier on the IGM. Then the certifier on the quads ("certify").
void smooth_extract_certify(PipelineResult& result, const PipelineOptions& options, StageReporter& stage,
                            const std::vector<Vec3d>& input_positions, const std::function<std::string()>& structured,
                            const std::vector<std::pair<int, int>>& isoline_edges = {});

/// Runs the independent certifier on result.igm (checks 1-4; not when `igm_report_done`: the
/// extraction by isolines ran it) and result.quads (check 5, expected genus result.stats.genus and,
/// for an open surface, its boundary loops) and stores the reports in `result`.
void certify_outputs(PipelineResult& result, const PipelineOptions& options, bool igm_report_done = false);

/// The first output locations (IgmMesh::locations): the input vertices as weight-1 points, then the
/// surface's constructed points, moved out of `surface` (surface.constructed is left empty), with
/// room reserved for `more` further points. O(n).
std::vector<SurfacePoint> take_locations(RefinedSurface& surface, std::size_t more = 0);

/// Appends to `quads` the vertex with barycentric weights `w` in output triangle `triangle` of
/// `igm`: its exact location (from igm.locations) and its 3D position (evaluate()). O(1) GMP
/// operations.
void add_quad_vertex(QuadMesh& quads, const IgmMesh& igm, int triangle, const std::array<Rational, 3>& w,
                     const std::vector<Vec3d>& input_positions);

}  // namespace igm
