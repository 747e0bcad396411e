// Middlebury .flo from bytes: any input is a Flow or one FileError.
#include <string_view>

#include "flowscape/core/files.h"
#include "flowscape/formats/flow_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    flowscape::parse_flo("fuzz.flo", {reinterpret_cast<const char*>(data), size});
  } catch (const flowscape::FileError&) {
  }
  return 0;
}
