// The README's example: a downstream project that links morphex::bool through find_package.
// Reads two meshes, unites them exactly and prints the exact volume of the result.
#include <iostream>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/io.h"

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  const morphex::Mesh a = morphex::read_mesh(argv[1]);  // throws morphex::InputError
  const morphex::Mesh b = morphex::read_mesh(argv[2]);
  const morphex::BooleanResult r = morphex::compute_boolean(a, b, morphex::BooleanOp::Difference);
  if (!r.ok()) {
    std::cerr << r.message << '\n';
    return 1;
  }
  const morphex::MeshReport report = morphex::check_mesh(r.mesh);
  std::cout << "valid " << report.valid_solid() << " volume "
            << morphex::to_rational_string(report.volume) << '\n';
  return report.valid_solid() ? 0 : 1;
}
