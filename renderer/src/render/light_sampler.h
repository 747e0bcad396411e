#pragma once
// Internal: next-event estimation. Which light a surface point samples (the sun or moon, a lamp of
// the lamp grid, the sky dome), the shadow ray towards it and the light it brings, and the MIS
// weight of the sky a bounce finds instead.
#include "render/lights.h"
#include "render/path_state.h"

namespace flowscape {

// The sky a path finds: sharp from the camera and its specular chains, averaged after a diffuse
// event (whose cone is wider than the average's blocks).
Rgb sky_seen(const Lights& lights, const Vec3& dir, bool scattered);

// One light for a diffuse event at s (its cosine lobe about `bounce_normal`), seen from `origin`:
// the sun (the moon), a lamp (picked with u.x) or the sky dome, each with the probability of its
// share of the light on the surface, chosen with u.y, which the sun's and the sky's samples then
// reuse. The sky is sampled only where the sun does not shine on the surface (dusk, night, clouds
// over the sun, faces turned from it): under the sun its shadow rays stay the sun's.
ShadowRay sample_light(const Lights& lights, const Surface& s, const Vec3& origin,
                       const Rgb& throughput, Vec2 u, const Vec3& bounce_normal, Layer layer);

// The MIS weight (balance heuristic) of the sky found along `dir` by a diffuse bounce that may
// have sampled it as a light (PathState::sky_chance): 1 where it could not have.
double found_sky_weight(const Lights& lights, const PathState& path, const Vec3& dir);

}  // namespace flowscape
