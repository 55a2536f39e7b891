// libFuzzer target over the certifier's OBJ reader and all checks (IGM and quad mode) and the
// JSON writer: any bytes must give a report (valid/invalid/unreadable), never a crash or a hang.
// Past a line "#features" the rest is also read as a features file (read_feature_edges) and, when
// it parses, checked on the IGM before it (Options::feature_edges; check 6).
#include <cstddef>
#include <cstdint>
#include <string>

#include "certify/certify.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (1u << 16)) return 0;  // keep single runs short; the reader is linear in the size
  const std::string text(reinterpret_cast<const char*>(data), size);
  igm::certify::Options opt;
  opt.max_witnesses = 3;
  const igm::certify::Report r = igm::certify::certify_igm_text(text, opt);
  const std::string j = igm::certify::to_json(r);
  if (j.empty() || (r.verdict == igm::certify::Verdict::Valid && !r.genus)) __builtin_trap();
  // Open surfaces and components: a closed, connected valid IGM stays valid; a valid open one
  // has its loops and genus.
  igm::certify::Options open_opt = opt;
  open_opt.allow_boundary = open_opt.allow_components = true;
  const igm::certify::Report o = igm::certify::certify_igm_text(text, open_opt);
  if (r.valid() && !o.valid()) __builtin_trap();
  if (o.valid() && (!o.genus || !o.boundary_loops)) __builtin_trap();
  (void)igm::certify::to_json(o);
  opt.expected_genus = 0;
  const igm::certify::Report q = igm::certify::certify_quads_text(text, opt);
  (void)igm::certify::to_json(q);
  open_opt.expected_boundary_loops = 1;
  open_opt.expected_components = {{0, 1}, {1, 0}};
  (void)igm::certify::to_json(igm::certify::certify_quads_text(text, open_opt));
  // The features file after "#features": parsed alone, then checked on the IGM before it.
  const std::size_t mark = text.find("\n#features\n");
  const igm::certify::FeatureReadResult f =
      igm::certify::read_feature_edges(mark == std::string::npos ? text : text.substr(mark + 11));
  if (f.ok != f.error.empty()) __builtin_trap();
  if (f.ok && mark != std::string::npos) {
    const std::string igm_text = text.substr(0, mark + 1);
    igm::certify::Options fo = opt;
    fo.feature_edges = f.edges;
    const igm::certify::Report r6 = igm::certify::certify_igm_text(igm_text, fo);
    if (r6.verdict != igm::certify::Verdict::Unreadable && !r6.features) __builtin_trap();
    // The features check only adds a condition: valid with it implies valid without it.
    if (r6.valid() && !igm::certify::certify_igm_text(igm_text, opt).valid()) __builtin_trap();
    (void)igm::certify::to_json(r6);
  }
  return 0;
}
