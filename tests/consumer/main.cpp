// The README's example: a downstream project that links morphex::bool through find_package.
// Reads two meshes, checks them into Solids, subtracts them exactly and prints the exact volume.
#include <iostream>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/io.h"
#include "morphex/solid.h"

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  try {
    // read_mesh throws morphex::InputError, check_solid morphex::InvalidSolid (an InputError).
    const morphex::Solid a = morphex::check_solid(morphex::read_mesh(argv[1]), argv[1]);
    const morphex::Solid b = morphex::check_solid(morphex::read_mesh(argv[2]), argv[2]);
    const morphex::BooleanResult r = morphex::compute_boolean(a, b, morphex::BooleanOp::Difference);
    const morphex::MeshReport report = morphex::check_mesh(r.solid);
    std::cout << "valid " << report.valid_solid() << " volume "
              << morphex::to_rational_string(report.volume) << '\n';
    return report.valid_solid() ? 0 : 1;
  } catch (const morphex::InputError& e) {
    std::cerr << e.what() << '\n';
    return 2;
  }
}
