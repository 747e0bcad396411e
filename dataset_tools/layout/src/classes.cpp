#include "flowscape/layout/classes.h"

#include <stdexcept>

#include "flowscape/formats/semantic_viz.h"

namespace flowscape {
namespace {

using Rgb = std::array<std::uint8_t, 3>;

ClassTable carla_0913() {
  ClassTable t;
  t.name = "carla-0.9.13";
  t.names = {"Unlabeled",    "Building", "Fence",    "Other",      "Pedestrian", "Pole",
             "RoadLine",     "Road",     "SideWalk", "Vegetation", "Vehicles",   "Wall",
             "TrafficSign",  "Sky",      "Ground",   "Bridge",     "RailTrack",  "GuardRail",
             "TrafficLight", "Static",   "Dynamic",  "Water",      "Terrain"};
  for (int id = 0; id < 23; ++id) t.colours.push_back(semantic_color(std::uint8_t(id)));
  for (int c = 0; c < kSceneClassCount; ++c)
    t.of_scene[std::size_t(c)] = std::uint8_t(c < 23 ? c : 10);
  t.sky = 13;
  return t;
}

ClassTable carla_0914() {
  ClassTable t;
  t.name = "carla-0.9.14";
  t.names = {"Unlabeled",  "Roads",        "SideWalks",   "Building",   "Wall",      "Fence",
             "Pole",       "TrafficLight", "TrafficSign", "Vegetation", "Terrain",   "Sky",
             "Pedestrian", "Rider",        "Car",         "Truck",      "Bus",       "Train",
             "Motorcycle", "Bicycle",      "Static",      "Dynamic",    "Other",     "Water",
             "RoadLine",   "Ground",       "Bridge",      "RailTrack",  "GuardRail", "EgoVehicle"};
  t.colours = {Rgb{0, 0, 0},    {128, 64, 128},  {244, 35, 232},  {70, 70, 70},    {102, 102, 156},
               {190, 153, 153}, {153, 153, 153}, {250, 170, 30},  {220, 220, 0},   {107, 142, 35},
               {152, 251, 152}, {70, 130, 180},  {220, 20, 60},   {255, 0, 0},     {0, 0, 142},
               {0, 0, 70},      {0, 60, 100},    {0, 80, 100},    {0, 0, 230},     {119, 11, 32},
               {110, 190, 160}, {170, 120, 50},  {55, 90, 80},    {45, 60, 150},   {157, 234, 50},
               {81, 0, 81},     {150, 100, 100}, {230, 150, 140}, {180, 165, 180}, {0, 255, 255}};
  // scene classes 0..29 (scene.h's order) -> CARLA 0.9.14's ids
  t.of_scene = {0,  3,  5,  22, 12, 6,  24, 1,  2,  9,  14, 4,  8,  11, 25,
                26, 27, 28, 7,  20, 21, 23, 10, 13, 14, 15, 16, 18, 19, 29};
  t.sky = 11;
  return t;
}

}  // namespace

const ClassTable& class_table(const std::string& name) {
  static const ClassTable tables[] = {carla_0913(), carla_0914()};
  for (const ClassTable& t : tables)
    if (t.name == name) return t;
  throw std::invalid_argument("unknown class table \"" + name +
                              "\" (carla-0.9.13 or carla-0.9.14)");
}

std::vector<std::string> class_table_names() { return {"carla-0.9.13", "carla-0.9.14"}; }

nlohmann::json to_json(const ClassTable& table) {
  return {{"table", table.name}, {"names", table.names}, {"sky", table.sky}};
}

void to_table_ids(const ClassTable& table, ImageView<std::uint8_t> semantic) {
  for (int y = 0; y < semantic.height; ++y)
    for (int x = 0; x < semantic.width; ++x) {
      std::uint8_t& id = *semantic.pixel(x, y);
      if (id < kSceneClassCount) id = table.of_scene[id];
    }
}

Image<std::uint8_t> table_colours(const ClassTable& table, ImageView<const std::uint8_t> semantic) {
  Image<std::uint8_t> out(semantic.width, semantic.height, 3);
  for (int y = 0; y < semantic.height; ++y)
    for (int x = 0; x < semantic.width; ++x) {
      const int id = *semantic.pixel(x, y);
      if (id < table.size())
        for (int c = 0; c < 3; ++c)
          out.pixel(x, y)[c] = table.colours[std::size_t(id)][std::size_t(c)];
    }
  return out;
}

}  // namespace flowscape
