#pragma once
// The release's denoisers behind one interface, each made by make_denoiser from its name: the one
// place a denoiser's name is read. "atrous": the edge-avoiding a-trous filter guided by the
// colour's feature layers and the view's ground truth (denoise.h); "oidn": OIDN's trained U-Net on
// colour, albedo and normal (neural_denoise.h; its weights read once per model and process);
// "none": the raw path tracer's colour. docs/renderer.md, "Denoisers".
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "flowscape/renderer/renderer.h"

namespace flowscape {

class Denoiser {
 public:
  virtual ~Denoiser() = default;
  // A view's colour (linear RGB) from its layers, the view's depth and instance ids its guides
  // (a-trous's; the final pass gives no instances, and a depth only where guided_by_depth()).
  virtual Image<float> view(const ColorLayers& layers, const Projection& camera,
                            ImageView<const float> depth,
                            ImageView<const std::uint16_t> instance) const = 0;
  // The six stacked cube faces' colour with their ground truth (render_cube's).
  virtual Image<float> cube(const ColorLayers& layers, const GroundTruth& truth) const = 0;
  // Whether it filters: a denoised frame gathers indirect light on a few samples of a pixel, the
  // raw path tracer's on every one (RenderOptions::indirect_samples).
  virtual bool filters() const { return true; }
  // Whether its guides include the depth: the final pass then averages one over its shutter.
  virtual bool guided_by_depth() const { return false; }
  // What the dataset card says of it.
  virtual std::string description() const = 0;
};

inline const std::vector<std::string> kDenoiserNames = {"atrous", "oidn", "none"};

// The denoiser of a name, `model` the U-Net's size for oidn ("default" or "small"); `temporal`:
// its layers reconstructed over several frames (temporal.h), which a-trous filters less. Throws
// std::invalid_argument for an unknown name or model, or for oidn in a build without the U-Net.
std::unique_ptr<const Denoiser> make_denoiser(const std::string& name,
                                              const std::string& model = "default",
                                              bool temporal = false);

}  // namespace flowscape
