#pragma once
// Internal: the physical sky of a weather: the clear atmosphere, a cloud layer over it, the sun's
// light after both, a daylight white balance and one exposure for the sequence.
#include <Eigen/Core>

#include "flowscape/scenes/scene.h"
#include "flowscape/weather/weather.h"

namespace flowscape::sky {

// A layer of cumulus 2 km up (fBm value noise over the layer, in km, shifted by the weather's
// cloud_shift), cut at the quantile that covers `cloudiness` of it, with an overcast sheet under
// it as the cover nears 1.
class CloudLayer {
 public:
  explicit CloudLayer(const Weather& weather);
  // Optical depth of the layer seen along d (d.z() > 0), filtered over `spread` radians.
  double depth(const Vec3& d, double spread) const;
  // Distance (km) from the ground to the layer along d.
  static double distance(const Vec3& d);
  double sheet() const { return sheet_; }  // how much of an overcast sheet lies under the cumulus

 private:
  double density(const Vec2& at, double footprint) const;  // 0 .. 1 at a point of the layer
  double threshold_, thickness_, sheet_;
  Vec2 shift_;
};

// Sets the environment's sun irradiance and disc visibility, its sky dome, the sky summaries
// (zenith, horizon, ground) and the exposure they are all scaled by.
void set_physical_sky(const Weather& weather, Environment& environment);

}  // namespace flowscape::sky
