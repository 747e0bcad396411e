#pragma once
// The semantic class tables a release writes its semantic images and actor classes in. The scene
// labels triangles with its own classes (scenes/scene.h: CARLA 0.9.13's 0-22 and finer ones
// 23-29); a table maps them to the ids a release holds.
//   carla-0.9.13: CARLA 0.9.10-0.9.13's 23 ids (FlowScape's, the default); riders, cars, trucks,
//                 buses, motorcycles, bicycles and the ego vehicle are Vehicles (10), as CARLA
//                 labels a bike with its rider.
//   carla-0.9.14: CARLA 0.9.14's 29 ids (Cityscapes' order: road 1, ..., sky 11, pedestrian 12,
//                 rider 13, car 14, truck 15, bus 16, motorcycle 18, bicycle 19, ...) and
//                 Cityscapes' ego vehicle as 29.
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flowscape/core/image.h"

namespace flowscape {

inline constexpr int kSceneClassCount = 30;  // scene.h's SemanticClass ids 0..29

struct ClassTable {
  std::string name;
  std::vector<std::string> names;                         // by id
  std::vector<std::array<std::uint8_t, 3>> colours;       // by id: the palette CARLA draws it in
  std::array<std::uint8_t, kSceneClassCount> of_scene{};  // scene class -> id
  int sky = 13;
  int size() const { return int(names.size()); }
};
inline constexpr const char* kDefaultClassTable = "carla-0.9.13";
// Throws std::invalid_argument naming the tables for another name.
const ClassTable& class_table(const std::string& name);
std::vector<std::string> class_table_names();
// The manifest's record of it: {"table", "names", "sky"} (and conventions read it back).
nlohmann::json to_json(const ClassTable& table);
// A semantic image of scene classes in the table's ids (ids past the scene's are kept).
void to_table_ids(const ClassTable& table, ImageView<std::uint8_t> semantic);
// Semantic ids as the table's colours (ids it lacks black).
Image<std::uint8_t> table_colours(const ClassTable& table, ImageView<const std::uint8_t> semantic);

}  // namespace flowscape
