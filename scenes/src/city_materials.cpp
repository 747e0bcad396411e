#include "city_materials.h"

#include <algorithm>
#include <cmath>

#include "flowscape/core/random.h"
#include "flowscape/scenes/texture.h"

namespace flowscape::city_materials {
namespace {

using namespace tex;

Material make(Material::Kind kind, const Rgb& albedo, float roughness, Pattern pattern) {
  Material m;
  m.kind = kind, m.albedo = albedo, m.roughness = roughness;
  m.pattern = std::make_shared<const Pattern>(std::move(pattern));
  return m;
}

Material diffuse(const Rgb& albedo, Pattern pattern) {
  return make(Material::Kind::Diffuse, albedo, 0.5f, std::move(pattern));
}

Rgb clamped(const Rgb& c) { return c.cwiseMax(0.0f).cwiseMin(0.95f); }

SurfaceLook scaled(const SurfaceLook& base, double factor, const Vec2& slope = Vec2::Zero()) {
  return {clamped(base.albedo * float(factor)), base.roughness, slope};
}

// A colour drawn around `mean`: each channel within +-spread, one draw for the whole colour.
Rgb varied(Random& random, const Rgb& mean, double spread) {
  const double shade = random.uniform(1 - spread, 1 + spread);
  Rgb c;
  for (int k = 0; k < 3; ++k) c[k] = float(mean[k] * shade * random.uniform(0.92, 1.08));
  return clamped(c);
}

// Unit variation of a cell id, faded where the cells are too small to see.
double unit_tone(std::uint64_t unit, std::uint64_t seed, double size, double footprint) {
  return (hash01(unit, seed) - 0.5) * visible(size, footprint);
}

// Dirt and wear: dark blotches where a low-frequency fBm rises above a threshold.
double blotches(const Vec2& uv, std::uint64_t seed, double frequency, double footprint) {
  return smoothstep(0.25, 0.65, fbm(uv, seed, frequency, 4, footprint).value);
}

}  // namespace

Material asphalt(std::uint64_t seed) {
  return diffuse({0.085f, 0.085f, 0.09f}, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const Vec2& uv = at.uv;
    // the aggregate's segregation and macrotexture (33 cm down to mm, its relief lit by the sun),
    // binder-rich and ravelled areas (2 m down to 10 cm), exposed chips: light stone and dark
    const Noise macro = fbm(uv, seed, 12, 6, fp, 0.7),
                mottle = fbm(uv, seed + 10, 0.5, 5, fp, 0.65);
    const Noise segregation = fbm(uv, seed + 11, 3, 2, fp, 0.8);
    double f = 1 + 0.3 * macro.value + 0.2 * mottle.value + 0.15 * segregation.value;
    const Cells chips = cells(uv, 0.03, seed + 60);
    const double chip = hash01(chips.id, seed + 61);
    f *= 1 + (chip < 0.3   ? 0.8
              : chip > 0.8 ? -0.4
                           : 0) *
                 visible(0.03, fp) * line_coverage(chips.f1, 0.01, fp);
    // resurfaced patches: a third of the Worley cells of ~9 m, darker or lighter
    const Cells patch = cells(uv, 9, seed + 20);
    const double pick = hash01(patch.id, seed + 21);
    if (pick < 0.3) {
      const double inside = smoothstep(0, fp + 0.05, (patch.f2 - patch.f1) / 2);
      f *= 1 + inside * (pick < 0.15 ? -0.25 : 0.25);
    }
    // cracks along the borders of a finer net, where a slow mask lets them
    const Cells net = cells(uv, 1.6, seed + 30);
    const double cracked = smoothstep(0.1, 0.5, fbm(uv, seed + 31, 0.12, 2, fp).value);
    f *= 1 - 0.6 * cracked * line_coverage((net.f2 - net.f1) / 2, 0.006, fp);
    // polished tyre tracks 0.8 m either side of each 3.5 m lane's centre, oil drips between them
    const double lateral = std::fmod(std::abs(uv.y()), 3.5);
    const double tracks =
        line_coverage(lateral - 0.95, 0.3, fp) + line_coverage(lateral - 2.55, 0.3, fp);
    f *= 1 - 0.14 * tracks * (0.6 + 0.4 * fbm({0.3 * uv.x(), uv.y()}, seed + 40, 1, 2, fp).value);
    const double oil = smoothstep(0.3, 0.6, fbm({uv.x(), 3 * uv.y()}, seed + 50, 0.8, 3, fp).value);
    f *= 1 - 0.35 * oil * line_coverage(lateral - 1.75, 0.35, fp);
    return scaled(base, f, 0.003 * macro.gradient);
  });
}

