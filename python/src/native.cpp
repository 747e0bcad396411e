// flowscape_native: the plugin's heavy per-pixel work in C++ (image decoding through OpenImageIO,
// bilinear remapping through OpenCV), for flowscape/io.py and flowscape/augment.py.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <opencv2/imgproc.hpp>

#include "flowscape/formats/image_io.h"

namespace py = pybind11;
using namespace flowscape;

namespace {

template <class T>
py::array to_numpy(const Image<T>& image) {
  py::array_t<T> out({image.height, image.width, image.channels});
  std::copy(image.data.begin(), image.data.end(), out.mutable_data());
  return out;
}

py::array read_image_file(const std::string& path) {
  return std::visit([](const auto& image) { return to_numpy(image); }, read_any_image(path));
}

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// image sampled at (map_x, map_y) with bilinear weights at 1/32-pixel steps; columns wrap when
// asked, taps outside read 0.
py::array remap(FloatArray image, FloatArray map_x, FloatArray map_y, bool wrap) {
  if (image.ndim() != 2 && image.ndim() != 3)
    throw std::invalid_argument("image must be H x W (x C)");
  const int h = int(image.shape(0)), w = int(image.shape(1));
  const int channels = image.ndim() == 3 ? int(image.shape(2)) : 1;
  if (channels < 1 || channels > 4) throw std::invalid_argument("1 to 4 channels");
  if (map_x.ndim() != 2 || map_y.ndim() != 2 || map_x.shape(0) != map_y.shape(0) ||
      map_x.shape(1) != map_y.shape(1))
    throw std::invalid_argument("map_x and map_y must be equal H x W arrays");
  const int oh = int(map_x.shape(0)), ow = int(map_x.shape(1));
  const cv::Mat src(h, w, CV_32FC(channels), const_cast<float*>(image.data()));
  const cv::Mat mx(oh, ow, CV_32F, const_cast<float*>(map_x.data()));
  const cv::Mat my(oh, ow, CV_32F, const_cast<float*>(map_y.data()));
  std::vector<py::ssize_t> shape{oh, ow};
  if (image.ndim() == 3) shape.push_back(channels);
  py::array_t<float> out(shape);
  cv::Mat dst(oh, ow, CV_32FC(channels), out.mutable_data());
  {
    py::gil_scoped_release release;
    cv::remap(src, dst, mx, my, cv::INTER_LINEAR, wrap ? cv::BORDER_WRAP : cv::BORDER_CONSTANT,
              cv::Scalar::all(0));
  }
  return out;
}

}  // namespace

PYBIND11_MODULE(flowscape_native, m) {
  m.doc() = "FlowScape's C++ helpers for the Python plugin";
  m.def("read_image", &read_image_file, py::arg("path"),
        "an image file as an H x W x C array of its own type (uint8, uint16 or float32)");
  m.def("remap", &remap, py::arg("image"), py::arg("map_x"), py::arg("map_y"), py::arg("wrap"),
        "bilinear sampling at 1/32-pixel steps (OpenCV remap); taps outside read 0");
}
