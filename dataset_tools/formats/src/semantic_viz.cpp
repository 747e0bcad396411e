#include "flowscape/formats/semantic_viz.h"

namespace flowscape {

std::array<std::uint8_t, 3> semantic_color(std::uint8_t class_id) {
  // CARLA 0.9.13's palette, then the scene's finer classes in CARLA 0.9.14's (rider, car, truck,
  // bus, motorcycle, bicycle) and the ego vehicle
  static constexpr std::uint8_t kPalette[30][3] = {
      {0, 0, 0},       {70, 70, 70},    {100, 40, 40},   {55, 90, 80},   {220, 20, 60},
      {153, 153, 153}, {157, 234, 50},  {128, 64, 128},  {244, 35, 232}, {107, 142, 35},
      {0, 0, 142},     {102, 102, 156}, {220, 220, 0},   {70, 130, 180}, {81, 0, 81},
      {150, 100, 100}, {230, 150, 140}, {180, 165, 180}, {250, 170, 30}, {110, 190, 160},
      {170, 120, 50},  {45, 60, 150},   {145, 170, 100}, {255, 0, 0},    {0, 0, 142},
      {0, 0, 70},      {0, 60, 100},    {0, 0, 230},     {119, 11, 32},  {0, 255, 255}};
  if (class_id >= 30) return {0, 0, 0};
  return {kPalette[class_id][0], kPalette[class_id][1], kPalette[class_id][2]};
}

Image<std::uint8_t> semantic_to_color(ImageView<const std::uint8_t> ids) {
  Image<std::uint8_t> out(ids.width, ids.height, 3);
  for (int y = 0; y < ids.height; ++y)
    for (int x = 0; x < ids.width; ++x) {
      const auto rgb = semantic_color(*ids.pixel(x, y));
      std::copy(rgb.begin(), rgb.end(), out.pixel(x, y));
    }
  return out;
}

}  // namespace flowscape
