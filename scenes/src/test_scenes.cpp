#include "flowscape/scenes/test_scenes.h"

#include <cmath>

namespace flowscape {

Scene box_room(float half) {
  Scene scene;
  Mesh& m = scene.world;
  add_box(m, Eigen::Vector3f::Constant(-half), Eigen::Vector3f::Constant(half),
          SemanticClass::Building, true);
  // floor and ceiling classes: the triangles whose three vertices share z = -half or z = +half
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const float z0 = m.vertices[m.triangles[t][0]].z(), z1 = m.vertices[m.triangles[t][1]].z(),
                z2 = m.vertices[m.triangles[t][2]].z();
    if (z0 == z1 && z1 == z2) m.classes[t] = z0 < 0 ? SemanticClass::Road : SemanticClass::Other;
  }
  return scene;
}

Scene textured_plane(double distance, double side) {
  Scene scene;
  const float d = float(distance), h = float(side / 2);
  scene.world.vertices = {{d, -h, -h}, {d, h, -h}, {d, h, h}, {d, -h, h}};
  scene.world.triangles = {{0, 2, 1}, {0, 3, 2}};
  scene.world.classes = {SemanticClass::Wall, SemanticClass::Wall};
  return scene;
}

Actor sliding_box(const Eigen::Vector3d& centre, const Eigen::Vector3d& velocity,
                  std::uint16_t material) {
  Actor box{7, {}, [centre, velocity](double t) {
              return Pose(Eigen::Translation3d(centre + velocity * t));
            }};
  Mesh body;
  add_box(body, Eigen::Vector3f::Constant(-1), Eigen::Vector3f::Constant(1),
          SemanticClass::Vehicles);
  body.materials.assign(body.triangles.size(), material);
  box.parts.push_back(rigid_part(std::move(body)));
  return box;
}

Scene moving_box(const Eigen::Vector3d& centre, const Eigen::Vector3d& velocity) {
  Scene scene = box_room(20);
  scene.actors.push_back(sliding_box(centre, velocity));
  return scene;
}

std::shared_ptr<const Pattern> checker(double size, const Eigen::Vector3f& contrast) {
  return std::make_shared<const Pattern>(
      [size, contrast](const TexturePoint& at, const SurfaceLook& base) {
        const Vec3 cell = (at.position / size).array() + 0.5;
        const long parity =
            long(std::floor(cell.x())) + long(std::floor(cell.y())) + long(std::floor(cell.z()));
        SurfaceLook look = base;
        if (parity & 1) look.albedo = base.albedo.cwiseProduct(contrast);
        return look;
      });
}

}  // namespace flowscape
