// The U-Net of a build configured with -DFLOWSCAPE_DENOISER=OFF (no oneDNN): the release config
// refuses --denoise oidn before any rendering (neural_denoiser_built), and a program that makes
// a UNet anyway gets this message.
#include <stdexcept>

#include "flowscape/renderer/neural_denoise.h"

namespace flowscape {

bool neural_denoiser_built() { return false; }

struct UNet::Impl {};

namespace {
[[noreturn]] void absent() {
  throw std::runtime_error(
      "this build has no neural denoiser (configured with -DFLOWSCAPE_DENOISER=OFF): denoise "
      "with atrous or none, or rebuild with oneDNN (libdnnl-dev)");
}
}  // namespace

UNet::UNet(UNetWeights) { absent(); }
UNet::~UNet() = default;
UNet::UNet(UNet&&) noexcept = default;
int UNet::input_channels() const { absent(); }
Image<float> UNet::run(const Image<float>&) const { absent(); }

}  // namespace flowscape