Material road_paint(std::uint64_t seed, const Rgb& colour) {
  return diffuse(colour, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const double wear = 0.7 * smoothstep(0.1, 0.8, 0.5 + 0.5 * fbm(at.uv, seed, 1.2, 4, fp).value);
    const Noise speck = fbm(at.uv, seed + 1, 25, 2, fp);
    SurfaceLook look = base;
    look.albedo =
        clamped(mix(base.albedo, base.albedo * 0.12f, wear) * float(1 + 0.12 * speck.value));
    look.slope = 0.001 * speck.gradient;
    return look;
  });
}

Material paving(std::uint64_t seed, double slab) {
  Random random(seed);
  const double shift = random.chance(0.5) ? 0.5 : 0;
  const Rgb colour = varied(random, {0.42f, 0.41f, 0.39f}, 0.15);
  return diffuse(colour, [seed, slab, shift](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const Bond b = bond(at.uv, {slab, slab}, 0.008, shift, fp);
    const Noise surface = fbm(at.uv, seed + 2, 10, 5, fp, 0.7);  // exposed sand and cement
    double f = 1 + 0.25 * unit_tone(b.unit, seed, slab, fp) +
               0.12 * fbm(at.uv, seed + 1, 1.5, 3, fp).value + 0.22 * surface.value;
    f *= 1 - 0.35 * blotches(at.uv, seed + 3, 0.4, fp);  // gum and dirt
    f *= 1 - 0.5 * b.mortar;
    return scaled(base, f, 0.002 * surface.gradient);
  });
}

Material kerb(std::uint64_t seed) {
  return diffuse({0.5f, 0.5f, 0.49f}, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const Bond b = bond(at.uv, {1.0, 0.5}, 0.01, 0, fp);
    const Noise speckle = fbm(at.uv, seed, 50, 2, fp);
    const double f = (1 + 0.15 * unit_tone(b.unit, seed + 1, 1.0, fp) + 0.2 * speckle.value) *
                     (1 - 0.5 * b.mortar) * (1 - 0.25 * blotches(at.uv, seed + 2, 0.5, fp));
    return scaled(base, f, 0.001 * speckle.gradient);
  });
}

Material concrete(std::uint64_t seed) {
  return diffuse({0.48f, 0.47f, 0.44f}, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const Bond b = bond(at.uv, {2.4, 1.2}, 0.012, 0.5, fp);
    const Noise surface = fbm(at.uv, seed + 1, 8, 5, fp, 0.7);
    double f = 1 + 0.16 * fbm(at.uv, seed, 0.5, 4, fp, 0.65).value + 0.2 * surface.value +
               0.14 * unit_tone(b.unit, seed + 2, 2.4, fp);
    f *= (1 - 0.45 * b.mortar) * (1 - 0.3 * blotches(at.uv, seed + 3, 0.3, fp));
    return scaled(base, f, 0.002 * surface.gradient);
  });
}

Material soil(std::uint64_t seed) {
  return diffuse({0.3f, 0.23f, 0.16f}, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const Noise clods = fbm(at.uv, seed, 0.3, 6, fp), crumbs = fbm(at.uv, seed + 1, 20, 3, fp);
    double f = 1 + 0.25 * clods.value + 0.2 * crumbs.value;
    const Cells stones = cells(at.uv, 0.09, seed + 2);
    f *= 1 + 0.5 * visible(0.05, fp) * line_coverage(stones.f1, 0.018, fp);
    SurfaceLook look = scaled(base, f, 0.004 * crumbs.gradient + 0.01 * clods.gradient);
    look.albedo.z() *= float(1 - 0.15 * clods.value);  // wetter patches are less blue
    return look;
  });
}

Material grass(std::uint64_t seed) {
  return diffuse({0.1f, 0.22f, 0.06f}, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const double dry = 0.6 * smoothstep(-0.2, 0.6, fbm(at.uv, seed, 0.15, 4, fp).value);
    // tufts and clumps (1 m down to 4 cm), blades (2.5 cm down to mm), the clumps' relief
    const Noise clumps = fbm(at.uv, seed + 1, 1.5, 5, fp, 0.75),
                blades = fbm(at.uv, seed + 2, 40, 3, fp, 0.7);
    const Rgb hue = mix(base.albedo, base.albedo.cwiseProduct(Rgb(1.9f, 1.25f, 1.1f)), dry);
    return SurfaceLook{clamped(hue * float(1 + 0.4 * clumps.value + 0.35 * blades.value)),
                       base.roughness, 0.006 * clumps.gradient + 0.003 * blades.gradient};
  });
}

