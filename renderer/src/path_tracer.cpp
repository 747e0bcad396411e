// A unidirectional path tracer in the manner of Embree's tutorials.
#include "path_tracer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace flowscape {
namespace {

using Rgb = Eigen::Vector3d;

std::uint64_t mix_bits(std::uint64_t x) {  // splitmix64 finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

double unit(std::uint64_t bits) { return double(bits >> 11) * 0x1.0p-53; }

// Sample `index` of a pixel: the R2 sequence (Roberts 2018) for each pair of dimensions, shifted
// by a hash of the pixel, the seed and the pair (Cranley-Patterson rotation).
class Sampler {
 public:
  Sampler(std::uint64_t pixel_key, int index) : key_(pixel_key), index_(index) {}
  Vec2 next() {
    constexpr double kA1 = 0.7548776662466927, kA2 = 0.5698402909980532;  // 1/phi2, 1/phi2^2
    const std::uint64_t h = mix_bits(key_ ^ mix_bits(std::uint64_t(++pair_)));
    const double n = index_ + 1;
    const double a = unit(h) + n * kA1, b = unit(mix_bits(h)) + n * kA2;
    return {a - std::floor(a), b - std::floor(b)};
  }

 private:
  std::uint64_t key_;
  int index_, pair_ = 0;
};

// Orthonormal frame around n (Duff et al. 2017).
Mat3 frame_around(const Vec3& n) {
  const double sign = std::copysign(1.0, n.z()), a = -1 / (sign + n.z()), b = n.x() * n.y() * a;
  Mat3 m;
  m.col(0) = Vec3(1 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  m.col(1) = Vec3(b, sign + n.y() * n.y() * a, -n.y());
  m.col(2) = n;
  return m;
}

Vec3 cosine_direction(const Vec3& n, Vec2 u) {
  const double r = std::sqrt(u.x()), phi = 2 * kPi * u.y();
  return frame_around(n) *
         Vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u.x())));
}

// A direction within `angle` of `axis`, uniform over that cone's solid angle.
Vec3 cone_direction(const Vec3& axis, double angle, Vec2 u) {
  const double cos_t = 1 - u.x() * (1 - std::cos(angle)), sin_t = std::sqrt(1 - cos_t * cos_t);
  const double phi = 2 * kPi * u.y();
  return frame_around(axis) * Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
}

Vec3 reflect(const Vec3& d, const Vec3& n) { return d - 2 * d.dot(n) * n; }

double schlick(double cos_i, double f0) { return f0 + (1 - f0) * std::pow(1 - cos_i, 5); }

// Fresnel reflectance of a smooth dielectric; 1 for total internal reflection.
double dielectric_fresnel(double cos_i, double eta) {  // eta = n_incident / n_transmitted
  const double sin2_t = eta * eta * (1 - cos_i * cos_i);
  if (sin2_t >= 1) return 1;
  const double cos_t = std::sqrt(1 - sin2_t);
  const double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const double rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return (rs * rs + rp * rp) / 2;
}

Rgb sky_radiance(const Environment& e, const Vec3& d) {
  if (d.z() < 0) return e.ground.cast<double>();
  const double t = std::sqrt(d.z());
  return ((1 - t) * e.sky_horizon + t * e.sky_zenith).cast<double>();
}

// Radiance of the sun disc seen along d (irradiance spread over the disc's solid angle).
Rgb sun_radiance(const Environment& e, const Vec3& d) {
  const double cone = std::cos(e.sun_angular_radius);
  if (d.dot(e.sun_direction) < cone) return Rgb::Zero();
  return e.sun_irradiance.cast<double>() / (2 * kPi * (1 - cone));
}

struct Surface {
  Vec3 position, normal;  // normal faces the incoming ray
  bool front;             // the ray arrives from the side the geometric normal points to
  const Material* material;
  Rgb albedo;
};

Surface surface_at(const EmbreeScene& embree, const Hit& hit, const Vec3& origin, const Vec3& dir) {
  const MeshRef& ref = embree.mesh(hit.mesh);
  const Eigen::Vector3i& tri = ref.mesh->triangles[hit.triangle];
  const Vec3 v0 = ref.mesh->vertices[tri[0]].cast<double>(),
             v1 = ref.mesh->vertices[tri[1]].cast<double>(),
             v2 = ref.mesh->vertices[tri[2]].cast<double>();
  const Pose& pose = embree.pose_now(hit.mesh);
  Vec3 normal = (pose.linear() * (v1 - v0).cross(v2 - v0)).normalized();
  const bool front = normal.dot(dir) < 0;
  if (!front) normal = -normal;
  const Vec3 position = origin + hit.distance * dir;
  const auto& materials = embree.scene().materials;
  const Material& m =
      materials[ref.mesh->materials.empty() ? 0 : ref.mesh->materials[hit.triangle]];
  Rgb albedo = m.albedo.cast<double>();
  // checker cells are centred on multiples of the size, so planes there are not split
  if (m.checker_size > 0) {
    const Vec3 cell = ((pose.inverse() * position) / m.checker_size).array() + 0.5;
    const long parity =
        long(std::floor(cell.x())) + long(std::floor(cell.y())) + long(std::floor(cell.z()));
    if (parity & 1) albedo = m.checker_albedo.cast<double>();
  }
  return {position, normal, front, &m, albedo};
}

