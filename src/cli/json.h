#pragma once
// A small JSON reader and string writer for the CLI (batch results, NAME.cert.json): values as
// a tree, no streaming. Not a library header: the library never reads JSON.
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace igm_cli {

struct Json {
  struct Member;  // a (name, value) pair; defined below, once Json is complete
  enum class Type { Null, Bool, Number, String, Array, Object };
  Type type = Type::Null;
  bool boolean = false;
  double number = 0;
  std::string string;
  std::vector<Json> items;                            // Array
  std::vector<Member> members;                        // Object, in file order

  /// The member `key` of an object (the first one of that name), or nullptr.
  const Json* get(std::string_view key) const;
  /// The number at the path of member names (e.g. {"quality", "quads", "sj_median"}), if any.
  std::optional<double> number_at(std::initializer_list<std::string_view> path) const;
  /// The string member `key`, or "" when absent or not a string.
  std::string string_of(std::string_view key) const;
};

// Not std::pair<std::string, Json>: a pair's members must be complete where the vector above is
// declared (libstdc++ under clang refuses it).
struct Json::Member {
  std::string first;
  Json second;
};

/// Parses one JSON text (RFC 8259; \u escapes to UTF-8, surrogate pairs joined). nullopt when
/// malformed, when anything but whitespace follows the value, or past 64 levels of nesting.
/// Cost O(text).
std::optional<Json> parse_json(std::string_view text);

/// s as a JSON string literal with its quotes: '"', '\\' and control characters escaped, other
/// bytes as they are.
std::string json_quote(std::string_view s);

}  // namespace igm_cli
