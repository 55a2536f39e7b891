// The certifier's own OBJ reader (see certify/obj.h).
#include "certify/obj.h"

#include <cstdio>
#include <utility>

#include "certify/exact.h"

namespace igm::certify {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Syntax of a number as parse_exact accepts it, without building it (positions, normals).
bool number_syntax(std::string_view s) {
  std::size_t i = 0, n = s.size();
  if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
  std::size_t d0 = i;
  while (i < n && is_digit(s[i])) ++i;  // bound: n
  std::size_t nint = i - d0;
  if (i < n && s[i] == '/') {
    ++i;
    std::size_t e0 = i;
    bool nonzero = false;
    while (i < n && is_digit(s[i])) nonzero |= s[i++] != '0';  // bound: n
    return nint > 0 && i > e0 && i == n && nonzero;
  }
  std::size_t nfrac = 0;
  if (i < n && s[i] == '.') {
    ++i;
    std::size_t f0 = i;
    while (i < n && is_digit(s[i])) ++i;  // bound: n
    nfrac = i - f0;
  }
  if (nint + nfrac == 0) return false;
  if (i < n && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t e0 = i;
    long e = 0;
    while (i < n && is_digit(s[i])) {  // bound: n
      e = e * 10 + (s[i] - '0');
      if (e > kMaxDecimalExponent) return false;
      ++i;
    }
    if (i == e0) return false;
  }
  return i == n;
}

// Printable, bounded excerpt of a token for messages.
std::string excerpt(std::string_view t) {
  std::string out;
  for (std::size_t i = 0; i < t.size() && i < 32; ++i) {  // bound: 32
    unsigned char c = static_cast<unsigned char>(t[i]);
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  if (t.size() > 32) out += "...";
  return out;
}

// Splits a line (comment already removed) into whitespace-separated tokens.
void tokenize(std::string_view line, std::vector<std::string_view>& toks) {
  toks.clear();
  std::size_t i = 0, n = line.size();
  while (i < n) {  // bound: n
    while (i < n && is_space(line[i])) ++i;
    if (i >= n) break;
    std::size_t b = i;
    while (i < n && !is_space(line[i])) ++i;
    toks.push_back(line.substr(b, i - b));
  }
}

// Parses a signed OBJ index (non-zero, |i| < 2^31). Returns false on bad syntax.
bool parse_index(std::string_view s, std::int64_t& out) {
  std::size_t i = 0, n = s.size();
  bool neg = false;
  if (i < n && (s[i] == '+' || s[i] == '-')) {
    neg = s[i] == '-';
    ++i;
  }
  if (i == n) return false;
  std::int64_t v = 0;
  for (; i < n; ++i) {  // bound: n
    if (!is_digit(s[i])) return false;
    v = v * 10 + (s[i] - '0');
    if (v >= (std::int64_t(1) << 31)) return false;
  }
  if (v == 0) return false;
  out = neg ? -v : v;
  return true;
}

// A line that ends with a backslash (spaces, tabs or a CR may follow it) continues on the next
// one: drops the backslash and what follows it and returns true. Comments are cut first, so a
// backslash inside a comment continues nothing.
bool drop_continuation(std::string_view& line) {
  std::size_t n = line.size();
  while (n > 0 && is_space(line[n - 1])) --n;  // bound: the line's length
  if (n == 0 || line[n - 1] != '\\') return false;
  line = line.substr(0, n - 1);
  return true;
}

struct Fail {
  std::int64_t line;
  std::string msg;
};

}  // namespace

ObjReadResult read_obj(std::string_view text) {
  ObjReadResult res;
  ObjMesh& m = res.mesh;
  m.face_begin.push_back(0);
  {
    // Reserve the vt array (mpq_class has no noexcept move: a growing vector would copy every
    // rational). Count lines starting with "vt": proportional to the text, not to a declared size.
    std::size_t nvt = 0;
    for (std::size_t p = 0; p + 2 < text.size();) {  // bound: text.size()
      std::size_t q = p;
      while (q < text.size() && is_space(text[q])) ++q;
      if (q + 2 < text.size() && text[q] == 'v' && text[q + 1] == 't' && is_space(text[q + 2])) ++nvt;
      const std::size_t e = text.find('\n', q);
      if (e == std::string_view::npos) break;
      p = e + 1;
    }
    m.uv.reserve(nvt);
  }
  std::int64_t num_vn = 0;
  std::vector<std::pair<std::int64_t, std::int64_t>> corner_vn;  // (normal id, line): range-checked
  std::vector<std::string_view> toks;
  std::int64_t line_no = 0;
  std::size_t pos = 0;
  auto fail = [&](std::int64_t line, const std::string& msg) {
    res.ok = false;
    res.error_line = line;
    res.error = "line " + std::to_string(line) + ": " + msg;
    res.mesh = ObjMesh{};
    return res;
  };
  // Resolves an OBJ index against `count` elements defined so far; positive indices are checked
  // against the final count later (forward references are allowed).
  auto resolve = [](std::int64_t idx, std::int64_t count, std::int64_t& out) {
    if (idx < 0) {
      out = count + idx;
      return out >= 0;
    }
    out = idx - 1;
    return true;
  };
  // The next physical line without its comment; advances pos and line_no.
  auto next_line = [&]() {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    return line;
  };
  std::string joined;  // a statement continued over several lines
  while (pos < text.size()) {  // bound: text.size(), every pass consumes >= 1 byte
    std::string_view line = next_line();
    const std::int64_t stmt_line = line_no;  // errors name the statement's first line
    if (drop_continuation(line)) {
      joined.assign(line);
      for (bool more = true; more && pos < text.size();) {  // bound: one physical line per round
        std::string_view next = next_line();
        more = drop_continuation(next);
        joined.push_back(' ');
        joined.append(next);
      }
      line = joined;
    }
    tokenize(line, toks);
    if (toks.empty()) continue;
    const std::string_view kw = toks[0];
    const std::size_t nargs = toks.size() - 1;
    if (kw == "v") {
      if (nargs < 3 || nargs > 7) return fail(stmt_line, "'v' needs 3 to 7 numbers, found " + std::to_string(nargs));
      for (std::size_t i = 1; i < toks.size(); ++i)
        if (!number_syntax(toks[i])) return fail(stmt_line, "not a finite number: '" + excerpt(toks[i]) + "'");
      ++m.num_vertices;
    } else if (kw == "vt") {
      if (nargs < 2 || nargs > 3)
        return fail(stmt_line, "'vt' needs 2 or 3 numbers (u v [w]), found " + std::to_string(nargs));
      std::array<mpq_class, 2> uv;
      for (int k = 0; k < 2; ++k)
        if (!parse_exact(toks[1 + k], uv[k]))
          return fail(stmt_line, "not an exact number (decimal or p/q): '" + excerpt(toks[1 + k]) + "'");
      if (nargs == 3 && !number_syntax(toks[3]))
        return fail(stmt_line, "not a finite number: '" + excerpt(toks[3]) + "'");
      m.uv.push_back(std::move(uv));
    } else if (kw == "vn") {
      if (nargs != 3) return fail(stmt_line, "'vn' needs 3 numbers, found " + std::to_string(nargs));
      for (std::size_t i = 1; i < toks.size(); ++i)
        if (!number_syntax(toks[i])) return fail(stmt_line, "not a finite number: '" + excerpt(toks[i]) + "'");
      ++num_vn;
    } else if (kw == "vp") {
      if (nargs < 1 || nargs > 3) return fail(stmt_line, "'vp' needs 1 to 3 numbers");
      for (std::size_t i = 1; i < toks.size(); ++i)
        if (!number_syntax(toks[i])) return fail(stmt_line, "not a finite number: '" + excerpt(toks[i]) + "'");
    } else if (kw == "f") {
      if (nargs < 3) return fail(stmt_line, "a face needs at least 3 corners, found " + std::to_string(nargs));
      for (std::size_t i = 1; i < toks.size(); ++i) {
        std::string_view t = toks[i];
        std::string_view parts[3];
        int np = 0;
        std::size_t b = 0;
        for (std::size_t j = 0; j <= t.size(); ++j) {  // bound: token length
          if (j == t.size() || t[j] == '/') {
            if (np == 3) return fail(stmt_line, "bad face corner '" + excerpt(t) + "'");
            parts[np++] = t.substr(b, j - b);
            b = j + 1;
          }
        }
        std::int64_t idx, r;
        if (!parse_index(parts[0], idx) || !resolve(idx, m.num_vertices, r))
          return fail(stmt_line, "bad vertex index in '" + excerpt(t) + "'");
        m.corner_vertex.push_back(static_cast<int>(r));
        if (np >= 2 && !parts[1].empty()) {
          if (!parse_index(parts[1], idx) || !resolve(idx, std::int64_t(m.uv.size()), r))
            return fail(stmt_line, "bad texture index in '" + excerpt(t) + "'");
          m.corner_uv.push_back(static_cast<int>(r));
        } else if (np == 2) {
          return fail(stmt_line, "empty texture index in '" + excerpt(t) + "'");
        } else {
          m.corner_uv.push_back(-1);
        }
        if (np == 3) {
          if (!parse_index(parts[2], idx) || !resolve(idx, num_vn, r))
            return fail(stmt_line, "bad normal index in '" + excerpt(t) + "'");
          corner_vn.emplace_back(r, stmt_line);
        }
      }
      m.face_begin.push_back(std::int64_t(m.corner_vertex.size()));
      m.face_line.push_back(stmt_line);
    } else if (kw == "o" || kw == "g" || kw == "s" || kw == "usemtl" || kw == "mtllib") {
      // grouping and material statements: no geometry, ignored
    } else {
      return fail(stmt_line, "unknown statement '" + excerpt(kw) + "'");
    }
  }
  // Positive indices may refer forward: check them against the final counts.
  const std::int64_t nuv = std::int64_t(m.uv.size());
  for (std::int64_t f = 0; f < m.num_faces(); ++f) {  // bound: F faces, their corners
    for (std::int64_t c = m.face_begin[f]; c < m.face_begin[f + 1]; ++c) {
      if (m.corner_vertex[c] >= m.num_vertices)
        return fail(m.face_line[f], "vertex index " + std::to_string(m.corner_vertex[c] + 1) +
                                        " out of range (" + std::to_string(m.num_vertices) + " vertices)");
      if (m.corner_uv[c] >= nuv)
        return fail(m.face_line[f], "texture index " + std::to_string(m.corner_uv[c] + 1) +
                                        " out of range (" + std::to_string(nuv) + " vt)");
    }
  }
  for (const auto& [r, line] : corner_vn)
    if (r >= num_vn)
      return fail(line, "normal index " + std::to_string(r + 1) + " out of range (" + std::to_string(num_vn) + " vn)");
  res.ok = true;
  return res;
}

}  // namespace igm::certify
