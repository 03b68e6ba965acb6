// Reads a mesh, checks it and prints its exact volume, through the installed morphex package.
#include <iostream>

#include "morphex/check.h"
#include "morphex/io.h"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const morphex::Mesh mesh = morphex::read_mesh(argv[1]);
  const morphex::MeshReport report = morphex::check_mesh(mesh);
  std::cout << "valid " << report.valid_solid() << " volume "
            << morphex::to_rational_string(report.volume) << '\n';
  return report.valid_solid() ? 0 : 1;
}
