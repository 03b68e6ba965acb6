// SPDX-License-Identifier: GPL-3.0-or-later
// glTF 2.0 binary (.glb), written for viewers (browsers, Blender, model viewers): a 12-byte
// header, a JSON chunk describing one mesh, and a BIN chunk with float32 positions and uint32
// triangle indices. No library needed; written only (morphex reads solids, not scenes).
#include <charconv>
#include <cstring>
#include <limits>
#include <ostream>

#include "mesh/io_text.h"

namespace morphex::detail {
namespace {

void append_u32(std::string& out, std::uint32_t v) {
  char bytes[4];
  std::memcpy(bytes, &v, 4);  // glb is little-endian, as every platform morphex builds on
  out.append(bytes, 4);
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string json_number(float v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, double(v));
  return std::string(buffer, r.ptr);
}

// The JSON chunk: one scene, one node, one mesh of one indexed triangle primitive. An empty mesh
// is a scene without nodes (accessors must not be empty).
std::string gltf_json(std::size_t vertices, std::size_t indices, const float lo[3],
                      const float hi[3], const std::string& note) {
  const std::size_t positions_bytes = vertices * 12, index_bytes = indices * 4;
  std::string j = "{\"asset\":{\"version\":\"2.0\",\"generator\":" +
                  json_string(std::string("morphex ") + version()) +
                  ",\"extras\":{\"provenance\":" + json_string(note) + "}},\"scene\":0,";
  if (vertices == 0 || indices == 0) return j + "\"scenes\":[{\"nodes\":[]}]}";
  j += "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
       "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
       "\"mode\":4}]}],";
  j += "\"buffers\":[{\"byteLength\":" + std::to_string(positions_bytes + index_bytes) + "}],";
  j += "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":" +
       std::to_string(positions_bytes) +
       ",\"target\":34962},{\"buffer\":0,\"byteOffset\":" + std::to_string(positions_bytes) +
       ",\"byteLength\":" + std::to_string(index_bytes) + ",\"target\":34963}],";
  j += "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":" +
       std::to_string(vertices) + ",\"type\":\"VEC3\",\"min\":[" + json_number(lo[0]) + "," +
       json_number(lo[1]) + "," + json_number(lo[2]) + "],\"max\":[" + json_number(hi[0]) + "," +
       json_number(hi[1]) + "," + json_number(hi[2]) +
       "]},{\"bufferView\":1,\"componentType\":5125,\"count\":" + std::to_string(indices) +
       ",\"type\":\"SCALAR\"}]}";
  return j;
}

}  // namespace

void write_glb(const DoubleMesh& d, std::ostream& out, const std::string& note) {
  std::string bin;
  bin.reserve(d.points.size() * 12 + d.triangles.size() * 12);
  float lo[3], hi[3];
  for (int c = 0; c < 3; ++c) {
    lo[c] = std::numeric_limits<float>::max();
    hi[c] = std::numeric_limits<float>::lowest();
  }
  for (const auto& p : d.points)
    for (int c = 0; c < 3; ++c) {
      const float f = float(p[c]);
      lo[c] = std::min(lo[c], f);
      hi[c] = std::max(hi[c], f);
      bin.append(reinterpret_cast<const char*>(&f), 4);
    }
  for (const Triangle& t : d.triangles)
    for (int k = 0; k < 3; ++k) append_u32(bin, std::uint32_t(t[k]));
  std::string json = gltf_json(d.points.size(), d.triangles.size() * 3, lo, hi, note);
  json.append((4 - json.size() % 4) % 4, ' ');  // chunks are 4-byte aligned
  bin.append((4 - bin.size() % 4) % 4, '\0');
  std::string glb;
  append_u32(glb, 0x46546C67);  // "glTF"
  append_u32(glb, 2);
  append_u32(glb, std::uint32_t(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
  append_u32(glb, std::uint32_t(json.size()));
  append_u32(glb, 0x4E4F534A);  // "JSON"
  glb += json;
  if (!bin.empty()) {
    append_u32(glb, std::uint32_t(bin.size()));
    append_u32(glb, 0x004E4942);  // "BIN\0"
    glb += bin;
  }
  out.write(glb.data(), std::streamsize(glb.size()));
}

}  // namespace morphex::detail
