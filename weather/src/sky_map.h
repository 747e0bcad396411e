#pragma once
// Internal: real HDR skies. CC0 Poly Haven maps from the npm package @pmndrs/assets 1.7.0
// (scripts/fetch_sky_maps.sh puts them in sky_map_directory()), each with a recorded horizon line
// above which it shows nothing but sky; the sun is taken out of the map and traced as a disc, so
// shadows stay sharp.
#include <memory>
#include <string>

#include "atmosphere.h"
#include "flowscape/core/image.h"
#include "flowscape/scenes/sky_dome.h"

namespace flowscape::sky {

// A map is a latitude-longitude panorama (width = 2 x height, linear RGB) seen from inside:
// row r looks at elevation 90 - (r + 0.5) / height x 180 degrees, column c at azimuth
// -(c + 0.5) / width x 360 degrees (turning right moves right in the picture).
Vec3 map_direction(const Image<float>& map, double row, double column);
Spectrum map_radiance(const Image<float>& map, const Vec3& d);  // bilinear, cyclic in azimuth
// The irradiance on a level surface from the map's upper hemisphere (sum of radiance x sin(e) x
// the cells' solid angles).
Spectrum horizontal_irradiance(const Image<float>& map);

struct SunInMap {
  Vec3 direction = Vec3::UnitZ();          // the centre of the sun's light in the map
  Spectrum irradiance = Spectrum::Zero();  // on a plane facing it; zero: the map shows no sun
};
// Takes the sun out of `map`: when the brightest pixel above the horizon is at least 20 times the
// upper hemisphere's median luminance, every pixel within 4 degrees of it is replaced by the mean
// of the ring 4-6 degrees round it, and what they held above that mean (with the ringing that
// lossy compression leaves round a bright sun, which sums to about nothing) is the sun.
SunInMap take_out_sun(Image<float>& map);

struct SkyMap {
  std::string name;
  double horizon = 0;     // radians: above this elevation the map shows nothing but sky
  Image<float> radiance;  // RGB, the sun taken out
  SunInMap sun;
};
// The horizon line recorded for each map weather.h's sky_map_names() lists.
double recorded_horizon(const std::string& name);
// `file` read and its sun taken out; a FileError naming it when it is not a whole RGB panorama of
// finite values.
SkyMap read_sky_map(const std::string& name, const std::string& file);
// The named map from sky_map_directory(), read once per process and file; null when it was not
// fetched (with one warning per map on diagnostics(): the physical sky stands in).
std::shared_ptr<const SkyMap> fetched_sky_map(const std::string& name);

// Lays `map` (turned `rotation` radians counter-clockwise, radiance times `scale`) over the dome
// above its horizon line, fading in over 4 degrees; below, the dome's own sky is brought to the
// map's level at the line, per azimuth (averaged over 40 degrees), so the two join without a seam.
void overlay_sky_map(const SkyMap& map, double rotation, double scale, SkyDome& dome);

}  // namespace flowscape::sky
