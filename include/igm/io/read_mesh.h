#pragma once
// Mesh file readers: OBJ, OFF, PLY (ascii, binary little/big endian), STL (ascii, binary).
// They return the raw polygon soup; validation and triangulation are in mesh/validate.h.
#include <filesystem>
#include <string_view>

#include "igm/mesh/soup.h"

namespace igm {

enum class MeshFormat { Obj, Off, Ply, Stl };

/// Format from the file extension (case-insensitive); throws igm::Error(Io) if unknown.
MeshFormat format_from_path(const std::filesystem::path& path);

/// Parses a whole file held in memory. Throws igm::Error(Parse) naming the line (text) or
/// byte offset (binary), igm::Error(TooLarge) when a declared count cannot fit in the bytes
/// present (checked before allocating). STL: vertices with bit-identical positions are welded.
/// Cost O(bytes).
PolygonSoup read_soup(std::string_view bytes, MeshFormat format);

/// Reads a file (format from its extension). Throws igm::Error(Io) if it cannot be read.
PolygonSoup read_soup(const std::filesystem::path& path);

}  // namespace igm
