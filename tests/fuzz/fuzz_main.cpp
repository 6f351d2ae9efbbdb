// libFuzzer entry point; built once per loader with FOREST_FUZZ_ENTRY naming the
// forest::fuzz function to call (tests/fuzz/CMakeLists.txt).
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FOREST_FUZZ_ENTRY(forest::fuzz::Bytes(data, size));
  return 0;
}
