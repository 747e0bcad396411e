#include "flowscape/renderer/denoiser.h"

#include <map>
#include <mutex>
#include <stdexcept>

#include "flowscape/renderer/denoise.h"
#include "flowscape/renderer/neural_denoise.h"

namespace flowscape {
namespace {

class Atrous : public Denoiser {
 public:
  explicit Atrous(bool temporal) {
    // over several frames the indirect light's variance is steady enough to stop at its edges
    // (bench_temporal)
    if (temporal) options_.luminance_tolerance[1] = 4;
  }
  Image<float> view(const ColorLayers& layers, const Projection& camera,
                    ImageView<const float> depth,
                    ImageView<const std::uint16_t> instance) const override {
    return denoise(layers, {&camera, depth, instance}, options_);
  }
  Image<float> cube(const ColorLayers& layers, const GroundTruth& truth) const override {
    return denoise_cube(layers, truth, options_);
  }
  bool guided_by_depth() const override { return true; }
  std::string description() const override {
    return "denoised (a-trous, guided by albedo, normal, depth, instance)";
  }

 private:
  DenoiseOptions options_;
};

// OIDN's U-Net of one size, its weights read once per process however many denoisers use them.
class Oidn : public Denoiser {
 public:
  explicit Oidn(std::string model) : model_(std::move(model)) {}
  Image<float> view(const ColorLayers& layers, const Projection& camera, ImageView<const float>,
                    ImageView<const std::uint16_t>) const override {
    const NeuralFeatures f = neural_features(layers);
    return neural_denoise(unet(), {f.color.view(), f.albedo.view(), f.normal.view(),
                                   autoexposure(f.color.view()), camera.wraps_around()});
  }
  Image<float> cube(const ColorLayers& layers, const GroundTruth&) const override {
    return neural_denoise_cube(unet(), layers);
  }
  std::string description() const override {
    return "denoised by OIDN's trained U-Net (" + model_ +
           " model, HDR colour + albedo + normal; Apache-2.0 weights)";
  }

 private:
  const UNet& unet() const {
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<const UNet>> unets;  // by model size
    const std::lock_guard<std::mutex> lock(mutex);
    std::unique_ptr<const UNet>& unet = unets[model_];
    if (!unet) unet = std::make_unique<const UNet>(read_unet_weights(oidn_weights_file(model_)));
    return *unet;
  }
  std::string model_;
};

class Raw : public Denoiser {
 public:
  Image<float> view(const ColorLayers& layers, const Projection&, ImageView<const float>,
                    ImageView<const std::uint16_t>) const override {
    return raw_color(layers);
  }
  Image<float> cube(const ColorLayers& layers, const GroundTruth&) const override {
    return raw_color(layers);
  }
  bool filters() const override { return false; }
  std::string description() const override { return "not denoised"; }
};

}  // namespace

std::unique_ptr<const Denoiser> make_denoiser(const std::string& name, const std::string& model,
                                              bool temporal) {
  if (model != "default" && model != "small")
    throw std::invalid_argument("denoise_model must be default or small");
  if (name == "atrous") return std::make_unique<const Atrous>(temporal);
  if (name == "none") return std::make_unique<const Raw>();
  if (name != "oidn") throw std::invalid_argument("denoise must be atrous, oidn or none");
  if (!neural_denoiser_built())
    throw std::invalid_argument(
        "denoise oidn needs the neural denoiser, which this build leaves out "
        "(-DFLOWSCAPE_DENOISER=OFF): use atrous or none, or rebuild with it");
  return std::make_unique<const Oidn>(model);
}

}  // namespace flowscape