Material facade(std::uint64_t seed, bool houses) {
  Random random(seed);
  const double style = random.uniform();
  if (style < (houses ? 0.45 : 0.3)) {  // brick in running bond
    const Rgb brick = varied(random, {0.42f, 0.2f, 0.13f}, 0.3);
    const Rgb mortar = varied(random, {0.5f, 0.48f, 0.44f}, 0.2);
    return diffuse(0.85f * brick + 0.15f * mortar, [seed, brick, mortar](const TexturePoint& at,
                                                                         const SurfaceLook& base) {
      const double fp = at.footprint,
                   wet = base.albedo.x() / (0.85 * brick.x() + 0.15 * mortar.x());
      const Bond b = bond(at.uv, {0.25, 0.075}, 0.012, 0.5, fp);
      const double tone = 1 + 0.3 * unit_tone(b.unit, seed, 0.25, fp) +
                          0.1 * fbm(at.uv, seed + 1, 0.4, 3, fp).value;
      const Rgb colour = mix(brick * float(tone), mortar, b.mortar) * float(wet);
      const double grime = 0.3 * smoothstep(1.2, 0, at.uv.y()) +
                           0.2 * blotches({3 * at.uv.x(), 0.2 * at.uv.y()}, seed + 2, 0.4, fp);
      return SurfaceLook{clamped(colour * float(1 - grime)), base.roughness, Vec2::Zero()};
    });
  }
  if (style < (houses ? 0.95 : 0.6)) {  // plaster with storey bands and rain streaks
    const Rgb colour = varied(random,
                              {float(random.uniform(0.45, 0.8)), float(random.uniform(0.4, 0.72)),
                               float(random.uniform(0.32, 0.62))},
                              0.1);
    const double storey = random.uniform(2.9, 3.6);
    return diffuse(colour, [seed, storey](const TexturePoint& at, const SurfaceLook& base) {
      const double fp = at.footprint;
      const Noise grain = fbm(at.uv, seed + 1, 20, 2, fp);
      double f = 1 + 0.12 * fbm(at.uv, seed, 0.25, 5, fp).value + 0.08 * grain.value;
      f *= 1 - 0.25 * blotches({3 * at.uv.x(), 0.15 * at.uv.y()}, seed + 2, 1, fp);  // streaks
      f *= 1 - 0.12 * pulse_train(at.uv.y() + 0.1, storey, 0.2, fp);                 // bands
      f *= 1 - 0.3 * smoothstep(1.0, 0, at.uv.y());                                  // splashes
      return scaled(base, f, 0.002 * grain.gradient);
    });
  }
  if (style < 0.85) {  // concrete panels, one per storey and bay
    const Rgb colour = varied(random, {0.55f, 0.54f, 0.5f}, 0.15);
    const Vec2 panel(random.uniform(2.4, 3.6), random.uniform(1.6, 3.4));
    return diffuse(colour, [seed, panel](const TexturePoint& at, const SurfaceLook& base) {
      const double fp = at.footprint;
      const Bond b = bond(at.uv, panel, 0.025, 0, fp);
      const Noise pores = fbm(at.uv, seed + 1, 30, 2, fp);
      double f = 1 + 0.16 * unit_tone(b.unit, seed, panel.x(), fp) +
                 0.12 * fbm(at.uv, seed + 2, 0.6, 4, fp).value + 0.08 * pores.value;
      f *= (1 - 0.55 * b.mortar) * (1 - 0.25 * blotches(at.uv, seed + 3, 0.3, fp));
      return scaled(base, f, 0.0015 * pores.gradient);
    });
  }
  // glass curtain wall: tinted panes between light mullions, each pane reflecting a little
  // differently
  const Rgb pane = varied(random, {0.12f, 0.16f, 0.2f}, 0.3);
  const Rgb mullion = varied(random, {0.55f, 0.56f, 0.58f}, 0.2);
  const Vec2 grid(random.uniform(1.2, 2.0), random.uniform(3.0, 3.6));
  return make(Material::Kind::Glossy, 0.8f * pane + 0.2f * mullion, 0.04f,
              [seed, pane, mullion, grid](const TexturePoint& at, const SurfaceLook& base) {
                const double fp = at.footprint;
                const Bond b = bond(at.uv, grid, 0.1, 0, fp);
                const double tone = 1 + 0.5 * unit_tone(b.unit, seed, grid.x(), fp);
                return SurfaceLook{clamped(mix(pane * float(tone), mullion, b.mortar)),
                                   float(base.roughness * (1 + 3 * b.mortar)), Vec2::Zero()};
              });
}

