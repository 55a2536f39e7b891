#pragma once
// Sharp features of a triangle mesh: the feature edges (sharp by dihedral angle, or given by the
// user), the feature curves (their chains) and the feature corners (issue 45, step 1; QuadWild,
// Pietroni et al. 2021, detects them the same way). They feed the quality report
// (quality/quality.h, measure_features) and the field layout (docs/field.md, section 8).
#include <array>
#include <cstdint>
#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "igm/exact/predicates.h"
#include "igm/mesh/trimesh.h"

namespace igm {

struct FeatureOptions {
  /// Detect sharp edges. Off: only the user's edges are features (`--no-features`, with or
  /// without `--features FILE`).
  bool enabled = true;
  /// An interior edge is sharp when the angle between its two faces' normals is >= this, in
  /// degrees, in [0, 180] (0: every edge between two non-degenerate faces; 180: only folds).
  double angle_degrees = 35;
  /// A vertex where exactly two feature edges meet is a corner when the curve turns there by at
  /// least this angle (between the directions a -> v and v -> b), degrees in [0, 180].
  double corner_angle_degrees = 60;
  /// Noise rule: a chain of detected edges (maximal path between vertices where the number of
  /// feature edges is not 2, or a closed loop) with fewer than noise_min_edges edges AND a length
  /// below noise_min_length times the mesh's bounding-box diagonal is dropped (scans' speckle).
  /// A chain with a user edge is never dropped. 0 for either disables the rule. The defaults
  /// change none of the shared CAD parts' creases but couplingdown's one 2-edge chain, and halve
  /// the coarse scan bull's (bench/README.md, "Issue 45").
  int noise_min_edges = 5;
  double noise_min_length = 0.02;
  /// Resolution rule: with quad_size > 0 (the target quad edge length, in the positions' units:
  /// the pipeline sets it from --quads or --edge-length; 0 with --resolution), a chain of
  /// detected edges (as above) shorter than min_quad_edges * quad_size stays a feature (measured)
  /// but is not followed (FeatureEdges::follow): a wall that short only bends the layout around
  /// it (organic scans: elephant 210 curves, most of 1-3 edges). Measured over the shared meshes
  /// at 10k quads (bench/README.md, "Issue 45: features the quads can follow"). A chain with a
  /// user edge is always followed; 0 for either disables the rule.
  double quad_size = 0;
  double min_quad_edges = 6;
};

/// One feature curve: vertices[i] -> vertices[i + 1] runs along halfedges[i] (a half-edge of the
/// mesh in that direction). closed: the curve comes back to its first vertex (front == back).
struct FeatureCurve {
  std::vector<int> vertices;
  std::vector<int> halfedges;
  bool closed = false;
  double length = 0;  // sum of the edges' 3D lengths
};

struct FeatureStats {
  int edges = 0;           // feature edges kept (user edges included)
  int user_edges = 0;      // distinct edges given by the user
  int curves = 0, closed_curves = 0, corners = 0;
  int dropped_chains = 0, dropped_edges = 0;  // by the noise rule
  int short_chains = 0, short_edges = 0;      // kept but not followed (the resolution rule)
  int degenerate_faces = 0;                   // zero normal (in double): their edges never sharp
  double length = 0;                          // total 3D length of the feature edges kept
};

struct FeatureEdges {
  /// Per half-edge of the mesh: 1 if its edge is a feature edge (both half-edges of an interior
  /// edge are set), else 0.
  std::vector<std::uint8_t> halfedge;
  /// Per half-edge: 1 on the feature edges a layout follows (all but the resolution rule's short
  /// chains; FeatureOptions::quad_size). Empty (a hand-made FeatureEdges): all followed.
  std::vector<std::uint8_t> follow;
  /// The feature edges by canonical half-edge: h with h < twin(h) (or twin(h) == -1), increasing.
  std::vector<int> edges;
  /// The feature edges split at the corners: a curve from a corner runs to the next corner; a
  /// closed chain without a corner is one closed curve starting at the origin of its smallest
  /// canonical half-edge. Curves from corners first, in increasing order of (corner, first
  /// canonical half-edge), then the corner-free loops by smallest canonical half-edge.
  std::vector<FeatureCurve> curves;
  /// Increasing vertex ids: vertices with one feature edge (a curve ends), three or more (curves
  /// meet), or two with a turn >= FeatureOptions::corner_angle_degrees.
  std::vector<int> corners;
  FeatureStats stats;
};

/// The features of `mesh` (closed or with boundary, TriMesh conventions). Sharp edge: an interior
/// edge between faces with normals n1, n2 (unnormalized cross products, coordinates first scaled
/// exactly by a power of two, mesh/scale.h) with n1.n2 <= cos(angle) |n1| |n2|, decided in
/// double with squared forms and det_sincos (core/det_math.h): the same bits on every machine.
/// Boundary edges are never detected (they are boundary already); an edge of a face whose normal
/// is zero in double is never detected. Then the noise and resolution rules (FeatureOptions) are
/// applied once to the detected chains, the user's edges added (merged with the detected ones; to use only them,
/// enabled = false), the corners and curves built. user_edges are pairs of vertex ids of `mesh`,
/// in either direction, repeats allowed; a boundary edge given by the user is a feature.
/// Throws igm::Error(InvalidArgument) for options out of range or a pair that is not an edge of
/// the mesh (naming the pair and why: a vertex out of range, the same vertex twice, no such edge);
/// positions.size() != num_vertices: InvalidArgument. Cost O(F + E log E).
FeatureEdges detect_features(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                             const std::vector<std::array<int, 2>>& user_edges = {},
                             const FeatureOptions& options = {});

/// Reads a features file: one pair "i j" of 0-based vertex ids (the mesh file's order) per line,
/// '#' to the end of a line is a comment, blank lines skipped. Throws igm::Error(Parse) with the
/// line number (elements = {line}) for anything else, igm::Error(Io) if the file cannot be read.
/// `name` names the source in messages. Cost O(size).
std::vector<std::array<std::int64_t, 2>> parse_feature_edges(std::istream& in, const std::string& name);
std::vector<std::array<std::int64_t, 2>> read_feature_edges(const std::filesystem::path& path);

/// The user's pairs (ids of the input file's vertices) that are edges of a mesh whose vertex v is
/// input vertex input_vertex[v] (ValidMesh, SurfaceComponent), as pairs of the mesh's vertex ids;
/// found[i] is set for each pair i found (found is resized to pairs.size() if smaller and only
/// ever set, so that several surfaces can share it). Cost O(V + k valence).
std::vector<std::array<int, 2>> input_feature_edges(const TriMesh& mesh, const std::vector<std::int64_t>& input_vertex,
                                                     const std::vector<std::array<std::int64_t, 2>>& pairs,
                                                     std::vector<std::uint8_t>& found);

/// Throws igm::Error(InvalidArgument) naming the first pair i with !found[i] ("feature edge (a, b)
/// is not an edge of the mesh"). O(k).
void check_feature_edges_found(const std::vector<std::array<std::int64_t, 2>>& pairs,
                               const std::vector<std::uint8_t>& found);

}  // namespace igm
