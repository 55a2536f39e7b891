#include "json.h"

#include <charconv>
#include <cstdio>

namespace igm_cli {

namespace {

constexpr int kMaxDepth = 64;

struct Parser {
  std::string_view s;
  std::size_t i = 0;

  void space() {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) ++i;
  }
  // Moves past `ch` if it is next.
  bool close(char ch) {
    if (i >= s.size() || s[i] != ch) return false;
    ++i;
    return true;
  }
  // Comma-separated elements up to `bracket` (the opening one consumed), each parsed by one().
  template <class One>
  bool elements(char bracket, One&& one) {
    space();
    if (close(bracket)) return true;
    for (;;) {  // bound: one element per round, each at least one byte of the text
      if (!one()) return false;
      space();
      if (!close(',')) return close(bracket);
    }
  }
  bool literal(std::string_view word) {
    if (s.substr(i, word.size()) != word) return false;
    i += word.size();
    return true;
  }
  static void put_utf8(std::string& out, unsigned cp) {
    if (cp < 0x80) {
      out.push_back(static_cast<char>(cp));
    } else if (cp < 0x800) {
      out.push_back(static_cast<char>(0xc0 | (cp >> 6)));
      out.push_back(static_cast<char>(0x80 | (cp & 0x3f)));
    } else if (cp < 0x10000) {
      out.push_back(static_cast<char>(0xe0 | (cp >> 12)));
      out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3f)));
      out.push_back(static_cast<char>(0x80 | (cp & 0x3f)));
    } else {
      out.push_back(static_cast<char>(0xf0 | (cp >> 18)));
      out.push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3f)));
      out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3f)));
      out.push_back(static_cast<char>(0x80 | (cp & 0x3f)));
    }
  }
  bool hex4(unsigned& out) {
    if (i + 4 > s.size()) return false;
    out = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s[i++];
      out <<= 4;
      if (c >= '0' && c <= '9') out |= static_cast<unsigned>(c - '0');
      else if (c >= 'a' && c <= 'f') out |= static_cast<unsigned>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') out |= static_cast<unsigned>(c - 'A' + 10);
      else return false;
    }
    return true;
  }
  bool string(std::string& out) {
    if (i >= s.size() || s[i] != '"') return false;
    ++i;
    while (i < s.size()) {  // bound: the text, one byte or escape per round
      const char c = s[i++];
      if (c == '"') return true;
      if (static_cast<unsigned char>(c) < 0x20) return false;
      if (c != '\\') {
        out.push_back(c);
        continue;
      }
      if (i >= s.size()) return false;
      const char e = s[i++];
      switch (e) {
        case '"': out.push_back('"'); break;
        case '\\': out.push_back('\\'); break;
        case '/': out.push_back('/'); break;
        case 'b': out.push_back('\b'); break;
        case 'f': out.push_back('\f'); break;
        case 'n': out.push_back('\n'); break;
        case 'r': out.push_back('\r'); break;
        case 't': out.push_back('\t'); break;
        case 'u': {
          unsigned cp = 0;
          if (!hex4(cp)) return false;
          if (cp >= 0xd800 && cp < 0xdc00 && s.substr(i, 2) == "\\u") {
            i += 2;
            unsigned lo = 0;
            if (!hex4(lo) || lo < 0xdc00 || lo >= 0xe000) return false;
            cp = 0x10000 + ((cp - 0xd800) << 10) + (lo - 0xdc00);
          }
          put_utf8(out, cp);
          break;
        }
        default:
          return false;
      }
    }
    return false;
  }
  bool number(double& out) {
    const std::size_t b = i;
    if (i < s.size() && s[i] == '-') ++i;
    while (i < s.size() && ((s[i] >= '0' && s[i] <= '9') || s[i] == '.' || s[i] == 'e' || s[i] == 'E' ||
                            s[i] == '+' || s[i] == '-'))
      ++i;
    const auto [p, ec] = std::from_chars(s.data() + b, s.data() + i, out);
    return ec == std::errc() && p == s.data() + i && i > b;
  }
  bool value(Json& v, int depth) {
    if (depth > kMaxDepth) return false;
    space();
    if (i >= s.size()) return false;
    const char c = s[i];
    if (c == '{') {
      v.type = Json::Type::Object;
      ++i;
      return elements('}', [&] {
        std::string key;
        space();
        if (!string(key)) return false;
        space();
        if (!close(':')) return false;
        Json member;
        if (!value(member, depth + 1)) return false;
        v.members.push_back({std::move(key), std::move(member)});
        return true;
      });
    }
    if (c == '[') {
      v.type = Json::Type::Array;
      ++i;
      return elements(']', [&] {
        Json item;
        if (!value(item, depth + 1)) return false;
        v.items.push_back(std::move(item));
        return true;
      });
    }
    if (c == '"') {
      v.type = Json::Type::String;
      return string(v.string);
    }
    if (literal("true") || literal("false")) {
      v.type = Json::Type::Bool;
      v.boolean = c == 't';
      return true;
    }
    if (literal("null")) return true;  // v.type is Null already
    v.type = Json::Type::Number;
    return number(v.number);
  }
};

}  // namespace

const Json* Json::get(std::string_view key) const {
  for (const auto& [k, v] : members)
    if (k == key) return &v;
  return nullptr;
}

std::optional<double> Json::number_at(std::initializer_list<std::string_view> path) const {
  const Json* v = this;
  for (std::string_view key : path)
    if (!(v = v->get(key))) return std::nullopt;
  if (v->type != Type::Number) return std::nullopt;
  return v->number;
}

std::string Json::string_of(std::string_view key) const {
  const Json* v = get(key);
  return v && v->type == Type::String ? v->string : std::string();
}

std::optional<Json> parse_json(std::string_view text) {
  Parser p{text};
  Json v;
  if (!p.value(v, 0)) return std::nullopt;
  p.space();
  if (p.i != text.size()) return std::nullopt;
  return v;
}

std::string json_quote(std::string_view s) {
  std::string out = "\"";
  for (const char ch : s) {  // bound: |s|
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out.push_back('\\');
      out.push_back(ch);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out.push_back(ch);
    }
  }
  return out + "\"";
}

}  // namespace igm_cli
