// libFuzzer target over the certifier's OBJ reader and all checks (IGM and quad mode) and the
// JSON writer: any bytes must give a report (valid/invalid/unreadable), never a crash or a hang.
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
  opt.expected_genus = 0;
  const igm::certify::Report q = igm::certify::certify_quads_text(text, opt);
  (void)igm::certify::to_json(q);
  return 0;
}
