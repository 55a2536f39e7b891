#pragma once
// The certifier's own Wavefront OBJ reader. Reads v / vt / vn / vp / f (plus o g s usemtl mtllib,
// ignored) with '#' comments (to the end of the physical line) and backslash line continuations
// (a line ending in '\', spaces, tabs or a CR after it, continues on the next one; errors name
// the statement's first line); vt numbers exactly (decimal or p/q, see exact.h). Indices may be
// negative (relative to the elements defined so far); positive indices are resolved after the
// whole file is read. Every allocation is proportional to the text actually present.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <gmpxx.h>

namespace igm::certify {

struct ObjMesh {
  std::int64_t num_vertices = 0;            // number of `v` lines
  std::vector<std::int64_t> face_begin;     // size F+1: corners of face f are [face_begin[f], face_begin[f+1])
  std::vector<int> corner_vertex;           // 0-based vertex id per corner
  std::vector<int> corner_uv;               // 0-based vt id per corner, -1 when absent
  std::vector<std::array<mpq_class, 2>> uv; // exact vt values (u, v); w ignored
  std::vector<std::int64_t> face_line;      // 1-based line of each face
  std::int64_t num_faces() const { return std::int64_t(face_begin.size()) - 1; }
};

struct ObjReadResult {
  bool ok = false;
  std::string error;          // "line N: ..." when !ok
  std::int64_t error_line = 0;
  ObjMesh mesh;
};

/// Parses OBJ text. Never throws except std::bad_alloc; any malformed statement, a missing or
/// out-of-range index, an index 0, a face with fewer than 3 corners, NaN/inf text or an unknown
/// statement gives ok = false with the line number.
ObjReadResult read_obj(std::string_view text);

}  // namespace igm::certify