Material roof_tiles(std::uint64_t seed) {
  Random random(seed);
  const Rgb colour = varied(random, {0.4f, 0.15f, 0.1f}, 0.35);
  return diffuse(colour, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const Bond b = bond(at.uv, {0.3, 0.25}, 0.025, 0.5, fp);
    double f = (1 + 0.3 * unit_tone(b.unit, seed, 0.3, fp)) * (1 - 0.6 * b.mortar);
    const double moss = 0.5 * blotches(at.uv, seed + 1, 0.6, fp);
    SurfaceLook look = scaled(base, f * (1 - 0.3 * moss));
    look.albedo.y() = std::min(0.95f, look.albedo.y() + float(0.05 * moss));
    look.slope = Vec2(0, -0.15 * pulse_train(at.uv.y(), 0.25, 0.08, fp));  // the tiles' lip
    return look;
  });
}

Material window_glass(std::uint64_t seed) {
  return make(Material::Kind::Metal, {0.22f, 0.25f, 0.28f}, 0.03f,
              [seed](const TexturePoint& at, const SurfaceLook& base) {
                // a few windows show blinds or curtains, every pane its own dust
                const Vec3 cell = (at.position.array() / 1.6).floor();
                const std::uint64_t window =
                    mix_bits(std::uint64_t(std::int64_t(cell.x())) * 73856093u ^
                             std::uint64_t(std::int64_t(cell.y())) * 19349663u ^
                             std::uint64_t(std::int64_t(cell.z())) * 83492791u);
                const double blind = hash01(window, seed) < 0.25 ? 1.6 : 1;
                const double dust = 0.2 * fbm(at.uv, seed + 1, 2, 3, at.footprint).value;
                return SurfaceLook{clamped(base.albedo * float(blind * (1 + dust))),
                                   float(base.roughness * (1 + 4 * std::abs(dust))), Vec2::Zero()};
              });
}

Material lit_window(std::uint64_t seed, const Rgb& glow) {
  Material m = window_glass(seed);
  m.night_emission = glow, m.glow_only = true;
  return m;
}

Material window_frame(std::uint64_t seed) {
  Random random(seed);
  const double pick = random.uniform();
  const Rgb colour = pick < 0.4   ? varied(random, {0.8f, 0.8f, 0.78f}, 0.1)
                     : pick < 0.7 ? varied(random, {0.12f, 0.12f, 0.13f}, 0.3)
                                  : varied(random, {0.55f, 0.5f, 0.42f}, 0.2);
  return diffuse(colour, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const Noise grain = fbm(at.uv, seed, 15, 3, at.footprint);
    return scaled(base,
                  (1 + 0.12 * grain.value) * (1 - 0.2 * blotches(at.uv, seed + 1, 1, at.footprint)),
                  0.001 * grain.gradient);
  });
}

Material bark(std::uint64_t seed) {
  return diffuse({0.22f, 0.16f, 0.1f}, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const Noise ridges = fbm({6 * at.uv.x(), 0.7 * at.uv.y()}, seed, 4, 4, fp);
    const double fissure = smoothstep(0.1, 0.5, ridges.value);
    return scaled(base, (1 - 0.55 * fissure) * (1 + 0.15 * fbm(at.uv, seed + 1, 8, 2, fp).value),
                  0.01 * ridges.gradient);
  });
}

Material leaves(std::uint64_t seed) {
  Random random(seed);
  const Rgb colour = varied(random, {0.07f, 0.18f, 0.045f}, 0.3);
  return diffuse(colour, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const Noise foliage = fbm(at.uv, seed, 5, 4, fp);
    const double gap = smoothstep(-0.1, -0.45, foliage.value);  // shadowed holes in the crown
    const double yellow = 0.5 * smoothstep(0.2, 0.7, fbm(at.uv, seed + 1, 0.7, 3, fp).value);
    const Rgb hue = mix(base.albedo, base.albedo.cwiseProduct(Rgb(1.8f, 1.3f, 0.9f)), yellow);
    return SurfaceLook{clamped(hue * float((1 + 0.35 * foliage.value) * (1 - 0.6 * gap))),
                       base.roughness, 0.02 * foliage.gradient};
  });
}

