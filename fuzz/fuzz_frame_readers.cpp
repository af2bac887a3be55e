// libFuzzer entry point: see targets.h and docs/robustness.md.
#include <cstddef>
#include <cstdint>

#include "targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return softsub::fuzz::frameReaders(data, size);
}
