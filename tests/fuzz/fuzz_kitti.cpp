// A KITTI flow PNG (16-bit RGB: u, v, valid): any input is a Flow or one FileError.
#include "flowscape/core/files.h"
#include "flowscape/formats/flow_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    flowscape::read_kitti_png(fuzz_input_file(data, size, ".png"));
  } catch (const flowscape::FileError&) {
  }
  return 0;
}
