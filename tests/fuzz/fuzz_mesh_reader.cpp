// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for one mesh reader (MORPHEX_FUZZ_FORMAT: Off, Obj, Stl or Ply; OFF covers the
// exact rational form, STL and PLY their ASCII and binary forms). A reader may reject its input,
// but only with InputError; every mesh it accepts then goes through the validity check that every
// command runs on its inputs, so that check sees the same hostile meshes.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "morphex/check.h"
#include "morphex/io.h"

#ifndef MORPHEX_FUZZ_FORMAT
#error "define MORPHEX_FUZZ_FORMAT to Off, Obj, Stl or Ply"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace morphex;
  morphex::fuzz::limit_inputs();
  const std::string content(reinterpret_cast<const char*>(data), size);
  morphex::fuzz::expect_only<InputError>([&] {
    const Mesh mesh = read_mesh_from_string(content, MeshFormat::MORPHEX_FUZZ_FORMAT, "fuzz");
    const MeshReport report = check_mesh(mesh);
    // The report must be self-consistent: a valid solid has no problem to describe.
    if (report.valid_solid() != describe_problems(report).empty())
      morphex::fuzz::finding("check_mesh and describe_problems disagree");
  });
  return 0;
}
