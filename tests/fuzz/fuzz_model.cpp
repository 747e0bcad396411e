// A user model (glTF through tinygltf, OBJ through assimp): any input is a mesh or one FileError.
// The first byte picks the format; the rest is the file.
#include "flowscape/core/files.h"
#include "flowscape/scenes/model_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".gltf", ".glb", ".obj"};
  const std::filesystem::path file = fuzz_input_file(data + 1, size - 1, kExtensions[data[0] % 3]);
  flowscape::Scene scene;
  try {
    flowscape::load_model(file.string(), flowscape::SemanticClass::Vehicles, 4.0, scene, {});
  } catch (const flowscape::FileError&) {
  }
  return 0;
}
