// The features file (certify/README.md, "Feature edges"): one feature edge per line as two 0-based
// vertex ids "i j"; blank lines and '#' lines ignored. The check itself is in igm.cpp.
#include <cstdint>
#include <string>

#include "certify/certify.h"
#include "internal.h"

namespace igm::certify {

namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

// A 0-based vertex id: decimal digits only, at most 2^31 - 1 (the OBJ reader's vertex ids are int).
bool parse_id(const std::string& s, std::size_t& i, std::int64_t& out) {
  const std::size_t begin = i;
  out = 0;
  while (i < s.size() && s[i] >= '0' && s[i] <= '9') {  // bound: |s|
    out = out * 10 + (s[i] - '0');
    if (out > 2147483647) return false;
    ++i;
  }
  return i > begin;
}

}  // namespace

FeatureReadResult read_feature_edges(const std::string& text) {
  FeatureReadResult r;
  std::int64_t line = 0;
  for (std::size_t pos = 0; pos < text.size();) {  // bound: |text|, each line consumed once
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string s = text.substr(pos, end - pos);
    pos = end + 1;
    ++line;
    if (!s.empty() && s.back() == '\r') s.pop_back();
    std::size_t i = 0;
    while (i < s.size() && blank(s[i])) ++i;  // bound: |s|
    if (i == s.size() || s[i] == '#') continue;
    FeatureEdge e;
    e.line = line;
    bool ok = parse_id(s, i, e.a) && i < s.size() && blank(s[i]);
    while (ok && i < s.size() && blank(s[i])) ++i;  // bound: |s|
    ok = ok && parse_id(s, i, e.b);
    while (ok && i < s.size() && blank(s[i])) ++i;  // bound: |s|
    if (!ok || i != s.size()) {
      const std::string shown = s.size() > 60 ? s.substr(0, 60) + "..." : s;
      r.error = "line " + std::to_string(line) + ": expected two vertex ids \"i j\" (0-based), got \"" + shown + "\"";
      r.error_line = line;
      r.edges.clear();
      return r;
    }
    r.edges.push_back(e);
  }
  r.ok = true;
  return r;
}

FeatureReadResult read_feature_edges_file(const std::string& path) {
  bool ok = false;
  const std::string text = detail::read_file(path, ok);
  if (!ok) {
    FeatureReadResult r;
    r.error = "cannot read file '" + path + "'";
    return r;
  }
  return read_feature_edges(text);
}

}  // namespace igm::certify
