#pragma once
// Images as plain typed buffers: width, height, interleaved channels, row-major.
#include <cstddef>
#include <type_traits>
#include <vector>

namespace flowscape {

template <class T>
struct ImageView {
  int width = 0, height = 0, channels = 0;
  T* data = nullptr;

  std::size_t pixel_count() const { return std::size_t(width) * height; }
  T* pixel(int x, int y) const { return data + (std::size_t(y) * width + x) * channels; }
  operator ImageView<const T>() const requires(!std::is_const_v<T>) {
    return {width, height, channels, data};
  }
};

template <class T>
struct Image {
  using value_type = T;
  int width = 0, height = 0, channels = 0;
  std::vector<T> data;

  Image() = default;
  Image(int w, int h, int c, T fill = T{})
      : width(w), height(h), channels(c), data(std::size_t(w) * h * c, fill) {}

  std::size_t pixel_count() const { return std::size_t(width) * height; }
  T* pixel(int x, int y) { return data.data() + (std::size_t(y) * width + x) * channels; }
  const T* pixel(int x, int y) const {
    return data.data() + (std::size_t(y) * width + x) * channels;
  }
  ImageView<T> view() { return {width, height, channels, data.data()}; }
  ImageView<const T> view() const { return {width, height, channels, data.data()}; }
};

}  // namespace flowscape
