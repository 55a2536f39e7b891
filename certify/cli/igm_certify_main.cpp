// igm-certify: judge an IGM (triangle OBJ with per-corner UVs) or a quad mesh exactly.
//   igm-certify [--quad] [--genus G] [--json OUT] [--max-witnesses N] FILE
// JSON certificate on stdout (or OUT), one summary line on stderr.
// Exit: 0 valid, 1 invalid, 2 unreadable input or bad arguments.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "certify/certify.h"

namespace {

int usage(const char* msg) {
  std::fprintf(stderr,
               "igm-certify: %s\nusage: igm-certify [--quad] [--genus G] [--json OUT] [--max-witnesses N] FILE\n",
               msg);
  return 2;
}

bool parse_int(const char* s, long long& out) {
  if (!s || !*s) return false;
  char* end = nullptr;
  out = std::strtoll(s, &end, 10);
  return end && *end == '\0';
}

}  // namespace

int main(int argc, char** argv) {
  bool quad = false;
  std::string json_out, file;
  igm::certify::Options opt;
  for (int i = 1; i < argc; ++i) {  // bound: argc
    std::string a = argv[i];
    long long v = 0;
    if (a == "--quad") {
      quad = true;
    } else if (a == "--genus") {
      if (i + 1 >= argc || !parse_int(argv[++i], v) || v < 0) return usage("--genus needs a non-negative integer");
      opt.expected_genus = v;
    } else if (a == "--json") {
      if (i + 1 >= argc) return usage("--json needs a file name");
      json_out = argv[++i];
    } else if (a == "--max-witnesses") {
      if (i + 1 >= argc || !parse_int(argv[++i], v) || v < 0) return usage("--max-witnesses needs a non-negative integer");
      opt.max_witnesses = static_cast<std::size_t>(v);
    } else if (a == "-h" || a == "--help") {
      usage("help");
      return 0;
    } else if (!a.empty() && a[0] == '-' && a != "-") {
      return usage(("unknown option " + a).c_str());
    } else if (file.empty()) {
      file = a;
    } else {
      return usage("only one FILE");
    }
  }
  if (file.empty()) return usage("missing FILE");
  if (opt.expected_genus && !quad) return usage("--genus applies to --quad");
  const igm::certify::Report r =
      quad ? igm::certify::certify_quads_file(file, opt) : igm::certify::certify_igm_file(file, opt);
  const std::string json = igm::certify::to_json(r);
  if (json_out.empty()) {
    std::fwrite(json.data(), 1, json.size(), stdout);
  } else {
    std::ofstream out(json_out, std::ios::binary);
    out << json;
    if (!out) {
      std::fprintf(stderr, "igm-certify: cannot write %s\n", json_out.c_str());
      return 2;
    }
  }
  std::fprintf(stderr, "igm-certify: %s\n", igm::certify::summary(r).c_str());
  return igm::certify::exit_code(r);
}
