// The opt-in asset packs of Debian's game data (city.h's asset_pack): the models, where they are
// installed, their sizes and licences.
#include <filesystem>
#include <stdexcept>

#include "flowscape/scenes/city.h"

namespace flowscape {

std::vector<std::string> asset_pack_names() { return {"torcs"}; }

namespace {

const std::string kTorcsCars = "/usr/share/games/torcs/cars/";

// A car of torcs-data, its size from its TORCS XML (TORCS draws its wheels apart: built-in ones
// stand in): length, axle positions from the middle, half the track, the rim's radius, and the
// tyre's width and aspect ratio (the wheel's radius is the rim's plus the sidewall's height).
PackModel torcs_car(const std::string& name, const std::string& licence,
                    const std::string& copyright, double length, std::vector<double> axles,
                    double track, double rim_radius, double tyre_width, double aspect) {
  return {"torcs",
          name,
          kTorcsCars + name + "/" + name + ".acc",
          ActorKind::Car,
          licence,
          copyright,
          kTorcsTurn,
          length,
          std::move(axles),
          track,
          rim_radius + tyre_width * aspect,
          tyre_width};
}

}  // namespace

std::string model_id(const PackModel& model) { return model.pack + "/" + model.name; }

std::vector<PackModel> asset_pack(const std::string& name) {
  if (name != "torcs") throw std::invalid_argument("unknown asset pack \"" + name + "\" (torcs)");
  if (!std::filesystem::is_directory(kTorcsCars))
    throw std::invalid_argument("asset pack torcs: " + kTorcsCars +
                                " is missing (apt-get install torcs-data)");
  const std::string art = "Free Art License 1.3", gpl = "GPL-2+";
  const std::string durieu = "TORCS: Jean-Christophe Durieu";
  return {torcs_car("p406", gpl, "TORCS: Eric Espie, Christophe Guionneau, Bernhard Wymann", 4.64,
                    {1.37, -1.37}, 0.75, 0.2032, 0.235, 0.55),
          torcs_car("baja-bug", art, durieu, 3.8, {1.3, -1.2}, 0.77, 0.1778, 0.155, 0.8),
          torcs_car("acura-nsx-sz", art, durieu, 5.0, {1.35, -1.43}, 0.8, 0.2159, 0.245, 0.45)};
}

}  // namespace flowscape
