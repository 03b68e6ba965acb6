// SPDX-License-Identifier: GPL-3.0-or-later
// The page of `morphex serve` (libretrieval/web: its HTML, script and style sheet), compiled into
// the program by web/embed.cmake, so that it works from the build tree and after installing
// without a data folder to find.
#pragma once

#include <cstddef>
#include <vector>

namespace morphex::serve {

struct WebAsset {
  const char* route;  // "/", "/app.js", ...
  const char* type;   // its Content-Type
  const unsigned char* data;
  std::size_t size;
};
const std::vector<WebAsset>& web_assets();

}  // namespace morphex::serve
