#include "render/image_textures.h"

#include <OpenImageIO/imageio.h>

#include <filesystem>

#include "flowscape/core/files.h"

namespace flowscape {

Vec2 interpolated_uv(const Mesh& mesh, unsigned triangle, double u, double v) {
  if (mesh.uvs.empty()) return Vec2::Zero();
  const Eigen::Vector3i& t = mesh.triangles[triangle];
  return ((1 - u - v) * mesh.uvs[t[0]].cast<double>() + u * mesh.uvs[t[1]].cast<double>() +
          v * mesh.uvs[t[2]].cast<double>());
}

ImageTextures::ImageTextures(const Scene& scene) : scene_(scene) {
  ids_.resize(scene.materials.size());
  for (std::size_t m = 0; m < scene.materials.size(); ++m) {
    const ImageMaps& images = scene.materials[m].images;
    if (!images.base_color.empty()) ids_[m].base_color = open(images.base_color);
    if (!images.metallic_roughness.empty())
      ids_[m].metallic_roughness = open(images.metallic_roughness);
    if (!images.normal.empty()) ids_[m].normal = open(images.normal);
  }
}

ImageTextures::~ImageTextures() {
  if (system_) OIIO::TextureSystem::destroy(system_);
}

int ImageTextures::open(const std::string& path) {
  for (std::size_t k = 0; k < paths_.size(); ++k)
    if (paths_[k] == path) return int(k);
  if (!std::filesystem::is_regular_file(path)) throw FileError(path, "texture file not found");
  if (auto in = OIIO::ImageInput::open(path); !in)
    throw FileError(path, "cannot read texture: " + OIIO::geterror());
  if (!system_) {
    system_ = OIIO::TextureSystem::create(false);
    system_->attribute("automip", 1);            // PNG and JPEG files get their mip-maps in memory
    system_->attribute("unassociatedalpha", 1);  // colours as stored, not multiplied by alpha
  }
  paths_.push_back(path);
  handles_.push_back(system_->get_texture_handle(OIIO::ustring(path)));
  return int(paths_.size()) - 1;
}

bool ImageTextures::try_lookup(int id, const Vec2& uv, double footprint, int channels,
                               float* out) const {
  OIIO::TextureOpt options;
  options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
  options.fill = 1;
  // trilinear mip-mapping (OIIO's default bicubic is a smoothing B-spline, not interpolating)
  options.interpmode = OIIO::TextureOpt::InterpBilinear;
  options.mipmode = OIIO::TextureOpt::MipModeTrilinear;
  const float width = float(footprint);
  return system_->texture(handles_[id], system_->get_perthread_info(), options, float(uv.x()),
                          float(uv.y()), width, 0, 0, width, channels, out);
}

void ImageTextures::lookup(int id, const Vec2& uv, double footprint, int channels,
                           float* out) const {
  if (!try_lookup(id, uv, footprint, channels, out))
    throw FileError(paths_[id], "texture lookup failed: " + system_->geterror());
}

bool ImageTextures::covered(std::uint16_t material_index, const Mesh& mesh, unsigned triangle,
                            float u, float v) const {
  const Material& material = scene_.materials[material_index];
  const int id = ids_[material_index].base_color;
  if (material.images.alpha_cutoff < 0 || id < 0) return true;
  float rgba[4];  // called inside Embree: a failed lookup (reported when shading) covers
  if (!try_lookup(id, interpolated_uv(mesh, triangle, u, v), 0, 4, rgba)) return true;
  return rgba[3] >= material.images.alpha_cutoff;
}

}  // namespace flowscape
