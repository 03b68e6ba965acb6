// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh files: round trips in every format, polygon triangulation, and one test per kind of bad
// input, each checking that the error names the file, the problem and where.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "morphex/generators.h"
#include "morphex/io.h"

using namespace morphex;
namespace fs = std::filesystem;

namespace {

class TempDir {
 public:
  TempDir()
      : path_(fs::temp_directory_path() /
              ("morphex-io-" + std::to_string(::getpid()) + "-" + std::to_string(counter_++))) {
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::size_t entries() const {
    return std::size_t(std::distance(fs::directory_iterator(path_), fs::directory_iterator()));
  }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The error thrown for `content` read as `file`, or a failure if none is thrown.
std::string error_for(const std::string& file, const std::string& content) {
  TempDir dir;
  const std::string path = dir.file(file);
  write_text(path, content);
  try {
    read_mesh(path);
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file), std::string::npos) << "no file name in: " << message;
    return message;
  }
  ADD_FAILURE() << file << ": no error for bad input";
  return "";
}

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << text

Mesh third_cube() {
  return make_box(Point(0, 0, 0), Point(FT(1) / 3, FT(2) / 7, FT(5) / 11));
}

}  // namespace

TEST(Io, ExactOffRoundTripKeepsRationals) {
  TempDir dir;
  const Mesh m = third_cube();
  write_mesh(m, dir.file("m.off"), {true});
  const Mesh back = read_mesh(dir.file("m.off"));
  ASSERT_EQ(back.points.size(), m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) EXPECT_EQ(back.points[i], m.points[i]);
  EXPECT_EQ(back.triangles, m.triangles);
  EXPECT_EQ(signed_volume(back), FT(10) / 231);
}

TEST(Io, PlainFormatsRoundTripDoublesExactly) {
  TempDir dir;
  const Mesh m = make_icosphere(1, FT(1));  // double coordinates
  for (const char* name : {"m.off", "m.obj", "m.ply"}) {
    write_mesh(m, dir.file(name));
    const Mesh back = read_mesh(dir.file(name));
    ASSERT_EQ(back.points.size(), m.points.size()) << name;
    for (std::size_t i = 0; i < m.points.size(); ++i)
      EXPECT_EQ(back.points[i], m.points[i]) << name;
    EXPECT_EQ(back.triangles, m.triangles) << name;
  }
}

