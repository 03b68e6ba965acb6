// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target for the structuring-element text form ("ball:r=1/20,level=1"): any text is
// either a valid SE, a closed outward exact mesh, or a StructuringElementError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "morphex/check.h"
#include "morphex/structuring_element.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace morphex;
  morphex::fuzz::limit_inputs();
  const std::string text(reinterpret_cast<const char*>(data), size);
  morphex::fuzz::expect_only<StructuringElementError>([&] {
    const StructuringElement se = parse_structuring_element(text);
    if (!check_mesh(se.mesh).valid_solid())
      morphex::fuzz::finding("an accepted structuring element is not a valid solid");
  });
  return 0;
}