Material painted_metal(std::uint64_t seed, const Rgb& colour) {
  return make(
      Material::Kind::Glossy, colour, 0.3f,
      [seed](const TexturePoint& at, const SurfaceLook& base) {
        const double fp = at.footprint;
        const double rust = 0.6 * blotches({4 * at.uv.x(), 0.25 * at.uv.y()}, seed, 0.8, fp);
        const Rgb rusty = base.albedo.cwiseProduct(Rgb(0.8f, 0.55f, 0.35f));
        const Noise grain = fbm(at.uv, seed + 1, 20, 2, fp);
        return SurfaceLook{clamped(mix(base.albedo, rusty, rust) * float(1 + 0.1 * grain.value)),
                           float(base.roughness * (1 + rust)), 0.001 * grain.gradient};
      });
}

Material sign_face(std::uint64_t seed) {
  Random random(seed);
  const Rgb field = random.chance(0.5) ? Rgb(0.5f, 0.04f, 0.04f) : Rgb(0.04f, 0.12f, 0.45f);
  const bool bar = random.chance(0.5);
  return diffuse(field, [field, bar](const TexturePoint& at, const SurfaceLook& base) {
    // uv: metres across the sign's face, centred; a white ring, the coloured field, a white bar
    const double fp = at.footprint, r = at.uv.norm();
    const double ring = line_coverage(r - 0.31, 0.04, fp);
    const double symbol =
        bar ? line_coverage(at.uv.y(), 0.05, fp) * line_coverage(at.uv.x(), 0.2, fp)
            : line_coverage(r, 0.08, fp);
    const float wet = base.albedo.maxCoeff() / field.maxCoeff();
    return SurfaceLook{mix(base.albedo, Rgb(0.8f, 0.8f, 0.8f) * wet, std::min(1.0, ring + symbol)),
                       base.roughness, Vec2::Zero()};
  });
}

Material signal_head(int lit) {
  // three lamps down the housing's faces (uv in metres from its centre)
  const auto lamp_cover = [](const TexturePoint& at, int k) {
    return line_coverage((at.uv - Vec2(0, 0.28 * (1 - k))).norm(), 0.09, at.footprint);
  };
  Material m =
      make(Material::Kind::Glossy, {0.04f, 0.04f, 0.04f}, 0.2f,
           [lamp_cover](const TexturePoint& at, const SurfaceLook& base) {
             const Rgb lamps[3] = {{0.6f, 0.05f, 0.03f}, {0.6f, 0.4f, 0.03f}, {0.05f, 0.5f, 0.2f}};
             Rgb colour = base.albedo;
             for (int k = 0; k < 3; ++k) colour = mix(colour, lamps[k], lamp_cover(at, k));
             return SurfaceLook{colour, base.roughness, Vec2::Zero()};
           });
  // 150 cd/m^2 over the lit lens: a night exposure clips its own channel, not the others (an LED
  // signal's 5000 would show white, where photos of streets at night show red and green)
  const Rgb glows[3] = {{1.0f, 0.06f, 0.02f}, {1.0f, 0.55f, 0.03f}, {0.02f, 1.0f, 0.3f}};
  m.night_emission = Rgb(1.5e-3f, 1.5e-3f, 1.5e-3f), m.glow_only = true;
  m.night_pattern = std::make_shared<const Pattern>(
      [lamp_cover, lit, glow = glows[lit]](const TexturePoint& at, const SurfaceLook& base) {
        return SurfaceLook{glow * float(lamp_cover(at, lit)), base.roughness, Vec2::Zero()};
      });
  return m;
}

Material timber(std::uint64_t seed) {
  return diffuse({0.35f, 0.26f, 0.17f}, [seed](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    const Noise rings = fbm({0.4 * at.uv.x(), 12 * at.uv.y()}, seed, 2, 4, fp);
    return scaled(base, (1 + 0.3 * rings.value) * (1 - 0.25 * blotches(at.uv, seed + 1, 0.7, fp)),
                  0.003 * rings.gradient);
  });
}

