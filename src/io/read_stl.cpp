// STL reader, ascii and binary, told apart by content, not by the case of the first word.
// A file is binary when its size is exactly 84 + 50 * (the triangle count at byte 80), unless
// it starts with "solid" and every byte is printable text (an ascii file whose size happens to
// match); otherwise it is ascii when it starts with "solid" and is text (or has "facet" in its
// first KB: non-ASCII names), and rejected when not. Ascii keywords (solid, facet, normal,
// outer, loop, vertex, endloop, endfacet, endsolid) are compared case-insensitively: writers
// such as admesh's examples write them in capitals. Vertices with identical coordinates are
// welded (compared as values: -0 and +0 weld; NaN never welds). Cost O(bytes + T log T).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include "read_detail.h"

namespace igm::detail {

namespace {

// Welds corner positions into shared vertices; vertex ids follow first appearance.
PolygonSoup weld(const std::vector<Vec3d>& corners, std::vector<std::size_t> face_begin) {
  struct Key {
    std::uint64_t x, y, z;
    std::uint32_t corner;
  };
  auto bits = [](double d) { return std::bit_cast<std::uint64_t>(d == 0.0 ? 0.0 : d); };
  std::vector<Key> keys(corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i)
    keys[i] = {bits(corners[i].x), bits(corners[i].y), bits(corners[i].z), static_cast<std::uint32_t>(i)};
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    if (a.z != b.z) return a.z < b.z;
    return a.corner < b.corner;
  });
  // group -> representative = its first corner (smallest index, thanks to the tie-break)
  std::vector<std::uint32_t> rep(corners.size());
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    const bool nan = std::isnan(corners[keys[i].corner].x) || std::isnan(corners[keys[i].corner].y) ||
                     std::isnan(corners[keys[i].corner].z);
    while (j < keys.size() && keys[j].x == keys[i].x && keys[j].y == keys[i].y && keys[j].z == keys[i].z) {
      rep[keys[j].corner] = nan ? keys[j].corner : keys[i].corner;
      ++j;
    }
    i = j;
  }
  PolygonSoup soup;
  std::vector<std::int64_t> id(corners.size(), -1);
  soup.corners.resize(corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const std::uint32_t r = rep[i];
    if (id[r] < 0) {
      id[r] = static_cast<std::int64_t>(soup.positions.size());
      soup.positions.push_back(corners[r]);
    }
    soup.corners[i] = id[r];
  }
  soup.face_begin = std::move(face_begin);
  return soup;
}

// ASCII case-insensitive equality with a lower-case keyword.
bool keyword_is(std::string_view token, std::string_view lower_keyword) {
  if (token.size() != lower_keyword.size()) return false;
  for (std::size_t i = 0; i < token.size(); ++i) {
    const char c = token[i] >= 'A' && token[i] <= 'Z' ? static_cast<char>(token[i] - 'A' + 'a') : token[i];
    if (c != lower_keyword[i]) return false;
  }
  return true;
}

// The first word is "solid" in any case, followed by whitespace or the end of the file.
bool starts_with_solid(std::string_view b) {
  std::size_t i = 0;
  while (i < b.size() && is_space_or_newline(b[i])) ++i;
  const std::size_t end = std::min(b.size(), i + 5);
  return keyword_is(b.substr(i, 5), "solid") && (end == b.size() || is_space_or_newline(b[end]));
}

// "facet" (any case) somewhere in the first KB.
bool early_facet(std::string_view b) {
  const std::string_view head = b.substr(0, 1024);
  for (std::size_t i = 0; i + 5 <= head.size(); ++i)  // bound: 1 KB
    if (keyword_is(head.substr(i, 5), "facet")) return true;
  return false;
}

bool all_text(std::string_view b) {
  for (unsigned char ch : b)
    if (!(ch == '\n' || ch == '\r' || ch == '\t' || ch == '\v' || ch == '\f' || (ch >= 0x20 && ch < 0x7f)))
      return false;
  return true;
}

PolygonSoup read_binary(std::string_view bytes, std::uint32_t n) {
  const auto* d = reinterpret_cast<const unsigned char*>(bytes.data());
  auto f32 = [&](std::size_t off) {
    std::uint32_t u = static_cast<std::uint32_t>(d[off]) | static_cast<std::uint32_t>(d[off + 1]) << 8 |
                      static_cast<std::uint32_t>(d[off + 2]) << 16 | static_cast<std::uint32_t>(d[off + 3]) << 24;
    return static_cast<double>(std::bit_cast<float>(u));
  };
  std::vector<Vec3d> corners(3 * static_cast<std::size_t>(n));
  std::vector<std::size_t> face_begin(static_cast<std::size_t>(n) + 1);
  for (std::size_t t = 0; t < n; ++t) {         // bounded by n; the size check guarantees the bytes
    const std::size_t base = 84 + 50 * t + 12;  // skip the normal
    for (std::size_t k = 0; k < 3; ++k)
      corners[3 * t + k] = {f32(base + 12 * k), f32(base + 12 * k + 4), f32(base + 12 * k + 8)};
    face_begin[t + 1] = 3 * (t + 1);
  }
  return weld(corners, std::move(face_begin));
}

