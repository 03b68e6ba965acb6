// SPDX-License-Identifier: GPL-3.0-or-later
// Thumbnails of indexed meshes, rendered by the server: a z-buffered, flat-shaded software
// rasteriser and a PNG encoder (zlib's deflate and crc32).
//
// Why on the server: the page lists every mesh of the index, and browsers cap the WebGL contexts
// a page may hold (about 16), so one 3D view per thumbnail does not scale; a small PNG per mesh
// is cached by the server and the browser, needs no GPU, and looks the same in the headless
// browser of the tests.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "morphex/mesh.h"

namespace morphex::serve {

// The direction from the mesh towards the viewer (y up, as in three.js); the page's 3D view
// starts from the same side, so that a thumbnail and its view look alike.
inline constexpr std::array<double, 3> kViewDirection = {0.62, 0.48, 0.62};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // row-major, top row first, straight (not premultiplied) alpha
};

// The mesh seen along -kViewDirection by an orthographic camera that fits its bounds in a square
// of `size` pixels, on a transparent background. Each pixel averages `supersample`^2 samples, so
// that edges are smooth. Faces turned away from the viewer (an open or inward mesh shows its
// inside) are tinted in another colour.
Image render_thumbnail(const DoubleMesh& mesh, int size = 96, int supersample = 3);

// The image as a PNG file (8-bit RGBA, not interlaced).
std::string encode_png(const Image& image);

}  // namespace morphex::serve
