#pragma once
// Internal: a path of the path tracer as its bounces, its materials (bsdf.h) and its light
// sampling (light_sampler.h) share it.
#include "render/embree_scene.h"
#include "render/surface.h"

namespace flowscape {

// After a diffuse event a path's cone opens this wide (radians): what it sees next is looked up
// blurred, as the average over the many directions it could have taken.
inline constexpr double kScatteredSpread = 0.2;

// Where a path's light goes (ColorLayers): kOther until its first surface decides.
enum Layer { kOther, kDirect, kIndirect, kSpecular, kLayerCount };

struct PathState {
  Vec3 origin, dir;
  float time = 0;  // over a shutter: its rays' (BundleRay::time)
  Rgb throughput = Rgb::Ones();
  Rgb light[kLayerCount] = {Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero()};
  Layer layer = kOther;  // where the light the path gathers now goes
  // How much a diffuse first surface's indirect light counts on this path; 0: the path stops there
  // (RenderOptions::indirect_samples).
  double indirect_weight = 1;
  Rgb albedo = Rgb::Zero();
  Vec3 normal = Vec3::Zero();
  // Whether it met a surface whose light is not 'other' (Bsdf::ends_other); an edge sample
  // (other_only) stops there: it gathers only the 'other' light before it.
  bool met_surface = false, other_only = false;
  // The ray's cone for texture filtering (ray cones): width at the origin (m) and spread (rad).
  double width = 0, spread = 0;
  // Whether it has scattered diffusely: its cone is then so wide that a texture filtered over it is
  // its material's mean, and the sky it finds the averaged dome.
  bool scattered = false;
  // Camera rays and specular chains from the camera may see the sun disc itself; after a diffuse
  // event the sun comes through next-event estimation only (no sun caustics: they would be rare,
  // huge fireflies at these sample counts).
  bool sun_visible = true;
  // After a diffuse event that may have sampled the sky as a light: the chance it did and the
  // normal the bounce was drawn about, for the MIS weight of the sky the bounce finds.
  double sky_chance = 0;
  Vec3 bounce_normal = Vec3::Zero();
};

// Next-event estimation: a shadow ray towards the sun (the moon at night), a lamp or the sky, and
// the light it brings if unblocked.
struct ShadowRay {
  BundleRay ray;
  Rgb light = Rgb::Zero();
  Layer layer = kOther;
  double sky_chance = 0;  // how likely the event picked the sky: for a bounce's MIS weight
};

}  // namespace flowscape
