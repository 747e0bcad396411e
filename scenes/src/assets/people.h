#pragma once
// Internal: people. One skinned mesh per look (a body of believable proportions with a head, hair,
// hands and shoes, clothes, a bag or an umbrella), weighted to a 17-bone skeleton so the skin bends
// smoothly at the joints (linear blend skinning). Proportions from anthropometric tables as shares
// of the height (adults 1.5-1.95 m, children 1.0-1.45 m with larger heads); x forward, y left, z
// up, the feet on z = 0 in the rest pose (standing, arms hanging).
#include <array>
#include <memory>

#include "flowscape/core/random.h"
#include "loft.h"

namespace flowscape::assets {

enum Bone : int {
  kPelvis,
  kSpine,
  kChest,
  kNeck,
  kHead,
  kUpperArmL,
  kForearmL,
  kHandL,
  kUpperArmR,
  kForearmR,
  kHandR,
  kThighL,
  kShinL,
  kFootL,
  kThighR,
  kShinR,
  kFootR,
  kBones
};

// Material slots of a person (Part::materials maps them to the person's own materials).
enum PersonSlot : std::uint16_t {
  kSkinTone,
  kTop,
  kBottom,
  kShoes,
  kHair,
  kBag,
  kUmbrella,
  kEyes,
  kPersonSlots
};

struct Skeleton {
  std::array<V3, kBones> joints;  // rest positions (the bone's pivot)
  std::array<int, kBones> parent;
  double height = 1.75;
  double thigh = 0, shin = 0, upper_arm = 0, forearm = 0;  // lengths
  double ankle = 0;                                        // height of the ankle over the sole
  double hip_y = 0;  // half the distance between the hip joints
  double foot = 0;   // heel to toe
};

struct Look {
  bool female = false, child = false;
  double height = 1.75, build = 1.0;  // build: widths scale (0.85 slim .. 1.25 heavy)
  enum class Top : std::uint8_t { TShirt, LongSleeves, Jacket, Coat } top = Top::TShirt;
  enum class Bottom : std::uint8_t { Trousers, Shorts, Skirt, Dress } bottom = Bottom::Trousers;
  enum class Hair : std::uint8_t { Short, Bob, Long, Ponytail, Bald, Cap } hair = Hair::Short;
  enum class Bag : std::uint8_t { None, Backpack, Shoulder } bag = Bag::None;
  bool umbrella = false;
};
// A look drawn for a person (children: `child`); umbrellas only when it rains.
Look random_look(Random& random, bool child, bool rain);

struct PersonModel {
  std::shared_ptr<const Mesh> mesh;  // skinned to the skeleton's bones (Bone order)
  Skeleton skeleton;
  Look look;
};
// `cls`: Pedestrian, or Rider for the people riding two-wheelers.
PersonModel build_person(const Look& look, SemanticClass cls);

// The skinning matrices (bone k: rest pose -> actor frame) from each bone's rotation relative to
// the rest pose, applied about its joint and chained from the pelvis, whose pivot is moved by
// `root` (a translation of the pelvis joint) and turned by local[kPelvis].
std::vector<Pose> forward_kinematics(const Skeleton& skeleton,
                                     const std::array<Eigen::Matrix3d, kBones>& local,
                                     const V3& root);

}  // namespace flowscape::assets