Material water() {
  Material m;
  m.kind = Material::Kind::Glossy, m.albedo = {0.02f, 0.05f, 0.07f}, m.roughness = 0.05f;
  m.pattern = std::make_shared<const Pattern>([](const TexturePoint& at, const SurfaceLook& base) {
    const Noise waves = fbm({at.uv.x(), 2 * at.uv.y()}, 99, 0.6, 5, at.footprint);
    return SurfaceLook{base.albedo, base.roughness, 0.04 * waves.gradient};
  });
  return m;
}

Material car_paint(std::uint64_t seed) {
  Random random(seed);
  static const Rgb kPopular[] = {
      {0.75f, 0.75f, 0.74f}, {0.03f, 0.03f, 0.035f}, {0.3f, 0.31f, 0.33f}, {0.5f, 0.03f, 0.03f},
      {0.04f, 0.1f, 0.35f},  {0.6f, 0.6f, 0.62f},    {0.05f, 0.2f, 0.08f}, {0.7f, 0.45f, 0.05f}};
  const Rgb colour = varied(random, kPopular[random.below(8)], 0.1);
  return make(
      Material::Kind::Glossy, colour, 0.05f,
      [seed](const TexturePoint& at, const SurfaceLook& base) {
        // panel gaps across the body every ~1.1 m, road dirt low down
        const double fp = at.footprint;
        const double gap =
            line_coverage(std::fmod(std::abs(at.position.x()) + 0.3, 1.1) - 0.55, 0.004, fp);
        const double dirt = smoothstep(0.55, 0.25, at.position.z()) *
                            (0.5 + 0.5 * fbm(at.uv, seed, 3, 3, fp).value);
        const Rgb grime(0.12f, 0.11f, 0.09f);
        return SurfaceLook{clamped(mix(base.albedo * float(1 - 0.7 * gap), grime, 0.6 * dirt)),
                           float(base.roughness + 0.4 * dirt), Vec2::Zero()};
      });
}

Material tyre(double width) {
  return diffuse(
      {0.035f, 0.035f, 0.035f}, [width](const TexturePoint& at, const SurfaceLook& base) {
        // the wheel's frame: the axle along y, the sidewalls at y = +-width / 2, u around the tread
        if (std::abs(at.position.y()) > width / 2 - 1e-3) return base;
        return scaled(base, 1 + 1.2 * pulse_train(at.uv.x(), 0.035, 0.012, at.footprint));
      });
}

Material wheel_rim(std::uint64_t seed) {
  Random random(seed);
  const Rgb metal = varied(random, {0.55f, 0.55f, 0.57f}, 0.3);
  const int spokes = 4 + random.below(4);
  return make(Material::Kind::Metal, metal, 0.3f,
              [spokes](const TexturePoint& at, const SurfaceLook& base) {
                // uv: metres from the axle on the rim's face; dark holes between the spokes
                const double r = at.uv.norm(), fp = at.footprint;
                const double turns = std::atan2(at.uv.y(), at.uv.x()) / (2 * kPi) * spokes;
                const double hole =
                    (1 - pulse_train(turns, 1, 0.4, fp / std::max(r, 1e-3) * spokes / (2 * kPi))) *
                    line_coverage(r - 0.14, 0.07, fp);
                return SurfaceLook{clamped(base.albedo * float(1 - 0.92 * hole)), base.roughness,
                                   Vec2::Zero()};
              });
}

Material vehicle_glass() {
  Material m;
  m.kind = Material::Kind::Metal, m.albedo = {0.2f, 0.22f, 0.25f}, m.roughness = 0.02f;
  return m;
}

Material lamp(const Rgb& colour, const Rgb& night_glow) {
  Material m;
  m.kind = Material::Kind::Glossy, m.albedo = colour, m.roughness = 0.02f;
  m.night_emission = night_glow, m.glow_only = true;
  return m;
}

Material street_lamp() {
  Material m;
  m.kind = Material::Kind::Glossy, m.albedo = {0.8f, 0.8f, 0.76f}, m.roughness = 0.3f;
  m.night_emission = Rgb(1.0f, 0.86f, 0.68f) * 0.02f, m.glow_only = true;
  return m;
}

