#pragma once
// Typed errors of the igm library. Every error names its kind and, where one exists, the
// offending element (vertex, face, edge endpoints, line of a file) so that a user can find it.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace igm {

enum class ErrorKind {
  Io,                 // file missing, unreadable, truncated
  Parse,              // malformed text or binary layout (with line or byte offset)
  TooLarge,           // a declared size that the file cannot hold, or beyond the index range
  Empty,              // no vertices
  NoFaces,            // vertices but no faces (point cloud)
  IndexOutOfRange,    // a face refers to a vertex that does not exist
  NonFinite,          // NaN or Inf coordinate
  RepeatedVertex,     // a face uses the same vertex twice
  NonManifoldEdge,    // an edge with more than two faces, or two faces with the same direction
  NonManifoldVertex,  // the faces around a vertex form more than one fan
  Boundary,           // the surface is not closed
  SeveralComponents,  // more than one connected component
  NonOrientable,      // no consistent orientation exists
  InvalidArgument,    // a caller's option is out of range (root vertex, genus, cone list ...)
  Unsupported,        // valid input this stage does not handle (e.g. genus 0 in topology)
  Internal,           // a broken invariant: a bug, reported instead of crashing
};

/// Stable lower-case name of a kind, e.g. "non_manifold_edge" (used in CLI and JSON output).
const char* to_string(ErrorKind kind);

/// The exception type of the library. `elements` lists offending ids (meaning depends on kind:
/// faces for NonManifoldEdge, the vertex for NonManifoldVertex, a line number for Parse ...).
class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message, std::vector<std::int64_t> elements = {})
      : std::runtime_error(compose(kind, message)),
        kind_(kind),
        elements_(std::move(elements)) {}
  ErrorKind kind() const noexcept { return kind_; }
  /// what() without its "kind: " prefix (to add to a message and throw again).
  std::string message() const { return std::string(what()).substr(std::char_traits<char>::length(to_string(kind_)) + 2); }
  const std::vector<std::int64_t>& elements() const noexcept { return elements_; }

 private:
  static std::string compose(ErrorKind kind, const std::string& message) {
    std::string s = to_string(kind);
    s.append(": ").append(message);
    return s;
  }
  ErrorKind kind_;
  std::vector<std::int64_t> elements_;
};

}  // namespace igm