// Every written file says what made it (issue 23): the version and the provenance line, as the
// format's comment, and still reads back as the same mesh.
TEST(Io, WrittenFilesCarryTheirProvenance) {
  TempDir dir;
  const Mesh m = make_icosphere(1, FT(1));
  WriteOptions options;
  options.provenance = "morphex bool union a.off b.off\n-o c.off";  // a newline is flattened
  const std::string line = provenance_line(options.provenance);
  EXPECT_EQ(line, std::string("written by morphex ") + version() +
                      ": morphex bool union a.off b.off -o c.off");
  for (const char* name : {"m.off", "m.obj", "m.ply", "m.stl"}) {
    write_mesh(m, dir.file(name), options);
    std::ifstream in(dir.file(name), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // binary STL keeps the first 80 bytes of it
    const std::string expected = std::string(name) == "m.stl" ? line.substr(0, 80) : line;
    EXPECT_NE(bytes.find(expected), std::string::npos) << name;
    const Mesh back = read_mesh(dir.file(name));
    EXPECT_EQ(back.triangles.size(), m.triangles.size()) << name;
  }
}

TEST(Io, BinaryStlMergesVerticesAndKeepsFloats) {
  TempDir dir;
  const Mesh m = make_cube(FT(1) / 2);  // exactly representable as floats
  write_mesh(m, dir.file("m.stl"));
  const Mesh back = read_mesh(dir.file("m.stl"));
  EXPECT_EQ(back.points.size(), 8u);
  EXPECT_EQ(back.triangles.size(), 12u);
  EXPECT_EQ(signed_volume(back), FT(1));
}

TEST(Io, AsciiStl) {
  const std::string stl =
      "solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 "
      "0\nendloop\nendfacet\n"
      "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 "
      "1\nendloop\nendfacet\n"
      "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 "
      "0\nendloop\nendfacet\n"
      "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 "
      "1\nendloop\nendfacet\nendsolid t\n";
  const Mesh m = read_mesh_from_string(stl, MeshFormat::Stl, "t.stl");
  EXPECT_EQ(m.points.size(), 4u);
  EXPECT_EQ(signed_volume(m), FT(1) / 6);
}

TEST(Io, ObjNegativeIndicesSlashesAndQuads) {
  const std::string obj =
      "# unit cube with quads\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 "
      "1 1\n"
      "vn 0 0 1\nvt 0 0\ng cube\nf 1/1/1 3/1/1 4/1/1 2/1/1\nf 5//1 6//1 8//1 7//1\nf 1 2 6 5\n"
      "f -6 -2 -1 -5\nf 1 5 7 3\nf 2 4 8 6\n";
  const Mesh m = read_mesh_from_string(obj, MeshFormat::Obj, "cube.obj");
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(signed_volume(m), FT(1));
}

TEST(Io, NonConvexPolygonIsEarClipped) {
  // an L-shaped hexagon prism top: the fan from vertex 0 would leave the polygon
  const std::vector<Point> pts = {Point(0, 0, 0), Point(2, 0, 0), Point(2, 1, 0),
                                  Point(1, 1, 0), Point(1, 2, 0), Point(0, 2, 0)};
  std::vector<Triangle> tris;
  triangulate_polygon(pts, {2, 3, 4, 5, 0, 1}, tris);
  ASSERT_EQ(tris.size(), 4u);
  FT area = 0;
  for (const Triangle& t : tris) {
    const auto& a = pts[t[0]];
    const auto& b = pts[t[1]];
    const auto& c = pts[t[2]];
    const FT cross = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    EXPECT_GT(cross, 0);  // every ear keeps the polygon's orientation
    area += cross / 2;
  }
  EXPECT_EQ(area, FT(3));
}

TEST(Io, PlyAsciiAndBinary) {
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float "
      "z\n"
      "property uchar red\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  EXPECT_EQ(signed_volume(read_mesh_from_string(ascii, MeshFormat::Ply, "t.ply")), FT(1) / 6);
  TempDir dir;
  write_mesh(make_tetrahedron(), dir.file("t.ply"));
  EXPECT_EQ(signed_volume(read_mesh(dir.file("t.ply"))), FT(1) / 6);
}

TEST(Io, AtomicWriteReplacesOnlyOnSuccessAndLeavesNoTemporaryFile) {
  TempDir dir;
  const std::string path = dir.file("out.off");
  write_text(path, "old");
  EXPECT_THROW(write_file_atomically(path, [](std::ostream&) { throw std::runtime_error("boom"); }),
               std::runtime_error);
  std::ifstream in(path);
  std::string content((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(content, "old");
  EXPECT_EQ(dir.entries(), 1u);
  write_mesh(make_tetrahedron(), path);
  EXPECT_EQ(read_mesh(path).triangles.size(), 4u);
  EXPECT_EQ(dir.entries(), 1u);
}

TEST(Io, SameFileDetectsAliases) {
  TempDir dir;
  write_text(dir.file("a.off"), "x");
  EXPECT_TRUE(same_file(dir.file("a.off"), dir.file("./a.off")));
  EXPECT_FALSE(same_file(dir.file("a.off"), dir.file("b.off")));
}

TEST(Io, ExactIsRefusedForPlainFormats) {
  TempDir dir;
  EXPECT_THROW(write_mesh(make_tetrahedron(), dir.file("t.stl"), {true}), InputError);
}

// ---- bad input ----

TEST(BadInput, EmptyFile) {
  EXPECT_CONTAINS(error_for("empty.off", ""), "empty file");
}

TEST(BadInput, MissingFile) {
  try {
    read_mesh("/nonexistent/dir/none.off");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_CONTAINS(e.what(), "none.off: cannot open file");
  }
}

TEST(BadInput, UnknownExtension) {
  EXPECT_THROW(read_mesh("mesh.xyz"), InputError);
}

TEST(BadInput, WrongHeader) {
  EXPECT_CONTAINS(error_for("wrong.off", "PLY\n3 1 0\n"), "not an OFF file");
  EXPECT_CONTAINS(error_for("wrong.ply", "OFF\n"), "not a PLY file");
}

TEST(BadInput, TruncatedFile) {
  const std::string msg =
      error_for("trunc.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n");
  EXPECT_CONTAINS(msg, "truncated");
  EXPECT_CONTAINS(
      error_for("trunc.stl", std::string(84 + 30, '\0').replace(80, 4, "\x01\0\0\0", 4)),
      "size mismatch");
  EXPECT_CONTAINS(
      error_for("trunc2.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"),
      "truncated");
}

TEST(BadInput, NanAndInfCoordinates) {
  EXPECT_CONTAINS(error_for("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), "line 4");
  EXPECT_CONTAINS(error_for("inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n"), "non-finite");
}

TEST(BadInput, OutOfRangeAndNegativeIndices) {
  const std::string msg = error_for("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  EXPECT_CONTAINS(msg, "face 0");
  EXPECT_CONTAINS(msg, "'7' out of range");
  EXPECT_CONTAINS(msg, "line 6");
  EXPECT_CONTAINS(error_for("neg.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"),
                  "out of range");
  EXPECT_CONTAINS(error_for("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), "out of range");
  EXPECT_CONTAINS(error_for("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), "out of range");
}

TEST(BadInput, PolygonsThatCannotBeTriangulated) {
  // a bow-tie (self-intersecting quad) and a polygon with all vertices collinear
  EXPECT_CONTAINS(error_for("bowtie.off", "OFF\n4 1 0\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n4 0 1 2 3\n"),
                  "face 0");
  EXPECT_CONTAINS(error_for("line.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n4 0 1 2 3\n"),
                  "degenerate polygon");
  EXPECT_CONTAINS(error_for("two.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n2 0 1\n"), "fewer than 3");
}

TEST(BadInput, HugeCountsFailFastWithoutAllocating) {
  const auto start = std::chrono::steady_clock::now();
  EXPECT_CONTAINS(error_for("huge.off", "OFF\n999999999999 999999999999 0\n0 0 0\n"), "truncated");
  EXPECT_CONTAINS(error_for("huge.ply",
                            "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\n"
                            "property float y\nproperty float z\nend_header\n0 0 0\n"),
                  "truncated");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(BadInput, NonNumericTokens) {
  EXPECT_CONTAINS(error_for("word.off", "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"), "line 4");
  EXPECT_CONTAINS(error_for("count.off", "OFF\nthree 1 0\n"), "vertex count");
}

TEST(BadInput, EndlessDeviceStopsAtTheSizeLimit) {
  // A device has no size to check before reading: the reader must stop at the limit by itself.
  TempDir dir;
  const std::string path = dir.file("zero.off");
  fs::create_symlink("/dev/zero", path);
  const InputLimits saved = input_limits();
  set_input_limits({/*max_file_bytes=*/1 << 20, saved.max_faces});
  try {
    read_mesh(path);
    ADD_FAILURE() << "no error for an endless input";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(e.what(), "zero.off: file too large");
  }
  set_input_limits(saved);
}

TEST(BadInput, PlyCountsThatCannotBeTrusted) {
  // Element counts whose sum wraps around 64 bits must not pass the size check.
  std::string header = "ply\nformat ascii 1.0\n";
  for (int i = 0; i < 20; ++i) header += "element e" + std::to_string(i) + " 999999999999999999\n";
  EXPECT_CONTAINS(error_for("wrap.ply", header + "end_header\n0\n"), "truncated");
  // A list count is an integer; as a float it could be NaN or 2.5.
  EXPECT_CONTAINS(error_for("float-count.ply",
                            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                            "property float y\nproperty float z\nelement face 1\n"
                            "property list float int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                  "list count must be an integer type");
}