Material number_plate(std::uint64_t seed) {
  return diffuse({0.75f, 0.75f, 0.7f}, [seed](const TexturePoint& at, const SurfaceLook& base) {
    // seven characters of seven-segment strokes, black on white (uv in metres, centred)
    const double fp = at.footprint, x = at.uv.x() + 0.22, y = at.uv.y();
    const int glyph = int(std::floor(x / 0.063));
    if (glyph < 0 || glyph >= 7 || std::abs(y) > 0.04) return base;
    const double cx = x - (glyph + 0.5) * 0.063;
    const std::uint64_t bits = mix_bits(seed + std::uint64_t(glyph));
    double ink = 0;
    const double horizontal[3] = {0.035, 0, -0.035};
    for (int k = 0; k < 3; ++k)
      if (bits >> k & 1)
        ink += line_coverage(y - horizontal[k], 0.004, fp) * line_coverage(cx, 0.018, fp);
    for (int k = 0; k < 4; ++k)
      if (bits >> (3 + k) & 1)
        ink += line_coverage(cx - (k % 2 ? 0.018 : -0.018), 0.004, fp) *
               line_coverage(y - (k < 2 ? 0.0175 : -0.0175), 0.0175, fp);
    return scaled(base, 1 - 0.9 * std::min(1.0, ink));
  });
}

Material clothing(std::uint64_t seed, bool trousers) {
  Random random(seed);
  const Rgb colour =
      trousers ? varied(random,
                        random.chance(0.5) ? Rgb(0.06f, 0.09f, 0.2f) : Rgb(0.1f, 0.09f, 0.08f), 0.5)
               : varied(random,
                        {float(random.uniform(0.05, 0.8)), float(random.uniform(0.05, 0.8)),
                         float(random.uniform(0.05, 0.8))},
                        0.2);
  const int weave = trousers ? 0 : random.below(3);  // plain, stripes, checks
  const double period = random.uniform(0.03, 0.09);
  return diffuse(colour, [seed, weave, period](const TexturePoint& at, const SurfaceLook& base) {
    const double fp = at.footprint;
    double f = 1 + 0.12 * fbm(at.uv, seed, 6, 3, fp).value;
    if (weave >= 1) f *= 1 - 0.45 * pulse_train(at.uv.y(), period, period / 2, fp);
    if (weave == 2) f *= 1 - 0.45 * pulse_train(at.uv.x(), period, period / 2, fp);
    return scaled(base, f);
  });
}

Material skin(std::uint64_t seed) {
  Random random(seed);
  const double tone = random.uniform(0.15, 0.85);
  const Rgb colour = mix({0.12f, 0.07f, 0.045f}, {0.62f, 0.45f, 0.36f}, tone);
  Material m;
  m.albedo = colour;
  return m;
}

Material hair(std::uint64_t seed) {
  Random random(seed);
  static const Rgb kShades[] = {
      {0.02f, 0.015f, 0.01f}, {0.09f, 0.05f, 0.025f}, {0.35f, 0.25f, 0.12f}, {0.4f, 0.4f, 0.4f}};
  Material m;
  m.albedo = kShades[random.below(4)];
  return m;
}

Rgb cargo_box_colour(std::uint64_t seed) {
  Random random(mix_bits(seed ^ 0x636172676full));  // "cargo"
  const double u = random.uniform();
  if (u < 0.55) return varied(random, {0.8f, 0.8f, 0.78f}, 0.04);
  if (u < 0.75) return varied(random, {0.55f, 0.56f, 0.57f}, 0.05);
  return popular_car_colour(random.bits());
}

Rgb popular_car_colour(std::uint64_t seed) {
  Random random(mix_bits(seed ^ 0x636f6c6f7572ull));  // "colour"
  // white, black, grey, silver, blue, red, green, beige, orange
  static const Rgb kColours[] = {
      {0.78f, 0.78f, 0.76f}, {0.025f, 0.025f, 0.028f}, {0.2f, 0.21f, 0.22f},
      {0.5f, 0.51f, 0.53f},  {0.04f, 0.09f, 0.3f},     {0.45f, 0.03f, 0.025f},
      {0.05f, 0.16f, 0.08f}, {0.5f, 0.42f, 0.3f},      {0.7f, 0.3f, 0.04f}};
  static const double kShares[] = {0.25, 0.2, 0.18, 0.14, 0.09, 0.08, 0.02, 0.02, 0.02};
  double u = random.uniform();
  int k = 0;
  while (k < 8 && (u -= kShares[k]) > 0) ++k;
  return varied(random, kColours[k], 0.06);
}

