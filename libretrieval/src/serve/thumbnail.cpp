// SPDX-License-Identifier: GPL-3.0-or-later
#include "thumbnail.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace morphex::serve {
namespace {

using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec normalised(const Vec& v) {
  const double n = std::sqrt(dot(v, v));
  return n > 0 ? Vec{v[0] / n, v[1] / n, v[2] / n} : Vec{0, 0, 0};
}

// The camera frame of three.js's lookAt with up = +y: `right` and `up` span the screen, `toward`
// points at the viewer.
struct Camera {
  Vec right, up, toward;
};
Camera camera() {
  Camera c;
  c.toward = normalised({kViewDirection[0], kViewDirection[1], kViewDirection[2]});
  c.right = normalised(cross({0, 1, 0}, c.toward));
  c.up = cross(c.toward, c.right);
  return c;
}

// A sample buffer: colour, whether a face covers the sample, and its depth (larger is nearer).
struct Samples {
  int size;
  std::vector<float> rgb, depth;
  explicit Samples(int n)
      : size(n),
        rgb(std::size_t(n) * n * 3, 0.0f),
        depth(std::size_t(n) * n, -std::numeric_limits<float>::infinity()) {}
};

struct ScreenVertex {
  double x, y, depth;
};

// Fills the samples whose centres lie in the triangle and are nearer than what is there.
void fill_triangle(Samples& s, const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c,
                   const float colour[3]) {
  const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (std::abs(area) < 1e-12) return;  // seen edge-on
  const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
  const int x1 = std::min(s.size - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
  const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
  const int y1 = std::min(s.size - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      // Barycentric weights from the edge functions, the same sign as the area inside.
      const double wa = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
      const double wb = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
      const double wc = 1 - wa - wb;
      if (wa < 0 || wb < 0 || wc < 0) continue;
      const float depth = float(wa * a.depth + wb * b.depth + wc * c.depth);
      const std::size_t i = std::size_t(y) * s.size + x;
      if (depth <= s.depth[i]) continue;
      s.depth[i] = depth;
      std::copy(colour, colour + 3, s.rgb.begin() + std::ptrdiff_t(i * 3));
    }
}

void append_u32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out += char((v >> shift) & 0xff);  // big-endian
}

void append_chunk(std::string& png, const char type[4], const std::string& data) {
  append_u32(png, std::uint32_t(data.size()));
  const std::string typed = std::string(type, 4) + data;
  png += typed;
  append_u32(png, std::uint32_t(
                      crc32(0L, reinterpret_cast<const Bytef*>(typed.data()), uInt(typed.size()))));
}

}  // namespace

Image render_thumbnail(const DoubleMesh& mesh, int size, int supersample) {
  const Camera cam = camera();
  const int n = size * supersample;
  Samples samples(n);
  // The orthographic fit: the bounds of the mesh on the screen, with a margin.
  double lo_x = std::numeric_limits<double>::infinity(), hi_x = -lo_x, lo_y = lo_x, hi_y = -lo_x;
  std::vector<ScreenVertex> screen(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    const Vec& p = mesh.points[i];
    screen[i] = {dot(p, cam.right), dot(p, cam.up), dot(p, cam.toward)};
    lo_x = std::min(lo_x, screen[i].x);
    hi_x = std::max(hi_x, screen[i].x);
    lo_y = std::min(lo_y, screen[i].y);
    hi_y = std::max(hi_y, screen[i].y);
  }
  const double extent = std::max(hi_x - lo_x, hi_y - lo_y);
  if (!mesh.triangles.empty() && extent > 0 && std::isfinite(extent)) {
    const double scale = n * 0.9 / extent, mid_x = (lo_x + hi_x) / 2, mid_y = (lo_y + hi_y) / 2;
    for (ScreenVertex& v : screen) {
      v.x = n / 2.0 + (v.x - mid_x) * scale;
      v.y = n / 2.0 - (v.y - mid_y) * scale;  // image rows go down
    }
    // A light from above, a little to the right and in front, fixed in the world as the view
    // is, and a light from the viewer: faces of different directions get distinct shades, and
    // no face in view is dark.
    const Vec light = normalised({0.35, 1.0, 0.6});
    const float front[3] = {0.42f, 0.62f, 0.9f}, back[3] = {0.9f, 0.5f, 0.36f};
    for (const Triangle& t : mesh.triangles) {
      const Vec& a = mesh.points[t[0]];
      Vec normal = normalised(cross(sub(mesh.points[t[1]], a), sub(mesh.points[t[2]], a)));
      const bool facing = dot(normal, cam.toward) >= 0;
      if (!facing) normal = {-normal[0], -normal[1], -normal[2]};
      const float shade =
          float(0.5 + 0.3 * std::max(0.0, dot(normal, light)) + 0.2 * dot(normal, cam.toward));
      const float* base = facing ? front : back;
      const float colour[3] = {base[0] * shade, base[1] * shade, base[2] * shade};
      fill_triangle(samples, screen[t[0]], screen[t[1]], screen[t[2]], colour);
    }
  }
  Image image;
  image.width = image.height = size;
  image.rgba.assign(std::size_t(size) * size * 4, 0);
  const float per_pixel = float(supersample * supersample);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      float rgb[3] = {0, 0, 0};
      int covered = 0;
      for (int sy = 0; sy < supersample; ++sy)
        for (int sx = 0; sx < supersample; ++sx) {
          const std::size_t i = std::size_t(y * supersample + sy) * n + x * supersample + sx;
          if (!std::isfinite(samples.depth[i])) continue;
          ++covered;
          for (int c = 0; c < 3; ++c) rgb[c] += samples.rgb[i * 3 + c];
        }
      if (covered == 0) continue;
      std::uint8_t* out = &image.rgba[(std::size_t(y) * size + x) * 4];
      for (int c = 0; c < 3; ++c)
        out[c] = std::uint8_t(std::lround(std::clamp(rgb[c] / covered, 0.0f, 1.0f) * 255));
      out[3] = std::uint8_t(std::lround(covered / per_pixel * 255));
    }
  return image;
}

std::string encode_png(const Image& image) {
  // Each row: filter type 0 (none), then its RGBA bytes.
  const std::size_t row = std::size_t(image.width) * 4;
  std::string raw;
  raw.reserve((row + 1) * image.height);
  for (int y = 0; y < image.height; ++y) {
    raw += '\0';
    raw.append(reinterpret_cast<const char*>(image.rgba.data()) + y * row, row);
  }
  uLongf packed_size = compressBound(uLong(raw.size()));
  std::string packed(packed_size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size,
                reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()),
                Z_BEST_COMPRESSION) != Z_OK)
    throw std::runtime_error("png: zlib failed to compress the image");
  packed.resize(packed_size);
  std::string header;
  append_u32(header, std::uint32_t(image.width));
  append_u32(header, std::uint32_t(image.height));
  header += std::string("\x08\x06\x00\x00\x00", 5);  // 8 bits, RGBA, deflate, filters, no interlace
  std::string png = "\x89PNG\r\n\x1a\n";
  append_chunk(png, "IHDR", header);
  append_chunk(png, "IDAT", packed);
  append_chunk(png, "IEND", "");
  return png;
}

}  // namespace morphex::serve
