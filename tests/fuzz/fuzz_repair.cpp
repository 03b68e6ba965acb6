// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for the exact repair: any OFF text (plain or exact) that the reader accepts
// goes through repair_mesh, which may refuse it only with InputError; what it returns must be a
// valid solid. Hostile meshes (degenerate, repeated, crossing, inside-out, non-manifold) are
// exactly what repair is for.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "morphex/check.h"
#include "morphex/io.h"
#include "morphex/repair.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace morphex;
  morphex::fuzz::limit_inputs();
  const std::string content(reinterpret_cast<const char*>(data), size);
  morphex::fuzz::expect_only<InputError>([&] {
    const Mesh mesh = read_mesh_from_string(content, MeshFormat::Off, "fuzz");
    if (mesh.num_triangles() > 2000) return;  // the arrangement of big soups is not a reader bug
    const RepairResult r = repair_mesh(mesh);
    if (!check_mesh(r.solid, kValidityOnly).valid_solid())
      morphex::fuzz::finding("repair_mesh returned a mesh that is not a valid solid");
  });
  return 0;
}
