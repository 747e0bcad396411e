#include "flowscape/formats/contact_sheet.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace flowscape {

Image<std::uint8_t> contact_sheet(const std::vector<std::vector<Image<std::uint8_t>>>& rows) {
  int width = 0, height = 0;
  for (const auto& row : rows) {
    int row_width = 0;
    for (const auto& tile : row) {
      if (tile.channels != 3 || tile.height != row.front().height)
        throw std::invalid_argument("contact sheet: tiles of a row need 3 channels and one height");
      row_width += tile.width;
    }
    width = std::max(width, row_width);
    height += row.empty() ? 0 : row.front().height;
  }
  Image<std::uint8_t> sheet(width, height, 3);
  int y0 = 0;
  for (const auto& row : rows) {
    int x0 = 0;
    for (const auto& tile : row) {
      for (int y = 0; y < tile.height; ++y)
        std::copy(tile.pixel(0, y), tile.pixel(0, y) + 3 * tile.width, sheet.pixel(x0, y0 + y));
      x0 += tile.width;
    }
    y0 += row.empty() ? 0 : row.front().height;
  }
  return sheet;
}

void label_tile(Image<std::uint8_t>& tile, const std::string& text) {
  if (tile.channels != 3) throw std::invalid_argument("label_tile: needs an RGB tile");
  cv::Mat mat(tile.height, tile.width, CV_8UC3, tile.data.data());
  const double scale = std::clamp(tile.width / 700.0, 0.3, 1.5);
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  const int pad = std::max(2, size.height / 3);
  cv::rectangle(mat,
                cv::Rect(0, 0, std::min(tile.width, size.width + 2 * pad),
                         std::min(tile.height, size.height + baseline + 2 * pad)),
                cv::Scalar(20, 20, 20), cv::FILLED);
  cv::putText(mat, text, cv::Point(pad, pad + size.height), cv::FONT_HERSHEY_SIMPLEX, scale,
              cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

Image<std::uint8_t> shrink_to_width(const Image<std::uint8_t>& image, int width) {
  if (image.width <= width) return image;
  const int height = std::max(1, image.height * width / image.width);
  Image<std::uint8_t> out(width, height, 3);
  const cv::Mat src(image.height, image.width, CV_8UC3,
                    const_cast<std::uint8_t*>(image.data.data()));
  cv::Mat dst(height, width, CV_8UC3, out.data.data());
  cv::resize(src, dst, dst.size(), 0, 0, cv::INTER_AREA);
  return out;
}

}  // namespace flowscape