PolygonSoup read_ascii(std::string_view bytes) {
  TextCursor c(bytes);
  std::vector<Vec3d> corners;
  std::vector<std::size_t> face_begin = {0};
  bool in_loop = false, in_solid = false;
  std::size_t loop_start = 0;
  const char* loop_at = c.p;
  while (!c.at_end()) {  // one line per round
    c.skip_inline_space();
    const std::string_view token = c.take_token();
    const auto key = [token](std::string_view lower_keyword) { return keyword_is(token, lower_keyword); };
    if (key("solid")) {
      if (in_solid) c.fail(ErrorKind::Parse, "'solid' inside a solid");
      in_solid = true;
    } else if (key("endsolid")) {
      if (!in_solid || in_loop) c.fail(ErrorKind::Parse, "unexpected 'endsolid'");
      in_solid = false;
    } else if (key("outer")) {
      if (!in_solid || in_loop) c.fail(ErrorKind::Parse, "unexpected 'outer loop'");
      in_loop = true;
      loop_start = corners.size();
      loop_at = c.p;
    } else if (key("vertex")) {
      if (!in_loop) c.fail(ErrorKind::Parse, "'vertex' outside 'outer loop'");
      double xyz[3];
      for (double& x : xyz) {
        c.skip_inline_space();
        const char* q = parse_double(c.p, c.end, x);
        if (!q || (q < c.end && !is_space_or_newline(*q))) c.fail(ErrorKind::Parse, "vertex needs three numbers");
        c.p = q;
      }
      corners.push_back({xyz[0], xyz[1], xyz[2]});
    } else if (key("endloop")) {
      if (!in_loop) c.fail(ErrorKind::Parse, "unexpected 'endloop'");
      if (corners.size() - loop_start < 3)
        throw_at_line(ErrorKind::Parse, bytes, loop_at,
                      "facet with " + std::to_string(corners.size() - loop_start) + " vertices (at least 3 needed)");
      face_begin.push_back(corners.size());
      in_loop = false;
    } else if (key("facet") || key("endfacet") || token.empty()) {
      if (key("facet") && (!in_solid || in_loop)) c.fail(ErrorKind::Parse, "unexpected 'facet'");
    } else {
      c.fail(ErrorKind::Parse, "unknown STL keyword '" + std::string(token) + "'");
    }
    c.next_line();
  }
  if (in_loop || in_solid)
    throw_at_line(ErrorKind::Parse, bytes, c.end, "unexpected end of file (missing 'endloop' or 'endsolid')");
  if (corners.size() > UINT32_MAX) throw Error(ErrorKind::TooLarge, "too many STL vertices");
  return weld(corners, std::move(face_begin));
}

}  // namespace

PolygonSoup read_stl(std::string_view bytes) {
  const bool solid = starts_with_solid(bytes);
  const bool text = solid && all_text(bytes);
  if (bytes.size() >= 84) {
    const auto* d = reinterpret_cast<const unsigned char*>(bytes.data());
    const std::uint32_t n = static_cast<std::uint32_t>(d[80]) | static_cast<std::uint32_t>(d[81]) << 8 |
                            static_cast<std::uint32_t>(d[82]) << 16 | static_cast<std::uint32_t>(d[83]) << 24;
    const std::uint64_t expected = 84 + 50 * static_cast<std::uint64_t>(n);
    if (expected == bytes.size() && !text) {
      if (3 * static_cast<std::uint64_t>(n) > UINT32_MAX)
        throw_at_byte(ErrorKind::TooLarge, 80, "too many STL triangles");
      return read_binary(bytes, n);
    }
    // A size mismatch: ascii if it starts with "solid" and looks like text (a non-ASCII byte in
    // a solid's name is allowed when "facet" appears early), else a broken binary file.
    const bool ascii = text || (solid && early_facet(bytes));
    if (!ascii)
      throw_at_byte(expected > bytes.size() ? ErrorKind::TooLarge : ErrorKind::Parse, 80,
                    "binary STL declares " + std::to_string(n) + " triangles (" + std::to_string(expected) +
                        " bytes) but the file has " + std::to_string(bytes.size()) + " bytes" +
                        (expected > bytes.size() ? " (truncated?)" : " (trailing data)"));
  }
  if (!solid) throw Error(ErrorKind::Parse, "not an STL file (too short for binary STL, no 'solid' keyword)");
  return read_ascii(bytes);
}

}  // namespace igm::detail
