// Wavefront OBJ reader: `v x y z [w | r g b]` and `f` with v, v/vt, v//vn, v/vt/vn corners,
// 1-based or negative (relative) indices, polygons, `#` comments, `\r\n` line ends and
// backslash line continuations (a backslash at the end of a line, spaces, tabs or a CR may
// follow it; a comment runs to the end of its physical line, as in the certifier's reader);
// every other statement (vt, vn, g, o, s, usemtl, l, ...) is ignored. Cost O(bytes).
#include <string>

#include "read_detail.h"

namespace igm::detail {

namespace {

// Skips spaces and backslash-newline continuations inside one logical line (spaces, tabs and
// a CR may stand between the backslash and the newline; a backslash at the very end of the
// file continues into nothing).
void skip_obj_space(TextCursor& c) {
  for (;;) {  // each round consumes at least one byte or returns: bounded by the size
    c.skip_inline_space();
    if (c.p < c.end && *c.p == '\\') {
      const char* q = c.p + 1;
      while (q < c.end && is_space(*q)) ++q;
      if (q == c.end) {
        c.p = q;
        return;
      }
      if (*q == '\n') {
        c.p = q + 1;
        continue;
      }
    }
    return;
  }
}

bool obj_eol(const TextCursor& c) { return c.at_eol() || *c.p == '#'; }

}  // namespace

PolygonSoup read_obj(std::string_view bytes) {
  PolygonSoup soup;
  TextCursor c(bytes);
  std::vector<std::int64_t> face;
  // Each iteration consumes one logical line (at least one byte): bounded by the size.
  while (!c.at_end()) {
    skip_obj_space(c);
    if (obj_eol(c)) {
      c.next_line();
      continue;
    }
    // The keyword ends at a space, a comment or a backslash (a continuation after it).
    const char* key_end = c.p;
    while (key_end < c.end && !is_space_or_newline(*key_end) && *key_end != '#' && *key_end != '\\') ++key_end;
    const std::string_view key(c.p, static_cast<std::size_t>(key_end - c.p));
    c.p = key_end;
    if (key == "v") {
      double xyz[3];
      for (double& x : xyz) {
        skip_obj_space(c);
        const char* q = parse_double(c.p, c.end, x);
        if (!q || (q < c.end && !is_space_or_newline(*q) && *q != '#' && *q != '\\'))
          c.fail(ErrorKind::Parse, "vertex needs three numbers");
        c.p = q;
      }
      soup.positions.push_back({xyz[0], xyz[1], xyz[2]});
    } else if (key == "f") {
      face.clear();
      const auto nv = static_cast<std::int64_t>(soup.positions.size());
      for (;;) {  // one corner per round, each at least one byte
        skip_obj_space(c);
        if (obj_eol(c)) break;
        std::int64_t idx = 0;
        const char* q = parse_int(c.p, c.end, idx);
        if (!q) c.fail(ErrorKind::Parse, "face corner is not an integer vertex index");
        if (idx == 0) c.fail(ErrorKind::Parse, "vertex index 0 (OBJ indices start at 1)");
        c.p = q;
        // Optional /vt, //vn or /vt/vn parts: integers are checked for syntax, then ignored.
        for (int part = 0; part < 2 && c.p < c.end && *c.p == '/'; ++part) {
          ++c.p;
          if (c.p < c.end && (*c.p == '-' || *c.p == '+' || (*c.p >= '0' && *c.p <= '9'))) {
            std::int64_t ignored = 0;
            const char* r = parse_int(c.p, c.end, ignored);
            if (!r) c.fail(ErrorKind::Parse, "bad texture or normal index");
            c.p = r;
          }
        }
        if (c.p < c.end && !is_space_or_newline(*c.p) && *c.p != '#' && *c.p != '\\')
          c.fail(ErrorKind::Parse, "unexpected character in face corner");
        // 1-based -> 0-based; negative indices count back from the last vertex read so far.
        // Out-of-range results are kept and reported by validation.
        face.push_back(idx > 0 ? idx - 1 : nv + idx);
      }
      if (face.size() < 3)
        c.fail(ErrorKind::Parse, "face with " + std::to_string(face.size()) + " corners (at least 3 needed)");
      soup.add_face(face.begin(), face.end());
    }
    // Ignore the rest of the statement (including continuation lines; a comment runs to the
    // end of its physical line, a backslash in it continues nothing).
    for (;;) {  // bounded: consumes bytes up to the end of the logical line
      while (!c.at_eol() && *c.p != '\\' && *c.p != '#') ++c.p;
      if (c.at_end()) break;
      if (*c.p == '\n' || *c.p == '#') {
        c.next_line();
        break;
      }
      const char* before = c.p;
      skip_obj_space(c);
      if (c.p == before) ++c.p;  // a backslash not ending the line
    }
  }
  return soup;
}

}  // namespace igm::detail
