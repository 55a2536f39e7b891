// The certifier is independent of the producer: no source under certify/ includes "igm/...".
// (The same rule fails the CMake configure; this test keeps it checked when sources change
// without a re-configure.) The source directory is found from this file's own path.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

TEST_CASE("certify/ sources never include the producer's headers") {
  namespace fs = std::filesystem;
  const fs::path certify_dir = fs::path(__FILE__).parent_path().parent_path().parent_path() / "certify";
  REQUIRE(fs::is_directory(certify_dir));
  const std::regex bad(R"(#\s*include\s*[<"]igm/)");
  const std::regex eigen(R"(#\s*include\s*[<"](Eigen|boost)/)");
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(certify_dir)) {
    const auto ext = e.path().extension();
    if (!e.is_regular_file() || (ext != ".cpp" && ext != ".h")) continue;
    ++files;
    std::ifstream in(e.path());
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      CAPTURE(e.path().string());
      CAPTURE(n);
      CHECK_FALSE(std::regex_search(line, bad));
      CHECK_FALSE(std::regex_search(line, eigen));
    }
  }
  CHECK(files >= 8);
}
