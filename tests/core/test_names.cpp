#include <catch2/catch.hpp>

#include "flowscape/core/names.h"

using namespace flowscape;

TEST_CASE("edit_distance counts insertions, deletions and substitutions, ignoring case") {
  CHECK(edit_distance("", "") == 0);
  CHECK(edit_distance("kitten", "sitting") == 3);  // the textbook pair
  CHECK(edit_distance("positon", "position") == 1);
  CHECK(edit_distance("Frames", "frames") == 0);
  CHECK(edit_distance("abc", "") == 3);
}

TEST_CASE("did_you_mean suggests the near name or an alias, else lists the known ones") {
  const std::vector<std::string> known{"position", "camera_to_rig", "yaw_pitch_roll_degrees"};
  CHECK(did_you_mean("positon", known) == " (did you mean \"position\"?)");
  CHECK(did_you_mean("yaw_pitch_roll_deg", known) == " (did you mean \"yaw_pitch_roll_degrees\"?)");
  CHECK(did_you_mean("xyz", known) == " (known: position, camera_to_rig, yaw_pitch_roll_degrees)");
  CHECK(did_you_mean("dist_coeffs", {"K", "D"}, {{"dist_coeffs", "D"}}) ==
        " (did you mean \"D\"?)");
}