namespace {

SurfaceLook grimy(const TexturePoint& at, const SurfaceLook& base, std::uint64_t seed,
                  const Rgb& colour) {
  const double dirt = smoothstep(0.5, 0.15, at.position.z()) *
                      (0.5 + 0.5 * fbm(at.uv, seed, 3, 3, at.footprint).value);
  return SurfaceLook{clamped(mix(colour, Rgb(0.12f, 0.11f, 0.09f), 0.5 * dirt)),
                     float(base.roughness + 0.3 * dirt), Vec2::Zero()};
}

}  // namespace

Material body_paint(const Rgb& colour, std::uint64_t seed) {
  return make(Material::Kind::Glossy, colour, 0.04f,
              [seed](const TexturePoint& at, const SurfaceLook& base) {
                return grimy(at, base, seed, base.albedo);
              });
}

Material banded_paint(const Rgb& colour, const Rgb& band, double z0, double z1, bool checks,
                      std::uint64_t seed) {
  return make(Material::Kind::Glossy, colour, 0.04f,
              [=](const TexturePoint& at, const SurfaceLook& base) {
                const double fp = at.footprint, z = at.position.z();
                double in = line_coverage(z - (z0 + z1) / 2, (z1 - z0) / 2, fp);
                if (checks)  // two rows of squares, the band's height each half
                  in *= pulse_train(at.position.x() + (z > (z0 + z1) / 2 ? (z1 - z0) / 2 : 0),
                                    z1 - z0, (z1 - z0) / 2, fp);
                return grimy(at, base, seed, mix(base.albedo, band, float(in)));
              });
}

Material clear_glass(const Rgb& night_glow) {
  Material m;
  m.kind = Material::Kind::Window, m.albedo = {0.38f, 0.41f, 0.42f}, m.roughness = 0;
  m.night_emission = night_glow, m.glow_only = true;
  return m;
}

Material trim_plastic() {
  Material m;
  m.kind = Material::Kind::Glossy, m.albedo = {0.025f, 0.025f, 0.027f}, m.roughness = 0.3f;
  return m;
}

Material chrome() {
  Material m;
  m.kind = Material::Kind::Metal, m.albedo = {0.7f, 0.7f, 0.72f}, m.roughness = 0.08f;
  return m;
}

Material upholstery(std::uint64_t seed) {
  Random random(seed);
  Material m;
  m.albedo = varied(random, {0.05f, 0.05f, 0.05f}, 0.4);
  return m;
}

Material underbody() {
  Material m;
  m.albedo = {0.03f, 0.03f, 0.03f};
  return m;
}

Material grille() {
  return make(Material::Kind::Glossy, {0.02f, 0.02f, 0.022f}, 0.2f,
              [](const TexturePoint& at, const SurfaceLook& base) {
                // horizontal slats with dark gaps (uv in metres over the patch)
                const double slat = pulse_train(at.uv.y(), 0.03, 0.012, at.footprint);
                return scaled(base, 0.4 + 1.6 * slat);
              });
}

Material shoes(std::uint64_t seed) {
  Random random(seed);
  static const Rgb kShoes[] = {
      {0.02f, 0.02f, 0.02f}, {0.15f, 0.08f, 0.04f}, {0.7f, 0.7f, 0.68f}, {0.08f, 0.08f, 0.12f}};
  Material m;
  m.kind = Material::Kind::Glossy, m.roughness = 0.4f;
  m.albedo = varied(random, kShoes[random.below(4)], 0.1);
  return m;
}

Material bag(std::uint64_t seed) {
  Random random(seed);
  Material m;
  m.albedo = varied(random,
                    {float(random.uniform(0.02, 0.4)), float(random.uniform(0.02, 0.3)),
                     float(random.uniform(0.02, 0.3))},
                    0.2);
  return m;
}

Material umbrella(std::uint64_t seed) {
  Random random(seed);
  static const Rgb kCanopies[] = {
      {0.02f, 0.02f, 0.02f}, {0.03f, 0.06f, 0.25f}, {0.4f, 0.03f, 0.03f}, {0.5f, 0.45f, 0.05f}};
  Material m;
  m.kind = Material::Kind::Glossy, m.roughness = 0.2f;
  m.albedo = varied(random, kCanopies[random.below(4)], 0.1);
  return m;
}

Material eyes() {
  Material m;
  m.albedo = {0.02f, 0.015f, 0.012f};
  return m;
}

}  // namespace flowscape::city_materials
