// libFuzzer target: the OFF reader, then inspect and validate (see read_fuzz_common.h).
#include "read_fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_read_mesh(data, size, igm::MeshFormat::Off);
}
