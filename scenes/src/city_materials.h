#pragma once
// Internal: the materials of the city maps, one function per kind of surface, each a procedural
// pattern (texture.h) over uv in metres along the surface, varied by its seed. A material's albedo
// is its mean colour (what a render without textures shows); the pattern modulates it.
#include <cstdint>

#include "flowscape/scenes/scene.h"

namespace flowscape::city_materials {

using Rgb = Eigen::Vector3f;

// Ground. Roads carry uv with u along the road and v across it from the centre line.
Material asphalt(std::uint64_t seed);
Material road_paint(std::uint64_t seed, const Rgb& colour);  // worn lane markings
Material paving(std::uint64_t seed, double slab);            // sidewalk slabs `slab` m square
Material kerb(std::uint64_t seed);                           // granite blocks
Material concrete(std::uint64_t seed);                       // lots, quays, walls
Material soil(std::uint64_t seed);                           // dirt, gravel, rail beds
Material grass(std::uint64_t seed);                          // lawns, parks, terrain

// Buildings: a facade style per building (brick, plaster, concrete panels or glass curtain),
// chosen and coloured by the seed, so no two neighbours look alike.
Material facade(std::uint64_t seed, bool houses);
Material roof_tiles(std::uint64_t seed);
Material window_glass(std::uint64_t seed);
Material window_frame(std::uint64_t seed);  // frames, sills, ledges, cornices

// Vegetation and street furniture.
Material bark(std::uint64_t seed);
Material leaves(std::uint64_t seed);
Material painted_metal(std::uint64_t seed, const Rgb& colour);  // poles, rails, housings
Material sign_face(std::uint64_t seed);                         // a round traffic sign
// A traffic light's housing with its red, amber and green lamps; after sunset lamp `lit` (0 red,
// 1 amber, 2 green) glows.
Material signal_head(int lit);
Material timber(std::uint64_t seed);  // fences, piers
Material water();

// Vehicles and people (uv and positions in the actor's own frame).
Material car_paint(std::uint64_t seed);
Material tyre(double width);             // rubber, tread grooves around (the wheel's frame)
Material wheel_rim(std::uint64_t seed);  // a metal disc with spokes on its faces
Material vehicle_glass();
// Head and tail lights: glossy glass that glows with `night_glow` (sky units, before the exposure)
// once the lamps are on.
Material lamp(const Rgb& colour, const Rgb& night_glow = Rgb::Zero());
Material street_lamp();  // a street lamp's diffuser: white by day, a warm glow at night
// A window's glass lit from inside at night (`glow` in sky units before the exposure): by day the
// same as window_glass.
Material lit_window(std::uint64_t seed, const Rgb& glow);
Material number_plate(std::uint64_t seed);
Material clothing(std::uint64_t seed, bool trousers);
Material skin(std::uint64_t seed);
Material hair(std::uint64_t seed);

// The detailed vehicles and people (assets/): body paint in today's popular colours with road
// grime low down, liveries (a band of `band` from z0 to z1 m, police checks), shared trim.
Rgb popular_car_colour(std::uint64_t seed);
// A truck's cargo box: white on most (55 %), silver on some (20 %), else a car paint's colour.
Rgb cargo_box_colour(std::uint64_t seed);
Material body_paint(const Rgb& colour, std::uint64_t seed);
Material banded_paint(const Rgb& colour, const Rgb& band, double z0, double z1, bool checks,
                      std::uint64_t seed);
// Windows you see through (thin, tinted panes); with `night_glow`, lit from inside once the lamps
// are on (a bus's cabin), in sky units before the exposure.
Material clear_glass(const Rgb& night_glow = Rgb::Zero());
Material trim_plastic();  // black bumpers, pillars, seals
Material chrome();
Material upholstery(std::uint64_t seed);
Material underbody();
Material grille();
Material shoes(std::uint64_t seed);
Material bag(std::uint64_t seed);
Material umbrella(std::uint64_t seed);
Material eyes();

}  // namespace flowscape::city_materials
