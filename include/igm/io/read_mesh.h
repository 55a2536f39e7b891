#pragma once
// Mesh file readers: OBJ, OFF, PLY (ascii, binary little/big endian), STL (ascii, binary).
// They return the raw polygon soup; validation and triangulation are in mesh/validate.h.
//
// What each reader accepts (details at the top of src/io/read_<fmt>.cpp):
// - OBJ: `v x y z`, `f` with v, v/vt, v//vn, v/vt/vn corners, negative (relative) indices,
//   polygons, comments, \r\n, backslash continuations; other statements are ignored.
// - OFF: [ST][C][N][n]OFF headers, counts on the keyword line or the next, `#` comments, blank
//   lines, extra per-vertex / per-face values (colours, normals) ignored.
// - PLY: ascii and binary, every scalar type for x/y/z, lists with any integer count/index
//   types, other properties and elements skipped; header lines of an unknown keyword (some
//   writers add a bare "Created by ...") skipped with a warning in PolygonSoup::warnings.
// - STL: ascii and binary told apart by content (binary when the size is 84 + 50 n for the
//   declared count n, even if it starts with "solid"; ascii keywords in any case, "SOLID" too);
//   vertices with equal coordinates are welded.
// Faces with fewer than 3 corners are rejected by the readers (Parse). Vertex ids are stored
// 0-based; ids out of range are kept and reported by validation.
#include <filesystem>
#include <string_view>

#include "igm/core/error.h"
#include "igm/mesh/soup.h"

namespace igm {

enum class MeshFormat { Obj, Off, Ply, Stl };

/// Format from the file extension (case-insensitive); throws igm::Error(Io) if unknown.
MeshFormat format_from_path(const std::filesystem::path& path);

/// Parses a whole file held in memory. Throws igm::Error(Parse) naming the line (text) or
/// byte offset (binary) in the message and in elements[0], igm::Error(TooLarge) when a
/// declared count cannot fit in the bytes present (checked before allocating, so memory
/// stays O(bytes)), igm::Error(Unsupported) for 4D or binary OFF. Never throws anything else
/// (except std::bad_alloc if the machine cannot hold O(bytes)). Cost O(bytes) (STL: plus a
/// sort of the corners for welding).
PolygonSoup read_soup(std::string_view bytes, MeshFormat format);

/// Reads a file (format from its extension). Throws igm::Error(Io) if it cannot be read;
/// parse errors are those of read_soup(bytes, format) with the path put in front.
PolygonSoup read_soup(const std::filesystem::path& path);

/// The same error (kind, elements) with "PATH: " put in front of its message.
Error with_path(const Error& e, const std::filesystem::path& path);

/// The whole content of a file. Throws igm::Error(Io) naming the path if it cannot be read.
std::string read_file_bytes(const std::filesystem::path& path);

}  // namespace igm
