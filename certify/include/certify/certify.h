#pragma once
// igm::certify — the independent judge of Integer Grid Maps (IGMs).
//
// Depends on GMP and the standard library only: its own OBJ reader (obj.h), its own adjacency,
// its own exact predicates and decimal parser (exact.h). It never includes the producer's headers.
// Format, checks, JSON schema and exit codes: certify/README.md.
//
// Checks (all exact; doubles only feed a filter with a proven error bound):
//   1 topology     closed, edge- and vertex-manifold, consistently oriented, connected; V,E,F, genus
//                  (boundary edges with Options::allow_boundary, several components with
//                  Options::allow_components)
//   2 orientation  every UV triangle strictly positive (exact orient2d); flipped / degenerate counts
//   3 transitions  every interior edge: x -> R^k x + t, k in {0..3}, t in Z^2, same for both ends;
//                  every boundary edge (allow_boundary) on an integer isoline u = c or v = c
//   4 cones        per-vertex index k (total angle k*pi/2) by exact quadrant counting; k != 4 must be
//                  on an integer point; boundary vertices: angle k*pi/2, k >= 1, k != 2 on an
//                  integer point; Poincare-Hopf per component sum_int(4-k) + sum_bnd(2-k) = 4 chi
//   5 quad mesh    (quad mode) pure quads, manifold oriented (closed and connected unless allowed),
//                  genus, boundary loops, per-component (genus, loops), valences
//   features       (IGM mode, when Options::feature_edges is set; Report::features) every given
//                  feature edge lies on an integer isoline u = c or v = c (c in Z) in the chart of
//                  every face containing it: the same exact test as boundary edges in check 3
// Ids in reports are 0-based (vertex v of an OBJ file is OBJ index v+1; faces in file order).
#include <array>
#include <compare>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gmpxx.h>

namespace igm::certify {

enum class Status { Pass, Fail, Incomplete, Skipped };
enum class Verdict { Valid = 0, Invalid = 1, Unreadable = 2 };

const char* to_string(Status s);
const char* to_string(Verdict v);

/// One offending element. kind: "face" (ids = {f}), "edge" (ids = {u, v}, vertex pair, u < v),
/// "vertex" (ids = {v}), "component" (ids = {its smallest vertex id}), "mesh" (ids = {}).
/// values: named exact values ("p/q" strings, points as "(x, y)").
struct Witness {
  std::string kind;
  std::vector<std::int64_t> ids;
  std::string reason;
  std::vector<std::pair<std::string, std::string>> values;
};

struct CheckResult {
  int id = 0;                 // 1..5
  std::string name;           // "topology", "uv_orientation", "transitions", "cones", "quad_mesh"
  Status status = Status::Skipped;
  std::vector<std::pair<std::string, std::int64_t>> counts;  // ordered, named counts
  std::string histogram_name;                                // e.g. "vertex_index_k", "valence"
  std::map<std::int64_t, std::int64_t> histogram;
  /// Check 4 with Options::allow_boundary: boundary vertices by boundary index k (angle k*pi/2);
  /// "vertex_index_k" then counts interior vertices only.
  std::string boundary_histogram_name;
  std::map<std::int64_t, std::int64_t> boundary_histogram;
  std::int64_t offending = 0;          // total number of offending elements (witnesses are capped)
  std::vector<Witness> witnesses;      // at most Options::max_witnesses
  std::string note;

  /// The named count, or -1 if absent.
  std::int64_t count(const std::string& key) const;
  bool passed() const { return status == Status::Pass; }
};

/// One connected component (vertices joined by edges; unreferenced vertices belong to none).
struct ComponentInfo {
  std::int64_t first_vertex = 0;  // its smallest vertex id: names the component in witnesses
  std::int64_t vertices = 0, edges = 0, faces = 0;
  std::int64_t boundary_edges = 0;
  std::optional<std::int64_t> boundary_loops;  // when the mesh is manifold and oriented
  std::int64_t euler_characteristic = 0;       // V - E + F of the component
  std::optional<std::int64_t> genus;           // (2 - chi - loops) / 2 when loops are defined
  /// IGM mode: sum_interior (4 - k) + sum_boundary (2 - k) when every vertex of the component has
  /// an exact index (check 4); Poincare-Hopf requires it to equal 4 chi.
  std::optional<std::int64_t> poincare_hopf_sum;
};

struct Report {
  Verdict verdict = Verdict::Unreadable;
  std::string mode = "igm";            // "igm" or "quad"
  std::string source;                  // file name or "<memory>"
  std::string error;                   // set when unreadable (names the line for files)
  std::int64_t error_line = 0;         // 1-based line of the error in the file, 0 if none
  std::int64_t num_vertices = 0, num_edges = 0, num_faces = 0;
  std::optional<std::int64_t> euler_characteristic;  // V - E + F (when the edge count is defined)
  /// When check 1 passes (closed, manifold, oriented, connected, or with boundary / several
  /// components where allowed): the sum of the components' genera.
  std::optional<std::int64_t> genus;
  std::int64_t num_boundary_edges = 0;         // edges with exactly one face
  std::optional<std::int64_t> boundary_loops;  // total, when the mesh is manifold and oriented
  std::vector<ComponentInfo> components;       // by increasing first_vertex
  std::vector<CheckResult> checks;
  /// Options::feature_edges given and the input readable: the features check (id 6, name
  /// "features"; counts, witnesses per face off its isoline). Not in `checks`; the verdict
  /// requires it to pass too.
  std::optional<CheckResult> features;

