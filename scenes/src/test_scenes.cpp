#include "flowscape/test_scenes.h"

namespace flowscape {

void add_box(Mesh& mesh, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, SemanticClass cls,
             bool inward) {
  const int base = int(mesh.vertices.size());
  for (int k = 0; k < 8; ++k)
    mesh.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                               k & 4 ? hi.z() : lo.z());
  // two triangles per side, counter-clockwise seen from outside
  const int sides[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& s : sides)
    for (const Eigen::Vector3i& t :
         {Eigen::Vector3i(s[0], s[1], s[2]), Eigen::Vector3i(s[0], s[2], s[3])}) {
      const Eigen::Vector3i tri = inward ? Eigen::Vector3i(t[0], t[2], t[1]) : t;
      mesh.triangles.push_back(tri + Eigen::Vector3i::Constant(base));
      mesh.classes.push_back(cls);
    }
}

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

Scene moving_box(const Eigen::Vector3d& centre, const Eigen::Vector3d& velocity) {
  Scene scene = box_room(20);
  Actor box{7, {}, [centre, velocity](double t) {
              return Pose(Eigen::Translation3d(centre + velocity * t));
            }};
  Part body{{}, fixed_pose()};
  add_box(body.mesh, Eigen::Vector3f::Constant(-1), Eigen::Vector3f::Constant(1),
          SemanticClass::Vehicles);
  box.parts.push_back(std::move(body));
  scene.actors.push_back(std::move(box));
  return scene;
}

}  // namespace flowscape
