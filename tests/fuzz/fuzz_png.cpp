// A .png through OpenImageIO and our header limits: any input decodes or gives one FileError,
// within the memory limit.
#include "flowscape/core/files.h"
#include "flowscape/formats/image_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    flowscape::read_any_image(fuzz_input_file(data, size, ".png"));
  } catch (const flowscape::FileError&) {
  }
  return 0;
}
