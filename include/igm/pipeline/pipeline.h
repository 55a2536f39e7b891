#pragma once
// The whole pipeline on a validated mesh: topology -> embed -> arrange -> igm -> extract ->
// certify (design.md). Returns the IGM, the quad mesh and the certifier's reports on both.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "certify/certify.h"
#include "igm/embed/orbifold_tutte.h"
#include "igm/embed/tutte.h"
#include "igm/embed/weights.h"
#include "igm/features/feature_edges.h"
#include "igm/field/cross_field.h"
#include "igm/field/field_layout.h"
#include "igm/igm/patch_maps.h"
#include "igm/layout/quad_layout.h"
#include "igm/layout/quantize.h"
#include "igm/layout/sizing.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/output/igm_mesh.h"
#include "igm/output/schema_svg.h"
#include "igm/quality/quality.h"
#include "igm/smooth/smooth.h"
#include "igm/topology/cut_to_canonical_disk.h"

namespace igm {

/// Peak resident memory per IGM triangle of the genus >= 1 pipeline after its arrangement, as
/// measured by `igm run` (couplingdown with the normal form: 22k triangles, 51 MB; cheese: 423k
/// triangles, 875 MB; a generated 1M-face torus: 1.0M triangles, 2065 MB): the basis of
/// PipelineOptions::memory_limit_bytes.
inline constexpr double kBytesPerIgmTriangle = 2048;

/// Reported after each stage through PipelineOptions::progress (the library never prints).
struct StageEvent {
  std::string stage;   // "topology", "embed", "arrange", "igm", "extract", "certify"
  double seconds = 0;  // wall time of the stage
  std::string detail;  // one line of numbers for humans
  /// With PipelineOptions::measure_stage_memory: the process's peak resident memory during the
  /// stage in MB (igm/core/memory.h); -1 when not measured.
  double peak_mb = -1;
  /// CPU seconds of the whole process (every thread) during the stage (igm/core/memory.h).
  double cpu_seconds = 0;
};

/// The quad count aimed at when no size is given (PipelineOptions): what a user who asks for no
/// size gets, whatever the input's resolution (docs/layouts.md).
inline constexpr std::int64_t kDefaultQuads = 10000;

struct PipelineOptions {
  /// The size of the quads, by the first of these that is set (layout/sizing.h):
  ///  - resolution N > 0: every chord (layout edge) gets N quads, N x N per layout quad (the paper's
  ///    meaning). Genus 0: N per unit of the pillowcase, 2 N^2 quads.
  ///  - edge_length H > 0: each chord gets round(mean 3D length of its layout edges / H) quads;
  ///  - quads Q > 0: H is chosen so that the quad count is nearest to Q;
  ///  - none: quads = kDefaultQuads.
  /// Whatever they say, every surface gets at least the quads its layout needs for a manifold
  /// quad mesh (the floor, layout/sizing.h: every chord at least 3 where a layout edge is a loop,
  /// as the torus's square and the paper's sides, 2 for some of the kite's spokes, 1 otherwise;
  /// genus 0: the 1 x 1 grid or both counts >= 2); PipelineStats says when it raised the counts.
  int resolution = 0;
  double edge_length = 0;
  std::int64_t quads = 0;
  /// The quad layout. Field (the default): the field-driven layout (field/field_layout.h: cones
  /// from a cross field, separatrices traced into patches, integer quantization), on every surface
  /// (closed of any genus, open, each component); where a stage of it cannot finish (the field,
  /// the layout, the quantization, the map, or the certifier rejecting its output) the surface
  /// falls back to the topological layout (spread; genus 0: the orbifold) and
  /// PipelineStats::layout_fallback says which stage and why. `cones` or `normal_form` ask for the
  /// topological layout (the field chooses its own cones): with them a closed surface takes it
  /// directly. Paper, Kite, Spread: the layouts of the polygonal schema (genus >= 1 and open
  /// surfaces; layout/quad_layout.h; genus 0 takes the orbifold) and, for the spread layout, its
  /// inner grid's rows (0: automatic). root, normal_form, restarts, memory_limit_bytes,
  /// structured_extraction and layout_rows concern the topological layouts only (and a fallback).
  LayoutKind layout = LayoutKind::Field;
  int layout_rows = 0;
  double layout_ring_depth = 1;  // LayoutOptions::ring_depth
  /// How each layout quad is mapped onto its rectangle (igm/patch_maps.h), with which weights.
  PatchMapKind patch_map = PatchMapKind::Tutte;
  WeightKind patch_weights = WeightKind::MeanValue;
  /// The disk's embedding onto the polygon, which places the layout on the surface: its weights,
  /// and its boundary vertices at arc-length parameters along the sides (else uniformly).
  WeightKind disk_weights = WeightKind::MeanValue;
  bool disk_arc_length = true;
  int root = -1;       // root vertex of the loops (-1: deterministic default); genus 0 has no root (ignored)
  /// Bring the gluing word to the normal form a1 b1 a1^-1 b1^-1 ... (topology step 3).
  /// Validity does not need it: every polygon side is a whole edge of one layout quad mapped onto
  /// a unit-square edge, so any pairing of sides glues by R^k x + t with integer t (the certifier
  /// checks it). Off by default: its loops are longer and grow the mesh more (couplingdown g9:
  /// 2.37k instead of 2.19k refined vertices; a 1M-face g20 mesh 0.54M instead of 0.51M vertices,
  /// in ~9 s instead of ~3 s; cheese g133 ~150k instead of 27k, by the crosses construction).
  bool normal_form = false;
  /// With normal_form: CutOptions::restarts, the topology stage run again on this many copies of
  /// the mesh with shuffled vertex ids where it added more than 2 %, the fewest vertices kept
  /// (couplingdown with 15: 87 vertices added instead of 129, in 15x the time). 0: none; -1:
  /// automatic, clamp(5e6 / (F g^2), 0, 15) (`igm run --restarts auto`).
  int restarts = 0;
  /// Genus 0 only: the four cone vertices (input vertex ids) in path order A, B, C, D; empty: the
  /// deterministic default (topology/sphere_cut.h). Bad lists give igm::Error(InvalidArgument).
  std::vector<int> cones;
  /// The field layout's cross field and tracing (LayoutKind::Field). The layout is tried with
  /// `field` and field_layout first, then, where no layout can be built, with each of
  /// field_attempts in order (docs/field.md, "Attempts"), before falling back.
  CrossFieldOptions field;
  FieldLayoutOptions field_layout;
  struct FieldAttempt {
    double alignment = 0;   // CrossFieldOptions::alignment
    bool cleanup = true;    // CrossFieldOptions::remove_close_pairs
    double snap = 0.5;      // TraceOptions::snap_length in units of the quad size
  };
  /// Measured over the shared and generated meshes (bench/README.md): each one rescues layouts the
  /// others miss. Empty: one attempt only.
  std::vector<FieldAttempt> field_attempts{{0, true, 0.5}, {0, false, 0.5}, {0, true, 1.0}, {10, true, 0.5},
                                           {300, true, 0.5}, {1000, true, 0.5}};
  /// With feature walls, at most max(1, field_wall_work / F) of the attempts for a surface of F
  /// faces (0: all of them); without walls every attempt runs. Each costs a field and a tracing of
  /// about F; on the shared meshes (F <= 100k) all of them run, on a 1M-face surface two (then, if
  /// they fail, the attempts without the walls). Sizes, not the clock, decide.
  std::int64_t field_wall_work = 2'000'000;
  /// Refinement bounds of the embedding (Tutte for g >= 1, orbifold Tutte for g = 0).
  TutteOptions tutte;
  std::size_t max_witnesses = 20;
  /// Genus >= 1: the memory the stages after the arrangement may need, in bytes (0: this machine's
  /// physical memory; no check where that is unknown). They need about kBytesPerIgmTriangle per
  /// IGM triangle (exact locations, UVs, charts, quads, the certifier's copy); an arrangement
  /// that would need more is igm::Error(Unsupported), raised by the overlay itself as soon as its
  /// lower bound passes the limit (OverlayOptions::max_triangles), instead of running out of
  /// memory minutes later (cheese with the normal form: 36.7M triangles, ~70 GB).
  std::uint64_t memory_limit_bytes = 0;
  /// Smooth the map (smooth/smooth.h: projected Newton on the symmetric Dirichlet energy, every
  /// iterate a certified IGM in doubles; transitions, cones and quad counts unchanged), then take
  /// the quads from its integer isolines (extract/isolines.h). Off: the layout's map, put on a
  /// double grid where that keeps it valid (smooth/dyadic.h), and its rectangles' grids.
  bool smooth = true;
  /// When smoothing stops (SmoothOptions): after smooth_iterations Newton iterations, after an
  /// iteration that lowers the energy by less than smooth_min_decrease of it, after two accepted
  /// steps in a row below smooth_stall_step of the Newton step (the map pressed against its
  /// barrier: cheese's steps are 3e-4..3e-3), or when converged. Never by the clock unless
  /// smooth_seconds > 0 (a wall-time budget: the result then depends on the machine's speed).
  /// Every size is smoothed. Measured in bench/README.md ("Issue 44").
  int smooth_iterations = 100;
  /// Also at most max(5, smooth_work / T) iterations for an IGM of T triangles (0: no such cap):
  /// a Newton iteration costs about T, so the whole smoothing stays near smooth_work triangle
  /// iterations whatever the size (100k triangles get the full 100; generated genus 20 with 1M
  /// faces, 1.27M triangles, 7 iterations instead of 85 and 20 minutes). Deterministic: sizes,
  /// not the clock. `igm run --smooth-iterations N` sets it to 0 (N iterations asked for).
  std::int64_t smooth_work = 10'000'000;
  double smooth_min_decrease = 1e-3;
  double smooth_stall_step = 0.005;
  double smooth_seconds = 0;
  /// Without smoothing: take the quads from the map's own structure (the layout's rectangles,
  /// extract/patch_grid.h; genus 0: the pillowcase's cells, extract/orbifold_quads.h) instead of
  /// its integer isolines. The same quads (the tests compare them): kept as the isolines' oracle.
  bool structured_extraction = false;
  /// Called after every smoothing iteration (the library never prints).
  std::function<void(const SmoothProgress&)> smooth_progress;
  /// Measure the outputs' quality (quality/quality.h; never decides validity): the IGM's
  /// distortion and the quad mesh's shape, and with quality_distance the two-sided distance
  /// between the quad mesh and the input (the costly part: ~1 s on 1M input triangles).
  bool quality = true;
  bool quality_distance = true;
  /// Sharp features (features/feature_edges.h): detected once per input surface after validation
  /// (compute_igm on a ValidMesh, compute_igms on each surface), with the user's feature_edges
  /// merged in. They feed the quality report (PipelineResult::feature_quality: how much of their
  /// length the quad edges cover); LayoutKind::Field follows them (docs/field.md, section 8: every
  /// kept feature edge on an integer isoline, checked by the certifier), the other layouts do not.
  /// Options out of range: igm::Error(InvalidArgument) before any other stage.
  FeatureOptions features;
  /// The user's feature edges: pairs of input vertex ids (0-based, the mesh file's order, as
  /// ValidMesh::input_vertex and SurfaceComponent::input_vertex give them), either direction. A
  /// pair that is an edge of no surface: igm::Error(InvalidArgument) naming it, before any other
  /// stage. Read from a file by read_feature_edges (`igm run --features FILE`).
  std::vector<std::array<std::int64_t, 2>> feature_edges;
  std::function<void(const StageEvent&)> progress;  // optional
  /// Measure each stage's peak resident memory (StageEvent::peak_mb; Linux: the process's peak is
  /// reset at the start of every stage, see igm/core/memory.h). Off by default: it resets a
  /// process-wide counter that the caller may be reading.
  bool measure_stage_memory = false;
  /// Threads for the parallel stages (igm/core/threads.h): 0 = IGM_THREADS if set, else all cores.
  /// The outputs are the same for any count.
  int threads = 0;
};

struct PipelineStats {
  /// The layout that produced the output: "field", "spread", "kite", "paper", or "orbifold" (the
  /// genus-0 pillowcase); with LayoutKind::Field and a fallback, the fallback's, and
  /// layout_fallback names the field path's stage that could not finish and why ("" when none).
  std::string layout;
  std::string layout_fallback;
  CrossFieldStats cross_field;     // the field layout's stages (when tried)
  FieldLayoutStats field_layout;
  /// The field layout's feature walls (issue 45): chains of feature edges traced as layout
  /// curves (kept), and those left out because the field gave no ray for them (a sharp turn).
  int feature_walls = 0, features_dropped = 0;
  /// When no field layout could follow the walls (all of them then left out): the first reason.
  std::string features_failure;
  QuantizeStats quantize;
  int genus = 0;
  int boundary_loops = 0;  // of an open surface (0: closed)
  int input_vertices = 0, input_faces = 0;
  int refined_vertices = 0, refined_faces = 0;  // after the topology stage's splits
  int output_vertices = 0, output_triangles = 0;  // the IGM triangle mesh
  int layout_quads = 0, quads = 0;  // genus 0: the 2 cells of the domain [0,2] x [0,1]
  int chords = 0;                   // genus >= 1: the layout's chords
  int layout_edges = 0;             // surface edges of the layout
  double edge_length = 0;           // the H of the sizing (0 with a resolution)
  std::array<int, 2> grid{0, 0};    // genus 0: quads per unit of the pillowcase in x and y
  /// The floor (PipelineOptions, sizes): the least quad count of a manifold quad mesh of this
  /// surface's layout (genus 0: 2); the quad count aimed at (the option, the default or, among
  /// several surfaces, this one's share; 0 with an edge length or a resolution); the chords (genus
  /// 0: grid counts) the floor raised above what the edge length or resolution gives them.
  std::int64_t floor_quads = 0;
  std::int64_t quads_asked = 0;
  int raised_chords = 0;
  /// The floor raised this surface's quads above what its size option asks (floor_note says how).
  /// When the IGM is valid but its isolines are not a manifold quad mesh: why, for people
  /// (extract/quad_defects.h: which quads, edges and cones); "" otherwise.
  std::string quad_defects;
  bool raised_by_floor() const { return quads_asked > 0 ? quads_asked < floor_quads : raised_chords > 0; }
  std::size_t max_uv_bits = 0;  // largest bit_size of an exact UV coordinate
  PatchMapStats patch_maps;
  SmoothStats smooth;           // with PipelineOptions::smooth (iterations 0 otherwise)
  DyadicStats dyadic;           // without it: the map put on a double grid (or why not)
  bool uv_doubles = false;      // every written UV coordinate is exactly a double
  CutStats cut;
  TutteStats tutte;
  // genus 0 (orbifold Tutte): the cones (vertex ids of the input and of the IGM), the cut, the embedding
  std::array<int, 4> cones{-1, -1, -1, -1};
  SphereCutStats sphere_cut;
  OrbifoldTutteStats orbifold;
  std::vector<StageEvent> stages;
};

/// "" unless stats.raised_by_floor(); else a phrase for humans, e.g. "at the floor of 8 quads (4
/// asked)" or "2 chords raised to the floor (18 quads at least)".
std::string floor_note(const PipelineStats& stats);

struct PipelineResult {
  IgmMesh igm;                       // refinement of the input: exact per-corner UV, exact vertex locations
  QuadMesh quads;                    // a x b quads per layout quad
  certify::Report igm_report;        // certifier checks 1-4 on `igm`
  certify::Report quad_report;       // certifier check 5 on `quads` (expected genus = input genus)
  SchemaDrawing schema;              // the polygonal schema, for the SVG picture
  IgmQuality igm_quality;            // with PipelineOptions::quality (else zero)
  QuadQuality quad_quality;
  /// The input's features (PipelineOptions::features; vertex ids of the input mesh or surface),
  /// and, with PipelineOptions::quality, how the quads cover them (quality/quality.h). Filled by
  /// compute_igm on a ValidMesh; under compute_igms each surface gets `features` and the measure
  /// is SurfacesResult::feature_quality; compute_igm on a SurfaceComponent fills neither.
  FeatureEdges features;
  FeatureQuality feature_quality;
  PipelineStats stats;
  bool certified() const { return igm_report.valid() && quad_report.valid(); }
};

/// Computes a certified IGM of a closed orientable mesh (paper §4–5). Genus g >= 1: loops and
/// cut (topology), rational convex 4g-gon and exact (weighted) Tutte map (embed), a quad layout of
/// the polygon (layout) overlaid exactly (arrange), each layout quad's patch sized into an integer
/// a x b rectangle (layout/sizing.h) and mapped onto it (igm/patch_maps.h), the rectangles' unit
/// grids as quads (extract/patch_grid.h). Genus 0: cut along a path through four cones
/// (topology/sphere_cut.h), orbifold Tutte map onto the pillowcase with four pi-cones at integer
/// points (embed/orbifold_tutte.h; scaled by integers a, b in x and y, it is the IGM), the 2 a b
/// unit cells of the domain as quads (extract/orbifold_quads.h). Then the independent certifier on
/// both outputs. Throws igm::Error(InvalidArgument) for bad sizes, a bad root or a bad cone list.
/// Cost: dominated by the embedding and the overlay, about O(n log n) plus the exact arithmetic.
PipelineResult compute_igm(const ValidMesh& mesh, const PipelineOptions& options = {});

/// compute_igm on one surface of validate_surfaces (mesh/validate_surfaces.h): a closed one as
/// above; an open one (boundary loops) cut into a disk with free sides along its boundary
/// (topology/open_cut.h), every boundary edge then on an integer isoline and every boundary
/// corner at an integer point, certified in the certifier's boundary mode (certify/README.md).
/// Vertex ids in the result are the component's local ids. Errors as compute_igm.
PipelineResult compute_igm(const SurfaceComponent& surface, const PipelineOptions& options = {});

/// Every surface's IGM and quads, and all of them as one output: ids of component c offset by the
/// vertices of the components before it (IGM: their refined vertices; quads: their quad vertices;
/// locations: their input vertices, in component order), certified together with the certifier's
/// components mode (and boundary mode for open surfaces; per component its genus and loops).
struct SurfacesResult {
  std::vector<PipelineResult> components;  // one per SurfaceSet component, in its order
  IgmMesh igm;
  QuadMesh quads;
  certify::Report igm_report, quad_report;  // the certifier on the merged outputs
  IgmQuality igm_quality;                   // with PipelineOptions::quality, over all of it
  QuadQuality quad_quality;
  FeatureQuality feature_quality;           // every surface's features (components[c].features)
  std::vector<Vec3d> input_positions;       // the components' input vertices, merged
  /// The quad count shared among the surfaces (the option or the default; 0 with an edge length
  /// or a resolution) and the quads they got: more when a surface's share is below its floor.
  std::int64_t quads_asked = 0, quads_total = 0;
  bool certified() const { return igm_report.valid() && quad_report.valid(); }
};

/// Runs compute_igm on every component of `surfaces` and merges them (above). A quad count (given,
/// or the default) is shared among several surfaces in proportion to their 3D areas; an edge
/// length or a resolution applies to each. Every surface gets at least its floor (PipelineOptions),
/// so the total can exceed the count (quads_total > quads_asked; each surface's stats say which). The progress events of component c carry its index in
/// their detail ("surface c: ..."). Cost: the sum.
SurfacesResult compute_igms(const SurfaceSet& surfaces, const PipelineOptions& options = {});

}  // namespace igm
