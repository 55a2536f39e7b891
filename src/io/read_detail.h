#pragma once
// Internal helpers shared by the mesh readers (not installed): a bounds-checked cursor over
// the file bytes, fast number parsing with std::from_chars, and error construction that
// names the line (text formats) or the byte offset (binary formats).
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <system_error>

#include "igm/core/error.h"
#include "igm/mesh/soup.h"

namespace igm::detail {

PolygonSoup read_obj(std::string_view bytes);
PolygonSoup read_off(std::string_view bytes);
PolygonSoup read_ply(std::string_view bytes);
PolygonSoup read_stl(std::string_view bytes);

/// 1-based line number of byte `offset` of `text`. Cost O(offset); only called on errors.
inline std::int64_t line_of(std::string_view text, std::size_t offset) {
  std::int64_t line = 1;
  if (offset > text.size()) offset = text.size();
  for (std::size_t i = 0; i < offset; ++i) line += text[i] == '\n';
  return line;
}

[[noreturn]] inline void throw_at_line(ErrorKind kind, std::string_view text, const char* at, const std::string& what) {
  const std::int64_t line = line_of(text, static_cast<std::size_t>(at - text.data()));
  throw Error(kind, "line " + std::to_string(line) + ": " + what, {line});
}

[[noreturn]] inline void throw_at_byte(ErrorKind kind, std::size_t offset, const std::string& what) {
  throw Error(kind, "byte " + std::to_string(offset) + ": " + what, {static_cast<std::int64_t>(offset)});
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
inline bool is_space_or_newline(char c) { return is_space(c) || c == '\n'; }

/// A cursor over text. Every method advances p by at least one byte or returns without
/// moving, so loops that stop when nothing is consumed are bounded by the text size.
struct TextCursor {
  std::string_view text;
  const char* p;
  const char* end;

  explicit TextCursor(std::string_view t) : text(t), p(t.data()), end(t.data() + t.size()) {}

  bool at_end() const { return p >= end; }
  /// Skips spaces and tabs (not newlines).
  void skip_inline_space() {
    while (p < end && is_space(*p)) ++p;
  }
  bool at_eol() const { return p >= end || *p == '\n'; }
  /// Moves past the next newline (or to the end).
  void next_line() {
    while (p < end && *p != '\n') ++p;
    if (p < end) ++p;
  }
  /// The token at p (up to whitespace); does not move.
  std::string_view peek_token() const {
    const char* q = p;
    while (q < end && !is_space_or_newline(*q)) ++q;
    return {p, static_cast<std::size_t>(q - p)};
  }
  std::string_view take_token() {
    std::string_view t = peek_token();
    p += t.size();
    return t;
  }
  [[noreturn]] void fail(ErrorKind kind, const std::string& what) const { throw_at_line(kind, text, p, what); }
};

/// Parses a double at [p, end) (an optional '+' is accepted, as in C's strtod; "nan" and
/// "inf" parse and are rejected later by validation). Returns the end of the number, or
/// nullptr if there is no number. Out-of-range magnitudes parse as +-inf or 0 like strtod.
inline const char* parse_double(const char* p, const char* end, double& out) {
  if (p < end && *p == '+') {
    ++p;
    if (p < end && *p == '-') return nullptr;
  }
  auto [q, ec] = std::from_chars(p, end, out);
  if (ec == std::errc::result_out_of_range) {
    // from_chars leaves out unchanged; mimic strtod: overflow -> inf, underflow -> 0.
    bool neg = p < end && *p == '-';
    bool tiny = false;
    for (const char* r = p; r < q; ++r)
      if (*r == 'e' || *r == 'E') {
        tiny = r + 1 < q && r[1] == '-';
        break;
      }
    out = tiny ? (neg ? -0.0 : 0.0) : (neg ? -1.0 : 1.0) * 1e308 * 10.0;
    return q;
  }
  if (ec != std::errc()) return nullptr;
  return q;
}

/// Parses a signed 64-bit integer (optional '+'). nullptr if none or if it overflows.
inline const char* parse_int(const char* p, const char* end, std::int64_t& out) {
  if (p < end && *p == '+') {
    ++p;
    if (p < end && *p == '-') return nullptr;
  }
  auto [q, ec] = std::from_chars(p, end, out);
  if (ec != std::errc()) return nullptr;
  return q;
}

}  // namespace igm::detail
