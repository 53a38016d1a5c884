// Loads an SDF file with libsdformat (the parser Gazebo itself uses) and prints what it read,
// one line per model, for tests/test_export_sdf.py: exit 1 and the parser's errors on stderr
// when the file does not load.
//   g++ -O0 sdf_check.cpp $(pkg-config --cflags --libs sdformat12) -o sdf_check
#include <iostream>

#include <sdf/Collision.hh>
#include <sdf/Geometry.hh>
#include <sdf/Link.hh>
#include <sdf/Mesh.hh>
#include <sdf/Model.hh>
#include <sdf/Root.hh>
#include <sdf/Visual.hh>
#include <sdf/World.hh>

static void print_model(const sdf::Model *model, int depth) {
  std::cout << "model " << model->Name() << " depth=" << depth
            << " static=" << model->Static() << " links=" << model->LinkCount();
  if (model->LinkCount() > 0) {
    const sdf::Link *link = model->LinkByIndex(0);
    const auto &inertial = link->Inertial();
    const auto moi = inertial.Moi();
    std::cout << " mass=" << inertial.MassMatrix().Mass()
              << " ixx=" << moi(0, 0) << " iyy=" << moi(1, 1) << " izz=" << moi(2, 2)
              << " collisions=" << link->CollisionCount();
    if (link->VisualCount() > 0) {
      const sdf::Mesh *mesh = link->VisualByIndex(0)->Geom()->MeshShape();
      if (mesh != nullptr) std::cout << " mesh=" << mesh->Uri();
    }
  }
  std::cout << "\n";
  for (uint64_t i = 0; i < model->ModelCount(); ++i)
    print_model(model->ModelByIndex(i), depth + 1);
}

int main(int argc, char **argv) {
  if (argc != 2) {
    std::cerr << "usage: sdf_check FILE.sdf\n";
    return 2;
  }
  sdf::Root root;
  const sdf::Errors errors = root.Load(argv[1]);
  for (const auto &e : errors) std::cerr << e << "\n";
  if (!errors.empty()) return 1;
  std::cout << "version " << root.Version() << "\n";
  for (uint64_t w = 0; w < root.WorldCount(); ++w) {
    const sdf::World *world = root.WorldByIndex(w);
    std::cout << "world " << world->Name() << " models=" << world->ModelCount() << "\n";
    for (uint64_t i = 0; i < world->ModelCount(); ++i) print_model(world->ModelByIndex(i), 0);
  }
  if (root.Model() != nullptr) print_model(root.Model(), 0);
  return 0;
}
