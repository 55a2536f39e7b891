#pragma once
// Mesh writers: triangle meshes as OBJ or OFF text. Coordinates are written with the shortest
// decimal that reads back to the same double (std::to_chars), so write -> read is exact.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

/// OBJ text: one `v x y z` per position, one `f a b c` (1-based) per triangle. Pre: triangle
/// ids in range (throws igm::Error(IndexOutOfRange) naming the triangle otherwise). O(V + F).
std::string format_obj(const std::vector<Vec3d>& positions, const std::vector<std::array<int, 3>>& triangles);

/// OFF text: `OFF`, counts, positions, `3 a b c` (0-based) per triangle. Same checks as format_obj.
std::string format_off(const std::vector<Vec3d>& positions, const std::vector<std::array<int, 3>>& triangles);

/// Writes format_obj(...) to `path`; throws igm::Error(Io) naming the path if it cannot.
void write_obj(const std::filesystem::path& path, const std::vector<Vec3d>& positions,
               const std::vector<std::array<int, 3>>& triangles);

/// Writes format_off(...) to `path`; throws igm::Error(Io) naming the path if it cannot.
void write_off(const std::filesystem::path& path, const std::vector<Vec3d>& positions,
               const std::vector<std::array<int, 3>>& triangles);

/// Writes `text` to `path` (binary mode, replaced if present); throws igm::Error(Io).
void write_text_file(const std::filesystem::path& path, const std::string& text);

}  // namespace igm
