#pragma once
// Internal: stacking the cube's faces (geometry.h's N x 6N layout) and cutting them out, for
// render_cube, the denoiser and the final pass's shutter_cube.
#include <algorithm>
#include <string>

#include "flowscape/geometry/geometry.h"
#include "flowscape/renderer/renderer.h"

namespace flowscape {

// render() for one face: a RayError of it names the face as its camera.
template <class Render>
auto on_face(Face face, Render&& render) {
  try {
    return render();
  } catch (const RayError& e) {
    throw e.of_camera("cube " + std::string(face_name(face)));
  }
}

// Puts `image` at `face` of `cube`, allocating the stacked image on the first face.
template <class T>
void put_face(Image<T>& cube, Face face, const Image<T>& image) {
  if (cube.data.empty()) cube = Image<T>(image.width, 6 * image.width, image.channels);
  std::copy(image.data.begin(), image.data.end(), face_view(cube.view(), face).data);
}

// Every layer of a face's colour.
inline void put_face(ColorLayers& cube, Face face, const ColorLayers& layers) {
  put_face(cube.direct, face, layers.direct), put_face(cube.indirect, face, layers.indirect);
  put_face(cube.specular, face, layers.specular), put_face(cube.other, face, layers.other);
  put_face(cube.albedo, face, layers.albedo), put_face(cube.normal, face, layers.normal);
  put_face(cube.variance, face, layers.variance);
}

// A copy of `face` of the stacked `cube`.
template <class T>
Image<T> face_of(const Image<T>& cube, Face face) {
  const ImageView<const T> view = face_view(cube.view(), face);
  Image<T> image(view.width, view.height, view.channels);
  std::copy(view.data, view.data + image.data.size(), image.data.begin());
  return image;
}

inline ColorLayers face_of(const ColorLayers& cube, Face face) {
  return {face_of(cube.direct, face),  face_of(cube.indirect, face), face_of(cube.specular, face),
          face_of(cube.other, face),   face_of(cube.albedo, face),   face_of(cube.normal, face),
          face_of(cube.variance, face)};
}

}  // namespace flowscape
