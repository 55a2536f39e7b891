#pragma once
// Small file helpers for the certifier's CLI tests (cli_test.cpp, features_test.cpp).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace certify_test {

inline void write(const std::filesystem::path& p, const std::string& text) {
  std::ofstream o(p, std::ios::binary);
  o << text;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream i(p, std::ios::binary);
  std::stringstream s;
  s << i.rdbuf();
  return s.str();
}

}  // namespace certify_test