// Direct light from the sun on a diffuse surface (the sun is too small to hit by chance).
Rgb sun_light(const EmbreeScene& embree, const Surface& s, const Vec3& origin, Vec2 u,
              std::uint64_t& rays) {
  const Environment& e = embree.scene().environment;
  const Vec3 to_sun = cone_direction(e.sun_direction, e.sun_angular_radius, u);
  const double cos_n = to_sun.dot(s.normal);
  if (cos_n <= 0) return Rgb::Zero();
  ++rays;
  if (embree.occluded(false, origin, to_sun, std::numeric_limits<double>::infinity()))
    return Rgb::Zero();
  return s.albedo.cwiseProduct(e.sun_irradiance.cast<double>()) * (cos_n / kPi);
}

Rgb trace_path(const EmbreeScene& embree, Vec3 origin, Vec3 dir, int max_bounces, Sampler& sampler,
               std::uint64_t& rays) {
  const Environment& env = embree.scene().environment;
  Rgb radiance = Rgb::Zero(), throughput = Rgb::Ones();
  bool sun_visible = true;  // camera rays and specular bounces may see the sun disc itself
  for (int bounce = 0; bounce <= max_bounces; ++bounce) {
    const Hit hit = embree.intersect(origin, dir);
    ++rays;
    if (!hit.found) {
      radiance += throughput.cwiseProduct(sky_radiance(env, dir) +
                                          (sun_visible ? sun_radiance(env, dir) : Rgb::Zero()));
      break;
    }
    const Surface s = surface_at(embree, hit, origin, dir);
    const Material& m = *s.material;
    if (m.kind == Material::Kind::Emissive) {
      radiance += throughput.cwiseProduct(m.emission.cast<double>());
      break;
    }
    const double offset = 1e-4 * (1 + s.position.norm());
    const Vec3 above = s.position + offset * s.normal, below = s.position - offset * s.normal;
    const Vec2 light_sample = sampler.next(), lobe_sample = sampler.next(), choice = sampler.next();
    const double cos_i = -dir.dot(s.normal);
    bool diffuse = m.kind == Material::Kind::Diffuse;
    if (m.kind == Material::Kind::Glossy)
      diffuse = choice.x() >= schlick(cos_i, 0.04);  // coat or base
    if (diffuse) {
      radiance += throughput.cwiseProduct(sun_light(embree, s, above, light_sample, rays));
      throughput = throughput.cwiseProduct(s.albedo);
      origin = above, dir = cosine_direction(s.normal, lobe_sample), sun_visible = false;
    } else if (m.kind == Material::Kind::Glass) {
      const double eta = s.front ? 1 / 1.5 : 1.5;
      if (choice.x() < dielectric_fresnel(cos_i, eta)) {
        origin = above, dir = reflect(dir, s.normal);
      } else {
        const double cos_t = std::sqrt(1 - eta * eta * (1 - cos_i * cos_i));
        origin = below, dir = (eta * dir + (eta * cos_i - cos_t) * s.normal).normalized();
      }
      sun_visible = true;
    } else {  // Metal, or the clear coat of Glossy: a mirror blurred by the roughness
      if (m.kind == Material::Kind::Metal) throughput = throughput.cwiseProduct(s.albedo);
      dir = (reflect(dir, s.normal) + m.roughness * cosine_direction(s.normal, lobe_sample))
                .normalized();
      if (dir.dot(s.normal) <= 0) break;
      origin = above, sun_visible = true;
    }
    if (bounce >= 3) {  // Russian roulette
      const double keep = std::clamp(throughput.maxCoeff(), 0.05, 0.95);
      if (choice.y() >= keep) break;
      throughput /= keep;
    }
  }
  return radiance;
}

}  // namespace

Image<float> path_trace(EmbreeScene& embree, const Projection& projection, const FramePair& frames,
                        const RenderOptions& options, RenderStats* stats) {
  embree.set_times(frames.time, frames.next_time);
  const int W = projection.width, H = projection.height;
  Image<float> image(W, H, 3);
  const Vec3 origin = frames.rig.translation();
  const Mat3 rotation = frames.rig.linear();
  std::atomic<std::uint64_t> rays{0};
  tbb::parallel_for(0, H, [&](int y) {
    std::uint64_t row_rays = 0;
    for (int x = 0; x < W; ++x) {
      const std::uint64_t key =
          mix_bits(options.seed ^ mix_bits((std::uint64_t(y) << 32) | unsigned(x)));
      Rgb sum = Rgb::Zero();
      for (int i = 0; i < options.samples_per_pixel; ++i) {
        Sampler sampler(key, i);
        const Vec2 jitter = sampler.next();
        const Vec3 dir = (rotation * projection.ray(Vec2(x, y) + jitter)).normalized();
        sum += trace_path(embree, origin, dir, options.max_bounces, sampler, row_rays);
      }
      const Rgb mean = sum / std::max(1, options.samples_per_pixel);
      for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = float(mean[c]);
    }
    rays += row_rays;
  });
  if (stats) stats->rays = rays;
  return image;
}

}  // namespace flowscape
