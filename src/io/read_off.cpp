// OFF reader. Header: optional `#` comments and blank lines, then a keyword
// [ST][C][N][n]OFF (texture, colour and normal variants; extra per-vertex values are skipped to
// the end of the line) followed, on the same or later lines, by `V F [E]`; a file that starts
// directly with the counts is accepted too. 4OFF, nOFF with a dimension other than 3 and
// OFF BINARY are rejected as Unsupported. Then V vertices (x y z, extra values to the end of
// the line ignored) and F faces (`k i1 .. ik`, colour values after the indices ignored).
// Cost O(bytes).
#include <string>

#include "read_detail.h"

namespace igm::detail {

namespace {

// Skips whitespace, newlines and `#` comments.
void skip_off_space(TextCursor& c) {
  for (;;) {  // each round consumes at least one byte or returns
    while (c.p < c.end && is_space_or_newline(*c.p)) ++c.p;
    if (c.p < c.end && *c.p == '#') {
      c.next_line();
      continue;
    }
    return;
  }
}

// True if the next non-space character on the current line starts a value (not a comment).
bool more_on_line(TextCursor& c) {
  c.skip_inline_space();
  return !c.at_eol() && *c.p != '#';
}

bool token_end(const TextCursor& c, const char* q) { return q >= c.end || is_space_or_newline(*q) || *q == '#'; }

std::int64_t read_count(TextCursor& c, const char* what) {
  skip_off_space(c);
  if (c.at_end()) c.fail(ErrorKind::Parse, std::string("unexpected end of file: expected the ") + what);
  std::int64_t n = 0;
  const char* q = parse_int(c.p, c.end, n);
  if (!q || !token_end(c, q)) c.fail(ErrorKind::Parse, std::string("expected the ") + what + " (an integer)");
  if (n < 0) c.fail(ErrorKind::Parse, std::string("negative ") + what);
  c.p = q;
  return n;
}

}  // namespace

PolygonSoup read_off(std::string_view bytes) {
  TextCursor c(bytes);
  skip_off_space(c);
  if (c.at_end()) c.fail(ErrorKind::Parse, "empty OFF file");
  const std::string_view key = c.peek_token();
  if (key.size() >= 3 && key.substr(key.size() - 3) == "OFF") {
    std::string_view prefix = key.substr(0, key.size() - 3);
    bool dim_given = false;
    // The prefix letters are ST, C, N, 4, n in this order (each optional).
    if (prefix.substr(0, 2) == "ST") prefix.remove_prefix(2);
    if (!prefix.empty() && prefix.front() == 'C') prefix.remove_prefix(1);
    if (!prefix.empty() && prefix.front() == 'N') prefix.remove_prefix(1);
    if (!prefix.empty() && prefix.front() == '4')
      c.fail(ErrorKind::Unsupported, "4D OFF (" + std::string(key) + ") is not supported");
    if (!prefix.empty() && prefix.front() == 'n') {
      prefix.remove_prefix(1);
      dim_given = true;
    }
    if (!prefix.empty()) c.fail(ErrorKind::Parse, "unknown OFF keyword '" + std::string(key) + "'");
    c.take_token();
    if (more_on_line(c) && c.peek_token() == "BINARY") c.fail(ErrorKind::Unsupported, "binary OFF is not supported");
    if (dim_given) {
      const std::int64_t dim = read_count(c, "dimension");
      if (dim != 3)
        c.fail(ErrorKind::Unsupported, "OFF of dimension " + std::to_string(dim) + " (only 3 is supported)");
    }
  } else if (!(key.size() > 0 && (key[0] >= '0' && key[0] <= '9'))) {
    c.fail(ErrorKind::Parse, "not an OFF file (no OFF keyword)");
  }
  const std::int64_t nv = read_count(c, "vertex count");
  const std::int64_t nf = read_count(c, "face count");
  if (more_on_line(c)) read_count(c, "edge count");  // optional, ignored
  c.next_line();

  // A vertex needs at least 5 bytes ("0 0 0") plus a separator, a face at least 7 ("3 0 1 2")
  // plus a separator: reject counts the remaining bytes cannot hold, before reserving.
  const auto remaining = static_cast<std::int64_t>(c.end - c.p);
  if (nv > remaining / 6 + 1 || nf > remaining / 8 + 1 || nv * 6 + nf * 8 > remaining + 2)
    throw Error(ErrorKind::TooLarge,
                "OFF header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                    " faces but only " + std::to_string(remaining) + " bytes follow (truncated?)",
                {nv, nf});

  PolygonSoup soup;
  soup.positions.reserve(static_cast<std::size_t>(nv));
  soup.face_begin.reserve(static_cast<std::size_t>(nf) + 1);
  soup.corners.reserve(static_cast<std::size_t>(nf) * 3);
  for (std::int64_t i = 0; i < nv; ++i) {  // bounded by nv, itself bounded by the bytes
    double xyz[3];
    for (double& x : xyz) {
      skip_off_space(c);
      if (c.at_end())
        c.fail(ErrorKind::Parse, "unexpected end of file in vertex " + std::to_string(i) + " of " + std::to_string(nv));
      const char* q = parse_double(c.p, c.end, x);
      if (!q || !token_end(c, q)) c.fail(ErrorKind::Parse, "vertex " + std::to_string(i) + ": expected a number");
      c.p = q;
    }
    soup.positions.push_back({xyz[0], xyz[1], xyz[2]});
    c.next_line();  // colours, normals, texture coordinates
  }
  for (std::int64_t f = 0; f < nf; ++f) {  // bounded by nf
    skip_off_space(c);
    if (c.at_end())
      c.fail(ErrorKind::Parse, "unexpected end of file in face " + std::to_string(f) + " of " + std::to_string(nf));
    const std::int64_t k = read_count(c, "face size");
    if (k < 3)
      c.fail(ErrorKind::Parse,
             "face " + std::to_string(f) + " has " + std::to_string(k) + " corners (at least 3 needed)");
    // Nothing is reserved for the k corners: each is pushed after it was parsed, and each
    // parse consumes at least one byte or throws, so the loop ends within the file.
    for (std::int64_t j = 0; j < k; ++j) {
      skip_off_space(c);
      std::int64_t v = 0;
      const char* q = c.at_end() ? nullptr : parse_int(c.p, c.end, v);
      if (!q || !token_end(c, q))
        c.fail(ErrorKind::Parse, "face " + std::to_string(f) + ": expected " + std::to_string(k) + " vertex indices");
      c.p = q;
      soup.corners.push_back(v);
    }
    soup.face_begin.push_back(soup.corners.size());
    c.next_line();  // face colour
  }
  return soup;
}

}  // namespace igm::detail
