// An OpenEXR file through OpenImageIO and our header limits, as an image and as flow: any input
// decodes or gives one FileError, within the memory limit.
#include "flowscape/core/files.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = fuzz_input_file(data, size, ".exr");
  try {
    flowscape::read_any_image(file);
  } catch (const flowscape::FileError&) {
  }
  try {
    flowscape::read_flow_exr(file);
  } catch (const flowscape::FileError&) {
  }
  return 0;
}
