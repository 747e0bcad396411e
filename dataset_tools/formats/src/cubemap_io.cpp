#include "flowscape/formats/cubemap_io.h"

#include <algorithm>
#include <array>

#include "flowscape/stitcher/stitch.h"

namespace flowscape {
namespace {

template <class T>
Image<T> stack_faces(const std::array<Image<T>, 6>& faces, const std::filesystem::path& cube_dir,
                     const std::string& modality, const std::string& file_name) {
  const Image<T>& front = faces[0];
  if (front.width != front.height)
    throw FileError(cube_file(cube_dir, Face::Front, modality, file_name),
                    "cube face is " + std::to_string(front.width) + "x" +
                        std::to_string(front.height) + ", faces must be square");
  Image<T> stack(front.width, 6 * front.width, front.channels);
  for (Face face : kFaces) {
    const Image<T>& image = faces[int(face)];
    if (image.width != front.width || image.height != front.height ||
        image.channels != front.channels)
      throw FileError(cube_file(cube_dir, face, modality, file_name),
                      "face size or channels differ from the front face");
    std::copy(image.data.begin(), image.data.end(), face_view(stack.view(), face).data);
  }
  return stack;
}

// The six faces, reading every face but the front, which the caller may have read already.
template <class T>
Image<T> read_cube_typed(const std::filesystem::path& cube_dir, const std::string& modality,
                         const std::string& file_name, Image<T> front = {}) {
  std::array<Image<T>, 6> faces;
  faces[0] = front.data.empty()
                 ? read_image<T>(cube_file(cube_dir, Face::Front, modality, file_name))
                 : std::move(front);
  for (Face face : kFaces)
    if (face != Face::Front)
      faces[int(face)] = read_image<T>(cube_file(cube_dir, face, modality, file_name));
  return stack_faces(faces, cube_dir, modality, file_name);
}

}  // namespace

std::filesystem::path cube_file(const std::filesystem::path& cube_dir, Face face,
                                const std::string& modality, const std::string& file_name) {
  return cube_dir / std::string(face_name(face)) / modality / file_name;
}

AnyImage read_cube_image(const std::filesystem::path& cube_dir, const std::string& modality,
                         const std::string& file_name) {
  AnyImage front = read_any_image(cube_file(cube_dir, Face::Front, modality, file_name));
  return std::visit(
      [&](auto& image) -> AnyImage {
        using T = typename std::decay_t<decltype(image)>::value_type;
        return read_cube_typed<T>(cube_dir, modality, file_name, std::move(image));
      },
      front);
}

template <class T>
Image<T> read_cube_image_as(const std::filesystem::path& cube_dir, const std::string& modality,
                            const std::string& file_name) {
  return read_cube_typed<T>(cube_dir, modality, file_name);
}

Flow read_cube_flow(const std::filesystem::path& cube_dir, const std::string& modality,
                    const std::string& file_name) {
  std::array<Image<float>, 6> uv;
  std::array<Image<std::uint8_t>, 6> valid;
  for (Face face : kFaces) {
    Flow flow = read_flow(cube_file(cube_dir, face, modality, file_name));
    uv[int(face)] = std::move(flow.uv);
    valid[int(face)] = std::move(flow.valid);
  }
  return {stack_faces(uv, cube_dir, modality, file_name),
          stack_faces(valid, cube_dir, modality, file_name)};
}

template <class T>
void write_cube_image(const std::filesystem::path& cube_dir, const std::string& modality,
                      const std::string& file_name, ImageView<const T> stack) {
  for (Face face : kFaces)
    write_image(cube_file(cube_dir, face, modality, file_name), face_view(stack, face));
}

void write_cube_flow(const std::filesystem::path& cube_dir, const std::string& modality,
                     const std::string& file_name, ImageView<const float> stack) {
  for (Face face : kFaces)
    write_flow(cube_file(cube_dir, face, modality, file_name), face_view(stack, face));
}

std::vector<std::string> cube_frame_files(const std::filesystem::path& cube_dir,
                                          const std::string& modality) {
  std::vector<std::string> names;
  const std::filesystem::path folder = cube_dir / "front" / modality;
  if (!std::filesystem::is_directory(folder)) return names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && !name.starts_with(".")) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

#define FLOWSCAPE_CUBE_IO(T)                                                             \
  template Image<T> read_cube_image_as(const std::filesystem::path&, const std::string&, \
                                       const std::string&);                              \
  template void write_cube_image(const std::filesystem::path&, const std::string&,       \
                                 const std::string&, ImageView<const T>);
FLOWSCAPE_CUBE_IO(std::uint8_t)
FLOWSCAPE_CUBE_IO(std::uint16_t)
FLOWSCAPE_CUBE_IO(float)
#undef FLOWSCAPE_CUBE_IO

}  // namespace flowscape
