#pragma once
// Internal: the image files of a scene's materials, looked up through OpenImageIO's TextureSystem
// (mip-mapped on the fly, filtered over the footprint, repeating like glTF's default wrap), and the
// alpha masks they define.
#include <OpenImageIO/texture.h>

#include <vector>

#include "flowscape/scenes/scene.h"
#include "render/embree_scene.h"

namespace flowscape {

class ImageTextures : public CoverageTest {
 public:
  // Opens every image a material names; a file that cannot be read is a FileError naming it.
  explicit ImageTextures(const Scene& scene);
  ~ImageTextures() override;
  ImageTextures(const ImageTextures&) = delete;
  ImageTextures& operator=(const ImageTextures&) = delete;

  // Texture ids of a material's images (-1: none).
  struct Ids {
    int base_color = -1, metallic_roughness = -1, normal = -1;
  };
  const Ids& of(std::size_t material) const { return ids_[material]; }
  // `channels` channels of texture `id` at uv, filtered over a square `footprint` uv units wide;
  // channels the file lacks read 1. Throws FileError when the file fails.
  void lookup(int id, const Vec2& uv, double footprint, int channels, float* out) const;
  const std::string& path(int id) const { return paths_[id]; }

  // Alpha masks: the base colour's alpha at the hit against the material's cutoff.
  bool covered(std::uint16_t material, const Mesh& mesh, unsigned triangle, float u,
               float v) const override;

 private:
  int open(const std::string& path);
  bool try_lookup(int id, const Vec2& uv, double footprint, int channels, float* out) const;

  const Scene& scene_;
  OIIO::TextureSystem* system_ = nullptr;
  std::vector<std::string> paths_;
  std::vector<OIIO::TextureSystem::TextureHandle*> handles_;
  std::vector<Ids> ids_;  // per material
};

// Texture coordinates at barycentric (u, v) of a triangle (0 when the mesh has none).
Vec2 interpolated_uv(const Mesh& mesh, unsigned triangle, double u, double v);

}  // namespace flowscape
