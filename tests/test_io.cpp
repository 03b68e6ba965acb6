// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh files: round trips in every format, polygon triangulation, and one test per kind of bad
// input, each checking that the error names the file, the problem and where.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "boolean/step1_triangulate.h"
#include "mesh/io_text.h"
#include "morphex/check.h"
#include "morphex/internal/files.h"
#include "morphex/io.h"
#include "morphex/shapes.h"

#ifdef MORPHEX_HAVE_3MF
#include <Model/COM/NMR_DLLInterfaces.h>
#endif

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

// -0 and 0 are one coordinate: the tetrahedron's corner written as "-0 0 -0" in one facet and
// "0 0 0" in the others is one vertex, and the mesh is closed.
TEST(Io, AsciiStlMergesNegativeZero) {
  const std::string stl =
      "solid t\nfacet normal 0 0 -1\nouter loop\nvertex -0 0 -0\nvertex 0 1 0\nvertex 1 0 "
      "0\nendloop\nendfacet\n"
      "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 "
      "1\nendloop\nendfacet\n"
      "facet normal -1 0 0\nouter loop\nvertex 0 -0 0\nvertex 0 0 1\nvertex 0 1 "
      "0\nendloop\nendfacet\n"
      "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 "
      "1\nendloop\nendfacet\nendsolid t\n";
  const Mesh m = read_mesh_from_string(stl, MeshFormat::Stl, "t.stl");
  EXPECT_EQ(m.points.size(), 4u);
  EXPECT_TRUE(check_mesh(m).valid_solid());
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

// Standard input has no extension: its format comes from its first bytes (issue 23).
TEST(Streams, FormatIsDetectedFromTheContent) {
  std::ostringstream stl;
  write_mesh(make_cube(FT(1) / 2), stl, MeshFormat::Stl);
  EXPECT_EQ(detect_format(stl.str(), "<stdin>"), MeshFormat::Stl);
  EXPECT_EQ(detect_format("solid x\nendsolid x\n", "<stdin>"), MeshFormat::Stl);
  EXPECT_EQ(detect_format("# made by hand\n\n  OFF\n4 4 0\n", "<stdin>"), MeshFormat::Off);
  EXPECT_EQ(detect_format("COFF 4 4 0\n", "<stdin>"), MeshFormat::Off);
  EXPECT_EQ(detect_format("ply\nformat ascii 1.0\n", "<stdin>"), MeshFormat::Ply);
  EXPECT_EQ(detect_format(std::string("PK\x03\x04", 4) + "rest", "<stdin>"), MeshFormat::ThreeMf);
  try {
    detect_format("v 0 0 0\nf 1 2 3\n", "<stdin>");
    ADD_FAILURE() << "OBJ on standard input was not refused";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(e.what(), "<stdin>: cannot tell the mesh format from the first bytes 'v 0 0");
  }
}

TEST(Streams, WritingToAStreamGivesTheSameBytesAsAFile) {
  TempDir dir;
  const Mesh m = third_cube();
  WriteOptions options;
  options.exact = true;
  std::ostringstream out;
  write_mesh(m, out, MeshFormat::Off, options);
  write_mesh(m, dir.file("m.off"), options);
  std::ifstream in(dir.file("m.off"), std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(out.str(), file);
  EXPECT_EQ(signed_volume(read_mesh_from_string(out.str(), MeshFormat::Off, "<stdin>")),
            FT(10) / 231);
}

// Exact OFF writes points of doubles from their doubles and the others from their exact points:
// each coordinate must be the text GMP gives its exact value, and read back as that value.
TEST(Streams, ExactOffWritesEveryPointAsItsExactValue) {
  Mesh m;
  m.points = {Point(0.1, -2.5, 1e-300), Point(FT(1) / 3, FT(2) / 7 + FT(0.1), FT(-5)),
              CGAL::midpoint(Point(0.1, 0.2, 0.3), Point(FT(1) / 3, FT(1) / 5, FT(7))),
              Point(1e300, -0x1p-70, 12345678.0)};
  m.triangles = {{0, 1, 2}, {1, 2, 3}};
  WriteOptions options;
  options.exact = true;
  std::ostringstream out;
  write_mesh(m, out, MeshFormat::Off, options);
  std::istringstream lines(out.str());
  std::string line;
  std::getline(lines, line);  // OFF
  std::getline(lines, line);  // the provenance comment
  std::getline(lines, line);  // counts
  for (const Point& p : m.points) {
    std::getline(lines, line);
    std::istringstream tokens(line);
    for (int k = 0; k < 3; ++k) {
      std::string token;
      tokens >> token;
      mpq_class expected = CGAL::exact(p.cartesian(k));
      expected.canonicalize();
      EXPECT_EQ(token, expected.get_str());
    }
  }
  const Mesh back = read_mesh_from_string(out.str(), MeshFormat::Off, "<stdin>");
  ASSERT_EQ(back.points.size(), m.points.size());
  for (std::size_t v = 0; v < m.points.size(); ++v) EXPECT_EQ(back.points[v], m.points[v]);
}

// A result whose features are thinner than the format's spacing collapses when written: a unit
// box at 1e300 is a point in doubles (written as the empty solid, and said so), and floats cannot
// hold 1e300 at all: refused before any file exists (issue 42; issue 23 refused both).
TEST(LossyOutput, ThinnerThanTheFormatCollapsesOutOfRangeIsRefused) {
  TempDir dir;
  const FT big(1e300);
  const Mesh m = make_box(Point(big, big, big), Point(big + 1, big + 1, big + 1));
  for (const char* name : {"m.off", "m.obj", "m.ply"}) {
    const RoundingReport r = write_mesh(m, dir.file(name));
    EXPECT_TRUE(r.collapsed) << name;
  }
  for (const char* name : {"m.stl", "m.glb"}) {
    try {
      write_mesh(m, dir.file(name));
      ADD_FAILURE() << name << ": no error";
    } catch (const LossyOutputError& e) {
      EXPECT_CONTAINS(e.what(), dir.file(name) + ": the result cannot be written as 32-bit floats");
      EXPECT_CONTAINS(e.what(), "outside the format's range");
    }
  }
  EXPECT_EQ(dir.entries(), 3u);
  write_mesh(m, dir.file("exact.off"), {true});  // the exact format holds it
  EXPECT_EQ(signed_volume(read_mesh(dir.file("exact.off"))), FT(1));
}

// A mesh that is not a solid is written as it is, vertex by vertex, and the report says that
// rounding changed it (here a face flattened in floats).
TEST(LossyOutput, NonSolidsAreRoundedAsTheyAre) {
  // 1 + 2^-30 is a double but not a float: in floats the added vertex is (1,0,0) again.
  Mesh m = make_tetrahedron();
  m.points.push_back(Point(1 + std::ldexp(1.0, -30), 0, 0));
  m.triangles.push_back({1, 4, 2});
  std::ostringstream doubles, floats;
  EXPECT_FALSE(write_mesh(m, doubles, MeshFormat::Off).not_a_solid);  // nothing moved
  const RoundingReport r = write_mesh(m, floats, MeshFormat::Stl);
  EXPECT_TRUE(r.not_a_solid);
  EXPECT_EQ(r.rounds, 0u);
  EXPECT_EQ(read_mesh_from_string(floats.str(), MeshFormat::Stl, "m.stl").num_triangles(), 5u);
}

// glTF binary for viewers: the header, the JSON chunk and the BIN chunk agree (issue 23, item 8).
TEST(Glb, HeaderJsonAndBinaryChunksAgree) {
  TempDir dir;
  const Mesh m = make_cube(FT(1) / 2);
  write_mesh(m, dir.file("m.glb"));
  std::ifstream in(dir.file("m.glb"), std::ios::binary);
  const std::string b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    std::memcpy(&v, b.data() + at, 4);
    return v;
  };
  ASSERT_GE(b.size(), 28u);
  EXPECT_EQ(b.substr(0, 4), "glTF");
  EXPECT_EQ(u32(4), 2u);
  EXPECT_EQ(u32(8), b.size());
  const std::uint32_t json_length = u32(12);
  EXPECT_EQ(u32(16), 0x4E4F534Au);  // JSON
  EXPECT_EQ(json_length % 4, 0u);
  const std::string json = b.substr(20, json_length);
  EXPECT_CONTAINS(json, "\"version\":\"2.0\"");
  EXPECT_CONTAINS(json,
                  "\"count\":8,\"type\":\"VEC3\",\"min\":[-0.5,-0.5,-0.5],\"max\":[0.5,0.5,0.5]");
  EXPECT_CONTAINS(json, "\"componentType\":5125,\"count\":36,\"type\":\"SCALAR\"");
  const std::size_t bin = 20 + json_length;
  EXPECT_EQ(u32(bin), 8u * 12 + 36 * 4);
  EXPECT_EQ(u32(bin + 4), 0x004E4942u);  // BIN
  float first[3];
  std::memcpy(first, b.data() + bin + 8, 12);
  const DoubleMesh d = to_double(m);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(first[c], float(d.points[0][c]));
  EXPECT_EQ(u32(bin + 8 + 96 + 4 * 35), m.triangles.back()[2]);
}

TEST(ThreeMf, WithoutLib3mfItIsRefusedClearly) {
  if (format_available(MeshFormat::ThreeMf)) GTEST_SKIP() << "built with lib3mf";
  try {
    format_from_path("x.3mf");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(e.what(), "x.3mf: 3MF is not available: this morphex was built without lib3mf");
  }
}

#ifdef MORPHEX_HAVE_3MF
// lib3mf is loaded when a 3MF file is first met: a machine without it must be told which library
// is missing and which package brings it, and a library that is not lib3mf 1.8 must be named.
TEST(ThreeMf, ALibraryThatCannotBeLoadedIsNamed) {
  const std::string missing = detail::load_3mf_library("libmorphex-no-such-lib3mf.so.1");
  EXPECT_CONTAINS(missing, "cannot load libmorphex-no-such-lib3mf.so.1");
  EXPECT_CONTAINS(missing, "install Debian's lib3mf1");
  const std::string other = detail::load_3mf_library("libz.so.1");
  EXPECT_CONTAINS(other, "libz.so.1 has no function lib3mf_");
  EXPECT_EQ(detail::load_3mf_library(MORPHEX_LIB3MF_SONAME), "");
  EXPECT_TRUE(detail::have_3mf());
  EXPECT_EQ(detail::why_no_3mf(), "");
}

namespace {

// A 3MF file made with lib3mf itself: one mesh object placed twice by build items with different
// transforms, in `unit` (lib3mf's MODELUNIT_*).
void write_3mf_with_transforms(const std::string& path, const Mesh& mesh, DWORD unit) {
  using namespace NMR;
  PLib3MFModel* model = nullptr;
  ASSERT_EQ(lib3mf_createmodel(&model), LIB3MF_OK);
  ASSERT_EQ(lib3mf_model_setunit(model, unit), LIB3MF_OK);
  PLib3MFModelMeshObject* object = nullptr;
  ASSERT_EQ(lib3mf_model_addmeshobject(model, &object), LIB3MF_OK);
  const DoubleMesh d = to_double(mesh);
  std::vector<MODELMESHVERTEX> v(d.points.size());
  std::vector<MODELMESHTRIANGLE> t(d.triangles.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int c = 0; c < 3; ++c) v[i].m_fPosition[c] = float(d.points[i][c]);
  for (std::size_t i = 0; i < t.size(); ++i)
    for (int k = 0; k < 3; ++k) t[i].m_nIndices[k] = DWORD(d.triangles[i][k]);
  ASSERT_EQ(
      lib3mf_meshobject_setgeometry(object, v.data(), DWORD(v.size()), t.data(), DWORD(t.size())),
      LIB3MF_OK);
  // Item 1: identity. Item 2: x' = 2x + 10, y' = y + 2z (a shear), z' = z.
  MODELTRANSFORM shift{};
  for (int i = 0; i < 3; ++i) shift.m_fFields[i][i] = 1;
  shift.m_fFields[0][0] = 2;
  shift.m_fFields[0][3] = 10;
  shift.m_fFields[1][2] = 2;
  PLib3MFModelBuildItem *first = nullptr, *second = nullptr;
  ASSERT_EQ(lib3mf_model_addbuilditem(model, object, nullptr, &first), LIB3MF_OK);
  ASSERT_EQ(lib3mf_model_addbuilditem(model, object, &shift, &second), LIB3MF_OK);
  PLib3MFModelWriter* writer = nullptr;
  ASSERT_EQ(lib3mf_model_querywriter(model, "3mf", &writer), LIB3MF_OK);
  ASSERT_EQ(lib3mf_writer_writetofileutf8(writer, path.c_str()), LIB3MF_OK);
  for (PLib3MFBase* p : {writer, second, first, object, model}) lib3mf_release(p);
}

}  // namespace

TEST(ThreeMf, RoundTripKeepsSizesAndVolume) {
  TempDir dir;
  // A cube (exact in six decimals) and an icosphere (rounded: volume within float tolerance).
  const Mesh cube = make_cube(FT(1) / 2), sphere = make_icosphere(2, FT(10));
  write_mesh(cube, dir.file("cube.3mf"));
  const Mesh cube_back = read_mesh(dir.file("cube.3mf"));
  EXPECT_EQ(cube_back.points.size(), 8u);
  EXPECT_EQ(cube_back.triangles, cube.triangles);
  EXPECT_EQ(signed_volume(cube_back), FT(1));
  WriteOptions options;
  options.provenance = "test round trip";
  write_mesh(sphere, dir.file("sphere.3mf"), options);
  const Mesh back = read_mesh(dir.file("sphere.3mf"));
  EXPECT_EQ(back.points.size(), sphere.points.size());
  EXPECT_EQ(back.triangles, sphere.triangles);
  const double v = CGAL::to_double(signed_volume(sphere));
  EXPECT_NEAR(CGAL::to_double(signed_volume(back)), v, 1e-5 * v);
  EXPECT_GT(v, 4000);  // sanity: about 4/3 pi 10^3
}

TEST(ThreeMf, BuildTransformsAndUnitsAreApplied) {
  TempDir dir;
  const Mesh cube = make_box(Point(0, 0, 0), Point(1, 1, 1));
  write_3mf_with_transforms(dir.file("two.3mf"), cube, NMR::MODELUNIT_MILLIMETER);
  const Mesh two = read_mesh(dir.file("two.3mf"));
  ASSERT_EQ(two.points.size(), 16u);
  EXPECT_EQ(two.triangles.size(), 24u);
  // the second copy: (1,1,1) -> (2*1+10, 1+2*1, 1)
  EXPECT_EQ(two.points[8 + 7], Point(12, 3, 1)) << "vertex 7 of make_box is its max corner";
  EXPECT_EQ(signed_volume(two), FT(1) + FT(2));  // the shear keeps volume, x doubles it
  // In inches, every coordinate is converted to millimetres exactly (25.4 = 127/5).
  write_3mf_with_transforms(dir.file("inch.3mf"), cube, NMR::MODELUNIT_INCH);
  const Mesh inch = read_mesh(dir.file("inch.3mf"));
  EXPECT_EQ(inch.points[7], Point(FT(127) / 5, FT(127) / 5, FT(127) / 5));
  EXPECT_EQ(signed_volume(inch), FT(3) * (FT(127) / 5) * (FT(127) / 5) * (FT(127) / 5));
}

TEST(ThreeMf, GarbageIsAnInputErrorNamingTheFile) {
  const std::string message = error_for("bad.3mf", "PK\x03\x04 not really a zip archive");
  EXPECT_CONTAINS(message, "not a readable 3MF file");
}
#endif
