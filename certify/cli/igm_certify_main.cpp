// igm-certify: judge an IGM (triangle OBJ with per-corner UVs) or a quad mesh exactly.
//   igm-certify [--quad] [--genus G] [--boundary] [--components] [--boundary-loops B]
//               [--component G:B]... [--features FEATURES] [--json OUT] [--max-witnesses N] FILE
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
               "igm-certify: %s\n"
               "usage: igm-certify [--quad] [--genus G] [--boundary] [--components]\n"
               "                   [--boundary-loops B] [--component G:B]... [--json OUT]\n"
               "                   [--features FEATURES] [--max-witnesses N] FILE\n"
               "  --boundary         accept boundary edges (open surfaces)\n"
               "  --features F       every feature edge listed in F (lines \"i j\", 0-based vertex\n"
               "                     ids of FILE; '#' lines ignored) must lie on an integer\n"
               "                     isoline of every face's chart containing it\n"
               "  --components       accept several connected components\n"
               "  --genus G          (--quad) the total genus must be G\n"
               "  --boundary-loops B (--quad) the total number of boundary loops must be B\n"
               "  --component G:B    (--quad, repeatable) the components' (genus, loops) must be\n"
               "                     these, in any order\n",
               msg);
  return 2;
}

bool parse_int(const char* s, long long& out) {
  if (!s || !*s) return false;
  char* end = nullptr;
  out = std::strtoll(s, &end, 10);
  return end && *end == '\0';
}

// "G:B" with non-negative integers.
bool parse_component(const char* s, igm::certify::ComponentTopology& out) {
  if (!s) return false;
  const std::string a = s;
  const std::size_t colon = a.find(':');
  long long g = 0, b = 0;
  if (colon == std::string::npos || !parse_int(a.substr(0, colon).c_str(), g) ||
      !parse_int(a.substr(colon + 1).c_str(), b) || g < 0 || b < 0)
    return false;
  out = {g, b};
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  bool quad = false;
  std::string json_out, file, features;
  igm::certify::Options opt;
  for (int i = 1; i < argc; ++i) {  // bound: argc
    std::string a = argv[i];
    long long v = 0;
    if (a == "--quad") {
      quad = true;
    } else if (a == "--genus") {
      if (i + 1 >= argc || !parse_int(argv[++i], v) || v < 0) return usage("--genus needs a non-negative integer");
      opt.expected_genus = v;
    } else if (a == "--boundary") {
      opt.allow_boundary = true;
    } else if (a == "--components") {
      opt.allow_components = true;
    } else if (a == "--boundary-loops") {
      if (i + 1 >= argc || !parse_int(argv[++i], v) || v < 0)
        return usage("--boundary-loops needs a non-negative integer");
      opt.expected_boundary_loops = v;
    } else if (a == "--component") {
      igm::certify::ComponentTopology c;
      if (i + 1 >= argc || !parse_component(argv[++i], c))
        return usage("--component needs GENUS:LOOPS (non-negative integers)");
      opt.expected_components.push_back(c);
    } else if (a == "--features") {
      if (i + 1 >= argc) return usage("--features needs a file name");
      features = argv[++i];
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
  if ((opt.expected_boundary_loops || !opt.expected_components.empty()) && !quad)
    return usage("--boundary-loops and --component apply to --quad");
  bool loops_expected = opt.expected_boundary_loops.value_or(0) > 0;
  for (const auto& c : opt.expected_components) loops_expected |= c.boundary_loops > 0;
  if (loops_expected && !opt.allow_boundary)
    return usage("boundary loops expected: add --boundary");
  if (opt.expected_components.size() > 1 && !opt.allow_components)
    return usage("several --component expected: add --components");
  if (!features.empty() && quad) return usage("--features applies to IGMs, not to --quad");
  igm::certify::Report r;
  if (!features.empty()) {
    igm::certify::FeatureReadResult fr = igm::certify::read_feature_edges_file(features);
    if (fr.ok) {
      opt.feature_edges = std::move(fr.edges);
    } else {  // unreadable (exit 2); the message names the features file and its line
      r.source = file;
      r.error = "features file '" + features + "': " + fr.error;
    }
  }
  if (r.error.empty())
    r = quad ? igm::certify::certify_quads_file(file, opt) : igm::certify::certify_igm_file(file, opt);
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
