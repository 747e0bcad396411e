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

Scene sunlit_street() {
  Scene scene = textured_plane(10, 60);
  Material wall;
  wall.albedo = {0.8f, 0.5f, 0.2f};
  wall.pattern = checker(1, {0.0625f, 0.2f, 1.5f});  // cells of (0.05, 0.1, 0.3)
  Material paint;
  paint.kind = Material::Kind::Glossy, paint.albedo = {0.1f, 0.6f, 0.1f};
  scene.materials = {Material{}, wall, paint};
  scene.world.materials = {1, 1};
  Mesh ground;
  add_box(ground, Eigen::Vector3f(-50, -50, -1.8f), Eigen::Vector3f(50, 50, -1.7f),
          SemanticClass::Road);
  for (std::size_t t = 0; t < ground.triangles.size(); ++t) {
    scene.world.triangles.push_back(ground.triangles[t] +
                                    Eigen::Vector3i::Constant(int(scene.world.vertices.size())));
    scene.world.classes.push_back(SemanticClass::Road);
    scene.world.materials.push_back(0);
  }
  scene.world.vertices.insert(scene.world.vertices.end(), ground.vertices.begin(),
                              ground.vertices.end());
  scene.actors.push_back(sliding_box({6, 1, -0.7}, {0, -3, 0}, 2));
  scene.environment.sun_direction = Vec3(-0.5, 0.3, 0.8).normalized();  // lights the wall's face
  return scene;
}

}  // namespace flowscape
