// SPDX-License-Identifier: GPL-3.0-or-later
// What mesh files really contain (issue 43, item 1): the OFF family's variants and Geomview's
// habits, gzip-compressed files, and the limits that keep a compressed file from exhausting memory.
#include <gtest/gtest.h>

#include <gmpxx.h>
#include <sys/stat.h>
#include <zlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "morphex/check.h"
#include "morphex/internal/files.h"
#include "morphex/io.h"
#include "morphex/shapes.h"

using namespace morphex;
namespace fs = std::filesystem;

namespace {

class Dir {
 public:
  Dir() : path_(fs::temp_directory_path() / ("morphex-variants-" + std::to_string(::getpid()))) {
    fs::create_directories(path_);
  }
  ~Dir() { fs::remove_all(path_); }
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string path = (path_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

 private:
  fs::path path_;
};

std::string gzipped(const std::string& text) {
  uLongf size = compressBound(uLong(text.size())) + 32;
  std::string out(size, '\0');
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = uInt(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = uInt(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(out.size() - z.avail_out);
  deflateEnd(&z);
  return out;
}

// A unit tetrahedron in an OFF variant: `extra` numbers after each vertex's x y z.
std::string tetrahedron(const std::string& header, const std::string& extra) {
  return header + "\n4 4 6\n0 0 0 " + extra + "\n1 0 0 " + extra + "\n0 1 0 " + extra + "\n0 0 1 " +
         extra + "\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
}

std::string error_of(const std::string& path) {
  try {
    read_mesh(path);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << ": no error";
  return "";
}

}  // namespace

TEST(OffVariants, ColoursNormalsAndTexturesAreRead) {
  Dir dir;
  const std::pair<const char*, const char*> variants[] = {
      {"OFF", ""},          {"COFF", "1 0 0 1"},
      {"NOFF", "0 0 1"},    {"CNOFF", "0 0 1 1 0 0 1"},
      {"STOFF", "0.5 0.5"}, {"STCNOFF", "0 0 0 0 1 0 0 1"}};
  for (const auto& [header, extra] : variants) {
    const Mesh m = read_mesh(dir.write(std::string(header) + ".off", tetrahedron(header, extra)));
    EXPECT_EQ(m.num_triangles(), 4u) << header;
    EXPECT_EQ(signed_volume(m), FT(1) / 6) << header;
  }
}

TEST(OffVariants, GeomviewHabitsAreRead) {
  Dir dir;
  // The header keyword left out (Geomview reads a file that starts with its counts as OFF).
  EXPECT_EQ(read_mesh(dir.write("bare.off", "# no keyword\n" + tetrahedron("", "").substr(1)))
                .num_triangles(),
            4u);
  // Appearance blocks before the header, over several lines, nested braces.
  const std::string appearance = "appearance {\n  +edge\n  material { diffuse 1 0 0 }\n}\n";
  EXPECT_EQ(
      read_mesh(dir.write("look.off", appearance + tetrahedron("COFF", "1 0 0 1"))).num_triangles(),
      4u);
  // Comments and blank lines anywhere.
  EXPECT_EQ(read_mesh(dir.write("comments.off",
                                "\n# a\n\nOFF # header\n\n4 4 0\n0 0 0\n# between\n1 0 0\n\n0 1 0\n"
                                "0 0 1\n3 0 2 1\n3 0 1 3 # face\n3 1 2 3\n\n3 0 3 2\n"))
                .num_triangles(),
            4u);
}

TEST(OffVariants, OtherDimensionsAndKindsAreRefusedByName) {
  Dir dir;
  EXPECT_NE(error_of(dir.write("h.off", "4OFF\n16 24 32\n")).find("4OFF: four-dimensional"),
            std::string::npos);
  EXPECT_NE(error_of(dir.write("n.off", "nOFF\n4\n16 24 32\n")).find("nOFF"), std::string::npos);
  EXPECT_NE(error_of(dir.write("u.off", "appearance { +edge }\nUMESH\n2 2\n"))
                .find("not an OFF file: header is 'UMESH' at line 2"),
            std::string::npos);
  EXPECT_NE(error_of(dir.write("a.off", "appearance { +edge\n")).find("unterminated appearance"),
            std::string::npos);
}

TEST(Gzip, CompressedFilesAreReadAndWritten) {
  Dir dir;
  const std::string text = tetrahedron("OFF", "");
  EXPECT_EQ(signed_volume(read_mesh(dir.write("t.off.gz", gzipped(text)))), FT(1) / 6);
  // Two gzip members one after the other are one file (as gzip itself reads them).
  const std::string half = text.substr(0, text.size() / 2), rest = text.substr(text.size() / 2);
  EXPECT_EQ(read_mesh(dir.write("two.off.gz", gzipped(half) + gzipped(rest))).num_triangles(), 4u);
  // Written compressed: the format inside is the name's before .gz.
  const Mesh cube = make_cube(FT(1) / 3);
  const std::string out = dir.write("cube.stl.gz", "");
  write_mesh(cube, out);
  std::ifstream in(out, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f);
  const MeshReport back = check_mesh(read_mesh(out));
  EXPECT_TRUE(back.valid_solid());
  EXPECT_EQ(back.triangles, 12u);
  // The inflated content's format is told by the name inside.
  EXPECT_EQ(format_from_path("x.PLY.gz"), MeshFormat::Ply);
}

TEST(Gzip, DamagedAndOversizedStreamsAreRefused) {
  Dir dir;
  const std::string packed = gzipped(tetrahedron("OFF", ""));
  EXPECT_NE(error_of(dir.write("cut.off.gz", packed.substr(0, packed.size() / 2)))
                .find("truncated gzip data"),
            std::string::npos);
  std::string corrupt = packed;
  corrupt[12] = char(corrupt[12] ^ 0x55);
  corrupt[13] = char(corrupt[13] ^ 0x55);
  EXPECT_NE(error_of(dir.write("bad.off.gz", corrupt)).find("gzip"), std::string::npos);
  // A bomb: 64 MB of one repeated line in a few hundred kilobytes, under a 1 MB input limit.
  const InputLimits before = input_limits();
  set_input_limits({1 << 20, before.max_faces});
  std::string big = "OFF\n0 0 0\n";
  big.append(64u << 20, '\n');
  const std::string bomb = dir.write("bomb.off.gz", gzipped(big));
  EXPECT_LT(fs::file_size(bomb), 1u << 20);
  EXPECT_NE(error_of(bomb).find("file too large once decompressed"), std::string::npos);
  set_input_limits(before);
}

TEST(ObjVariants, GroupsMaterialsNormalsAndPolygonsAreRead) {
  Dir dir;
  // A unit cube as six quads with every record an exporter adds; one face a pentagon (a point on
  // an edge of the top), negative indices on another.
  const std::string obj =
      "mtllib cube.mtl\no cube\ng box\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\n"
      "v 1 1 1\nv 0 1 1\nv 0.5 1 1\nvt 0 0\nvn 0 0 1\ns off\nusemtl red\n"
      "f 1/1/1 4/1/1 3/1/1 2/1/1\nf 5 6 7 9 8\nf -9 -8 -4 -5\nf 2 3 7 6\nf 3 4 8 9 7\n"
      "f 4 1 5 8\n";
  const Mesh m = read_mesh(dir.write("cube.obj", obj));
  const MeshReport r = check_mesh(m);
  EXPECT_TRUE(r.valid_solid()) << describe_problems(r);
  EXPECT_EQ(r.volume, FT(1));
}

TEST(PlyVariants, ExtraPropertiesAndIndexTypesAreRead) {
  Dir dir;
  const std::string header =
      "ply\nformat ascii 1.0\ncomment colours and normals\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nproperty float nx\nproperty uchar red\n"
      "element face 4\nproperty list uint8 uint16 vertex_index\nproperty uchar flags\n"
      "element material 1\nproperty float shine\nend_header\n";
  const std::string body =
      "0 0 0 1 255\n1 0 0 1 0\n0 1 0 1 0\n0 0 1 1 0\n3 0 2 1 7\n3 0 1 3 7\n"
      "3 1 2 3 7\n3 0 3 2 7\n0.5\n";
  const Mesh m = read_mesh(dir.write("t.ply", header + body));
  EXPECT_EQ(m.num_triangles(), 4u);
  EXPECT_EQ(signed_volume(m), FT(1) / 6);
}

// A device is written in place, never replaced: renaming a temporary over /dev/null (as root)
// turned it into a regular file that later redirections filled (found by this session's
// `--stats /dev/null`).
TEST(AtomicWrite, DevicesAreWrittenInPlace) {
  struct stat before {
  }, after{};
  ASSERT_EQ(stat("/dev/null", &before), 0);
  ASSERT_TRUE(S_ISCHR(before.st_mode));
  write_file_atomically("/dev/null", [](std::ostream& out) { out << "written\n"; });
  ASSERT_EQ(stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode));
  EXPECT_EQ(after.st_ino, before.st_ino);
  std::ifstream in("/dev/null");
  EXPECT_EQ(in.peek(), std::char_traits<char>::eof());  // still the device: reads nothing
}

namespace {

// The exact value a coordinate literal stands for, by other means than the readers': GMP for
// integers and fractions, the C library's strtod for decimals (the nearest double).
FT expected_value(const std::string& literal) {
  const std::string text = literal[0] == '+' ? literal.substr(1) : literal;
  if (text.find_first_of(".eE") == std::string::npos) {
    mpq_class q(text, 10);
    q.canonicalize();
    return FT(Kernel::Exact_kernel::FT(q));
  }
  return FT(std::strtod(text.c_str(), nullptr));
}

}  // namespace

// Plain decimals and short integers are read straight to doubles (the fast path of large files);
// everything else exactly. Every form, alone on a line or beside the others, must give the value
// it stands for in OFF, OBJ and ASCII PLY alike.
TEST(NumberForms, EveryLiteralReadsAsTheValueItStandsFor) {
  const std::vector<std::string> literals = {"0.1",
                                             "+0.5",
                                             "-2.5e-3",
                                             "1E2",
                                             "7",
                                             "+7",
                                             "-0",
                                             "0",
                                             "-0.0",
                                             "123456789012345",
                                             "-123456789012345",
                                             "1234567890123456",
                                             "12345678901234567",
                                             "-98765432109876543210",
                                             "6/16",
                                             "-1/3",
                                             "+2/4",
                                             "1e308",
                                             "4.9e-324",
                                             "2.2250738585072014e-308",
                                             ".5",
                                             "5.",
                                             "1e-5",
                                             "0.30000000000000004",
                                             "9007199254740993",
                                             "9007199254740993.0"};
  std::vector<std::array<std::string, 3>> rows;
  for (std::size_t i = 0; i < literals.size(); ++i)  // each literal in each place
    rows.push_back(
        {literals[i], literals[(i + 7) % literals.size()], literals[(i + 13) % literals.size()]});
  std::string off = "OFF\n" + std::to_string(rows.size() + 3) + " 1 0\n", obj,
              ply = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(rows.size() + 3) +
                    "\nproperty double x\nproperty double y\nproperty double z\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& row : rows) {
    const std::string line = row[0] + "\t" + row[1] + "  " + row[2];
    off += line + " # a comment\n";
    obj += "v " + line + "\n";
    ply += line + "\n";
  }
  // A triangle of three more vertices, so that each file is a mesh.
  const std::string corners = "10 0 0\n0 10 0\n0 0 10\n";
  const std::string face = std::to_string(rows.size()) + " " + std::to_string(rows.size() + 1) +
                           " " + std::to_string(rows.size() + 2);
  off += corners + "3 " + face + "\n";
  for (const char* c : {"v 10 0 0\n", "v 0 10 0\n", "v 0 0 10\n"}) obj += c;
  obj += "f " + std::to_string(rows.size() + 1) + " " + std::to_string(rows.size() + 2) + " " +
         std::to_string(rows.size() + 3) + "\n";
  ply += corners + "3 " + face + "\n";
  const std::pair<MeshFormat, std::string> files[] = {
      {MeshFormat::Off, off}, {MeshFormat::Obj, obj}, {MeshFormat::Ply, ply}};
  for (const auto& [format, content] : files) {
    const Mesh mesh = read_mesh_from_string(content, format, "forms");
    ASSERT_EQ(mesh.num_vertices(), rows.size() + 3);
    for (std::size_t v = 0; v < rows.size(); ++v)
      for (int k = 0; k < 3; ++k) {
        const FT expected = expected_value(rows[v][std::size_t(k)]);
        // PLY stores doubles: a rational literal there is its nearest double.
        const FT want = format == MeshFormat::Ply ? FT(CGAL::to_double(expected)) : expected;
        EXPECT_EQ(mesh.points[v].cartesian(k), want)
            << "literal " << rows[v][std::size_t(k)] << " in format " << int(format);
      }
  }
}
