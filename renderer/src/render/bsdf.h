#pragma once
// Internal: what a material does where a path meets it. One Bsdf per Material::Kind, one file each
// under bsdfs/, found by bsdf_of; the bounce loop (path_tracer.cpp) calls it without knowing the
// kind. A Bsdf adds the light the surface itself sends along the path (emission, a glow, what a
// pane mirrors), picks the next-event estimate (light_sampler.h) where it scatters diffusely, and
// turns the path: its next direction, origin, throughput and layer.
#include "render/lights.h"
#include "render/path_state.h"

namespace flowscape {

// The surface a path has met and the sample numbers of this bounce.
struct SurfaceEvent {
  const Lights& lights;
  const Surface& s;
  double offset;  // how far off the surface the next ray starts (metres)
  bool first;     // the path's first surface (its layer is still kOther)
  Vec2 light_sample, lobe_sample, choice;

  Vec3 above() const { return s.position + offset * s.geometric; }
  Vec3 below() const { return s.position - offset * s.geometric; }
  const Material& material() const { return *s.material; }
};

// What became of the path.
enum class Turn {
  Ends,           // absorbed, or stopped by design (an emitter, a pane after a diffuse bounce)
  PassesThrough,  // goes on in its own direction beyond the surface
  Reflected,      // a new direction that must leave on the side it came from
  Transmitted,    // a new direction that must leave through the surface
};

class Bsdf {
 public:
  virtual ~Bsdf() = default;
  // Turns the path at e (and fills `shadow` where it samples a light).
  virtual Turn interact(const SurfaceEvent& e, PathState& path, ShadowRay& shadow) const = 0;
  // Whether the first surface a camera path meets here is not its first surface for the guides
  // (the normal the denoiser reads): a rain streak, a pane it sees through.
  virtual bool see_through() const { return false; }
  // Whether the light of a camera path stops being 'other' here (the first surface for the
  // layers): not where it only glows (an emitter) or passes by (a rain streak, a pane).
  virtual bool ends_other() const { return true; }
};

const Bsdf& bsdf_of(Material::Kind kind);

// The lobes the Bsdfs share (bsdfs/lobes.cpp).
// At the first surface: the direct light on the diffuse part and its albedo, which every path
// takes whatever it does next (the denoiser's guides and the direct layer).
void first_diffuse_light(const SurfaceEvent& e, const Rgb& diffuse_part, PathState& path,
                         ShadowRay& shadow);
// A diffuse reflection: at the first surface the start of the indirect light (on a share of the
// paths, weighted for all), after it a light sample and a cosine-distributed direction.
Turn diffuse_lobe(const SurfaceEvent& e, PathState& path, ShadowRay& shadow);
// The start of a specular event: the sky it finds is not sampled as a light; from the first
// surface its light goes to the specular layer.
void begin_specular(const SurfaceEvent& e, PathState& path);
// A mirror blurred by the surface's roughness (a metal, a clear coat).
Turn rough_mirror(const SurfaceEvent& e, PathState& path);

}  // namespace flowscape
