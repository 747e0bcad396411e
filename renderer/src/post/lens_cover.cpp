#include "flowscape/renderer/lens_cover.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "flowscape/core/random.h"

namespace flowscape {
namespace {

// Bilinear RGB at a continuous pixel position (pixel centres at +0.5), clamped to the image.
Eigen::Vector3f sample(const cv::Mat& image, Vec2 at) {
  const double x = std::clamp(at.x() - 0.5, 0.0, double(image.cols - 1));
  const double y = std::clamp(at.y() - 0.5, 0.0, double(image.rows - 1));
  const int x0 = int(x), y0 = int(y);
  const int x1 = std::min(x0 + 1, image.cols - 1), y1 = std::min(y0 + 1, image.rows - 1);
  const float fx = float(x - x0), fy = float(y - y0);
  const auto at_pixel = [&](int px, int py) {
    const cv::Vec3f v = image.at<cv::Vec3f>(py, px);
    return Eigen::Vector3f(v[0], v[1], v[2]);
  };
  return (1 - fy) * ((1 - fx) * at_pixel(x0, y0) + fx * at_pixel(x1, y0)) +
         fy * ((1 - fx) * at_pixel(x0, y1) + fx * at_pixel(x1, y1));
}

cv::Mat blurred(const cv::Mat& image, double sigma) {
  cv::Mat out;
  cv::GaussianBlur(image, out, cv::Size(0, 0), sigma, sigma, cv::BORDER_REFLECT);
  return out;
}

// Dirt: Gaussian blotches, scaled so the densest point takes `dirt` of the light.
Image<float> dirt_map(int width, int height, double dirt, Random& random) {
  Image<float> map(width, height, 1);
  const double side = std::min(width, height);
  for (int k = 0; k < 8; ++k) {
    const Vec2 centre(random.uniform(0, width), random.uniform(0, height));
    const double sigma = random.uniform(0.04, 0.12) * side, weight = random.uniform(0.3, 1);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const double r2 = (Vec2(x + 0.5, y + 0.5) - centre).squaredNorm();
        *map.pixel(x, y) += float(weight * std::exp(-r2 / (2 * sigma * sigma)));
      }
  }
  const float peak = *std::max_element(map.data.begin(), map.data.end());
  for (float& v : map.data) v = peak > 0 ? float(dirt) * v / peak : 0;
  return map;
}

}  // namespace

double drop_share(const LensDrop& drop, double distance) {
  return std::clamp((drop.radius - distance) / (kDropRim * drop.radius), 0.0, 1.0);
}

LensCover lens_cover(int width, int height, int drops, double dirt, std::uint64_t seed) {
  Random random(seed);
  LensCover cover;
  const double side = std::min(width, height);
  for (int k = 0; k < drops; ++k) {
    const Vec2 centre(random.uniform(0, width), random.uniform(0, height));
    cover.drops.push_back({centre, random.uniform(0.01, 0.04) * side});
  }
  if (dirt > 0) cover.dirt = dirt_map(width, height, dirt, random);
  return cover;
}

Image<float> through_cover(ImageView<const float> light, const LensCover& cover) {
  Image<float> out(light.width, light.height, 3);
  std::copy(light.data, light.data + out.data.size(), out.data.begin());
  cv::Mat image(out.height, out.width, CV_32FC3, out.data.data());
  if (!cover.dirt.data.empty()) {
    const cv::Mat haze = blurred(image, kDirtBlur);
    for (int y = 0; y < out.height; ++y)
      for (int x = 0; x < out.width; ++x) {
        const float a = *cover.dirt.pixel(x, y);
        cv::Vec3f& v = image.at<cv::Vec3f>(y, x);
        v = (1 - a) * v + a * float(kDirtTransmission) * haze.at<cv::Vec3f>(y, x);
      }
  }
  const cv::Mat scene = image.clone();  // drops see the scene, not each other
  for (const LensDrop& drop : cover.drops) {
    // the part of the scene the drop shows, blurred (with the pixels round it as its border)
    const double sigma = std::max(0.5, drop.radius / 3),
                 reach = kDropView * drop.radius + 3 * sigma;
    const cv::Rect region = cv::Rect(int(drop.centre.x() - reach), int(drop.centre.y() - reach),
                                     int(2 * reach) + 2, int(2 * reach) + 2) &
                            cv::Rect(0, 0, out.width, out.height);
    if (region.empty()) continue;
    const cv::Mat seen = blurred(scene(region), sigma);
    const Vec2 corner(region.x, region.y);
    const int x0 = std::max(0, int(drop.centre.x() - drop.radius)),
              x1 = std::min(out.width - 1, int(drop.centre.x() + drop.radius));
    const int y0 = std::max(0, int(drop.centre.y() - drop.radius)),
              y1 = std::min(out.height - 1, int(drop.centre.y() + drop.radius));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Vec2 offset = Vec2(x + 0.5, y + 0.5) - drop.centre;
        const float share = float(drop_share(drop, offset.norm()));
        if (share <= 0) continue;
        const Eigen::Vector3f through =
            float(kDropTransmission) * sample(seen, drop.centre - kDropView * offset - corner);
        cv::Vec3f& v = image.at<cv::Vec3f>(y, x);
        for (int c = 0; c < 3; ++c) v[c] = (1 - share) * v[c] + share * through[c];
      }
  }
  return out;
}

Image<std::uint8_t> cover_mask(const LensCover& cover, int width, int height) {
  Image<std::uint8_t> mask(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      bool hidden = !cover.dirt.data.empty() && *cover.dirt.pixel(x, y) >= 0.5f;
      for (const LensDrop& drop : cover.drops)
        hidden = hidden || drop_share(drop, (Vec2(x + 0.5, y + 0.5) - drop.centre).norm()) >= 0.5;
      *mask.pixel(x, y) = hidden;
    }
  return mask;
}

}  // namespace flowscape