  /// The check with this id (1..5), or nullptr.
  const CheckResult* check(int id) const;
  bool valid() const { return verdict == Verdict::Valid; }
};

/// Topology of one component, for quad-mode expectations.
struct ComponentTopology {
  std::int64_t genus = 0;
  std::int64_t boundary_loops = 0;
  auto operator<=>(const ComponentTopology&) const = default;
};

/// One feature edge (a crease the IGM must map onto an integer isoline): an unordered pair of
/// 0-based vertex ids, and its 1-based line in a features file (0 when given in memory).
struct FeatureEdge {
  std::int64_t a = 0, b = 0;
  std::int64_t line = 0;
};

/// A parsed features file (read_feature_edges): the pairs in file order, or the error.
struct FeatureReadResult {
  bool ok = false;
  std::string error;           // "line N: ..." when !ok
  std::int64_t error_line = 0; // 1-based, 0 when the file cannot be read
  std::vector<FeatureEdge> edges;
};

/// Parses a features file: text, one feature edge per line as two 0-based vertex ids "i j"
/// (decimal digits, separated by spaces or tabs; surrounding spaces, tabs and a trailing CR
/// allowed); blank lines and lines whose first non-blank character is '#' are ignored. Anything
/// else (a third token, a sign, a trailing comment, an id above 2^31 - 1) is malformed: ok =
/// false, error names the line. Cost O(text). The same format as `igm run --features FILE`.
FeatureReadResult read_feature_edges(const std::string& text);
/// The same for a file (a missing or unreadable file: ok = false, error_line 0).
FeatureReadResult read_feature_edges_file(const std::string& path);

/// The defaults judge closed, connected surfaces only (a boundary edge or a second component
/// fails check 1).
struct Options {
  std::size_t max_witnesses = 20;
  std::optional<std::int64_t> expected_genus;  // quad mode: check 5 requires this (total) genus
  /// Surfaces with boundary: boundary edges pass check 1 and are judged by checks 3 and 4.
  bool allow_boundary = false;
  /// Several connected components: each is judged on its own (Poincare-Hopf per component).
  bool allow_components = false;
  /// Quad mode: check 5 also requires this total number of boundary loops.
  std::optional<std::int64_t> expected_boundary_loops;
  /// Quad mode, when not empty: the components' (genus, boundary loops), compared as multisets
  /// (order free: a producer may number its output's components differently).
  std::vector<ComponentTopology> expected_components;
  /// Threads for the per-element checks (certify/README.md, "Threads"): 0 = the environment's
  /// IGM_THREADS if set, else every core. The report is the same for any count.
  int threads = 0;
  /// IGM mode, when set (even empty): the features check (Report::features). Each pair must be an
  /// edge of the mesh (vertex ids in range, a != b, some face has both as consecutive corners),
  /// else the report is Unreadable naming the pair (and its line when line > 0). Each edge is
  /// checked once (repeated pairs, in either order, are counted in "duplicates"): in every face
  /// containing it, the corner UVs at a and b satisfy u_a = u_b in Z or v_a = v_b in Z, exactly.
  /// A failure makes the verdict Invalid. Quad mode ignores it. Cost O(E + n log E), n pairs.
  std::optional<std::vector<FeatureEdge>> feature_edges;
};

/// In-memory IGM: triangles (0-based vertex ids) and one exact UV per face corner, three per face
/// in face order (corner i of face f is corner_uv[3f+i]). The vertex count is num_vertices if
/// >= 0, else positions.size() if positions are given, else max index + 1. Positions are optional
/// and used by no check (an IGM is judged on its combinatorics and UVs only).
struct IgmInput {
  std::vector<std::array<int, 3>> faces;
  std::vector<std::array<mpq_class, 2>> corner_uv;
  std::int64_t num_vertices = -1;
  std::vector<std::array<double, 3>> positions;
};

/// In-memory quad mesh (0-based ids); num_vertices < 0 means "max index + 1".
struct QuadInput {
  std::vector<std::array<int, 4>> quads;
  std::int64_t num_vertices = -1;
};

/// Certify an in-memory IGM (checks 1-4). Cost O(F log F) plus exact arithmetic where the
/// double filter cannot decide. Malformed input (bad sizes, indices out of range) gives a
/// report with verdict Unreadable; never throws except std::bad_alloc.
Report certify_igm(const IgmInput& input, const Options& options = {});
/// The same, consuming the input: its UVs are moved, not copied (for large producers' outputs).
Report certify_igm(IgmInput&& input, const Options& options = {});

/// Certify an in-memory quad mesh (check 5).
Report certify_quads(const QuadInput& input, const Options& options = {});

/// Certify OBJ text (IGM mode: triangles with `f v/vt`; see certify/README.md).
Report certify_igm_text(const std::string& text, const Options& options = {});
/// Certify OBJ text as a quad mesh (`f a b c d`, uv optional).
Report certify_quads_text(const std::string& text, const Options& options = {});

/// Read a file (missing/unreadable file -> verdict Unreadable) and certify it.
Report certify_igm_file(const std::string& path, const Options& options = {});
Report certify_quads_file(const std::string& path, const Options& options = {});

/// The report as JSON (schema in certify/README.md). Deterministic, ends with a newline.
std::string to_json(const Report& report);

/// One line for humans: "VALID igm V=.. F=.. genus=.." or "INVALID: failed checks ...".
std::string summary(const Report& report);

/// Process exit code for the verdict: 0 valid, 1 invalid, 2 unreadable.
inline int exit_code(const Report& r) { return static_cast<int>(r.verdict); }

}  // namespace igm::certify
