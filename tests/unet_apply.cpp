// Test fixture for tests/python/test_unet.py: denoises colour, albedo and normal EXRs with the
// U-Net of a TZA file as a release does (renderer/neural_denoise.h) and writes the result and the
// autoexposure, so that an independent PyTorch U-Net can be set against it.
// Usage: unet_apply WEIGHTS.tza COLOR.exr ALBEDO.exr NORMAL.exr OUT.exr [--wrap] [--threads=N]
#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

#include "flowscape/formats/image_io.h"
#include "flowscape/renderer/neural_denoise.h"

using namespace flowscape;

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(
        stderr, "usage: unet_apply WEIGHTS.tza COLOR.exr ALBEDO.exr NORMAL.exr OUT.exr [--wrap]\n");
    return 2;
  }
  try {
    const UNet unet(read_unet_weights(argv[1]));
    const Image<float> color = read_image<float>(argv[2]), albedo = read_image<float>(argv[3]),
                       normal = read_image<float>(argv[4]);
    const double exposure = autoexposure(color.view());
    bool wrap = false;
    std::optional<tbb::global_control> threads;
    for (int k = 6; k < argc; ++k) {
      if (std::strcmp(argv[k], "--wrap") == 0) wrap = true;
      if (std::strncmp(argv[k], "--threads=", 10) == 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism, std::atoi(argv[k] + 10));
    }
    write_image(argv[5],
                neural_denoise(unet, {color.view(), albedo.view(), normal.view(), exposure, wrap}));
    std::printf("%.17g\n", exposure);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "unet_apply: error: %s\n", e.what());
    return 1;
  }
}
