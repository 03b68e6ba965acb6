// SPDX-License-Identifier: GPL-3.0-or-later
// 3MF through Debian's lib3mf 1.8 (its plain C interface, NMR_DLLInterfaces.h, loaded with dlopen
// when first needed). Reading takes the mesh objects of every build item, through components, with
// each transform and the file's unit applied exactly, in millimetres (3MF's default unit). Written
// in micrometres (a mesh's unit is the millimetre): lib3mf stores coordinates as floats and writes
// them with six decimals, which in micrometres is nearly as fine as the float itself
// (RoundingGrid::ThreeMf, morphex/rounding.h, rounds to exactly what it writes; write_3mf checks
// that it did).
#include "mesh/io_text.h"

#ifdef MORPHEX_HAVE_3MF
#include <dlfcn.h>

#include <Model/COM/NMR_DLLInterfaces.h>
#endif

#include <memory>
#include <ostream>

namespace morphex::detail {

#ifndef MORPHEX_HAVE_3MF

bool have_3mf() {
  return false;
}
std::string why_no_3mf() {
  return "this morphex was built without lib3mf (install lib3mf-dev and reconfigure)";
}
std::string load_3mf_library(const char*) {
  return why_no_3mf();
}
Mesh read_3mf(const std::string&, const std::string& name) {
  throw InputError(name, "3MF is not available: this morphex was built without lib3mf");
}
void write_3mf(const DoubleMesh&, std::ostream&, const std::string&, const std::string& name) {
  throw InputError(name, "3MF is not available: this morphex was built without lib3mf");
}

#else

namespace {

using namespace NMR;

// The functions of lib3mf's C interface used here, looked up once when 3MF is first needed.
// clang-format off
#define MORPHEX_LIB3MF_FUNCTIONS(X) \
  X(builditem_getobjectresource) X(builditem_getobjecttransform) \
  X(builditemiterator_getcurrent) X(builditemiterator_movenext) \
  X(component_getobjectresource) X(component_gettransform) \
  X(componentsobject_getcomponent) X(componentsobject_getcomponentcount) X(createmodel) \
  X(getlasterror) X(meshobject_gettrianglecount) X(meshobject_gettriangleindices) \
  X(meshobject_getvertexcount) X(meshobject_getvertices) X(meshobject_setgeometry) \
  X(model_addbuilditem) X(model_addmeshobject) X(model_addmetadatautf8) \
  X(model_getbuilditems) X(model_getunit) X(model_queryreader) X(model_querywriter) \
  X(model_setunit) X(object_gettype) X(object_ismeshobject) X(reader_readfrombuffer) \
  X(release) X(writer_getstreamsize) X(writer_writetobuffer)
// clang-format on

// lib3mf is loaded with dlopen when a 3MF file is first read or written, not linked: loading it
// (with the libzip it brings) took about 7 ms of every command's start, 3MF or not.
struct Lib3mf {
#define MORPHEX_LIB3MF_POINTER(f) decltype(&lib3mf_##f) f = nullptr;
  MORPHEX_LIB3MF_FUNCTIONS(MORPHEX_LIB3MF_POINTER)
#undef MORPHEX_LIB3MF_POINTER
  std::string error;  // why it could not be loaded; empty once loaded
};

// Fills `api` from the library `soname`, or says why it cannot.
std::string load(Lib3mf& api, const char* soname) {
  void* library = dlopen(soname, RTLD_NOW | RTLD_LOCAL);  // never closed: used until exit
  if (!library) {
    const char* why = dlerror();
    return std::string("cannot load ") + soname + (why ? std::string(" (") + why + ")" : "") +
           ": install Debian's lib3mf1 (scripts/setup does)";
  }
#define MORPHEX_LIB3MF_LOOKUP(f)                                           \
  api.f = reinterpret_cast<decltype(api.f)>(dlsym(library, "lib3mf_" #f)); \
  if (!api.f) return std::string(soname) + " has no function lib3mf_" #f ": not lib3mf 1.8";
  MORPHEX_LIB3MF_FUNCTIONS(MORPHEX_LIB3MF_LOOKUP)
#undef MORPHEX_LIB3MF_LOOKUP
  return {};
}

// The process's lib3mf, loaded on first use (MORPHEX_LIB3MF_SONAME: the name configure found).
const Lib3mf& loaded() {
  static const Lib3mf api = [] {
    Lib3mf a;
    a.error = load(a, MORPHEX_LIB3MF_SONAME);
    return a;
  }();
  return api;
}

// The loaded library: only called after require() (or on a handle it gave).
const Lib3mf& lib() {
  return loaded();
}

void require(const std::string& name) {
  if (!loaded().error.empty()) throw InputError(name, "3MF is not available: " + why_no_3mf());
}

// Releases a lib3mf instance at the end of its scope.
struct Handle {
  PLib3MFBase* p = nullptr;
  Handle() = default;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (p) lib().release(p);
  }
};

// lib3mf's last error on `instance`, as text.
std::string last_error(PLib3MFBase* instance) {
  DWORD code = 0;
  LPCSTR message = nullptr;
  if (instance && lib().getlasterror(instance, &code, &message) == 0 && message && *message)
    return std::string(message) + " (lib3mf error " + std::to_string(code) + ")";
  return "lib3mf error";
}

void call(HRESULT result, PLib3MFBase* instance, const std::string& name, const char* what) {
  if (result != LIB3MF_OK) throw InputError(name, std::string(what) + ": " + last_error(instance));
}

// An affine map x'_i = sum_j m[i][j] x_j + m[i][3], exact.
using Affine = std::array<std::array<FT, 4>, 3>;

Affine identity(const FT& scale) {
  Affine a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) a[i][j] = i == j ? scale : FT(0);
  return a;
}

// lib3mf's MODELTRANSFORM: m_fFields[i][j] is the 3MF attribute's m_ji (row vectors, p' = p M):
// row i gives output coordinate i, column 3 the translation.
Affine from_3mf(const MODELTRANSFORM& t) {
  Affine a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) a[i][j] = FT(double(t.m_fFields[i][j]));
  return a;
}

// outer ∘ inner.
Affine compose(const Affine& outer, const Affine& inner) {
  Affine r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) {
      FT v = j == 3 ? outer[i][3] : FT(0);
      for (int k = 0; k < 3; ++k) v += outer[i][k] * inner[k][j];
      r[i][j] = v;
    }
  return r;
}

// Millimetres per unit, exactly (an inch is 25.4 mm by definition).
FT millimetres_per(DWORD unit) {
  switch (unit) {
    case MODELUNIT_MICROMETER:
      return FT(1) / 1000;
    case MODELUNIT_CENTIMETER:
      return FT(10);
    case MODELUNIT_INCH:
      return FT(127) / 5;
    case MODELUNIT_FOOT:
      return FT(1524) / 5;
    case MODELUNIT_METER:
      return FT(1000);
    default:
      return FT(1);
  }
}

struct Reader {
  const std::string& name;
  Mesh mesh;

  void add_mesh_object(PLib3MFModelMeshObject* object, const Affine& a) {
    DWORD nv = 0, nt = 0;
    call(lib().meshobject_getvertexcount(object, &nv), object, name, "vertex count");
    call(lib().meshobject_gettrianglecount(object, &nt), object, name, "triangle count");
    std::vector<MODELMESHVERTEX> vertices(nv);
    std::vector<MODELMESHTRIANGLE> triangles(nt);
    if (nv)
      call(lib().meshobject_getvertices(object, vertices.data(), nv, nullptr), object, name,
           "vertices");
    if (nt)
      call(lib().meshobject_gettriangleindices(object, triangles.data(), nt, nullptr), object, name,
           "triangles");
    const VertexIndex base = VertexIndex(mesh.points.size());
    for (const MODELMESHVERTEX& v : vertices) {
      FT c[3];
      for (int i = 0; i < 3; ++i) {
        c[i] = a[i][3];
        for (int j = 0; j < 3; ++j)
          if (a[i][j] != 0) c[i] += a[i][j] * FT(double(v.m_fPosition[j]));
        c[i] = FT(CGAL::exact(c[i]));  // flatten: the arithmetic DAG is not kept per vertex
      }
      mesh.points.emplace_back(c[0], c[1], c[2]);
    }
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      Triangle tri;
      for (int k = 0; k < 3; ++k) {
        const DWORD i = triangles[t].m_nIndices[k];
        if (i >= nv)
          throw InputError(name, "triangle " + std::to_string(t) + " has vertex index " +
                                     std::to_string(i) + " out of range [0, " + std::to_string(nv) +
                                     ")");
        tri[k] = base + VertexIndex(i);
      }
      mesh.triangles.push_back(tri);
    }
  }

  // A mesh object, or a components object whose parts are added with their transforms.
  void add_object(PLib3MFModelObjectResource* object, const Affine& a, int depth) {
    if (depth > 32) throw InputError(name, "components nested deeper than 32 levels");
    DWORD type = 0;
    call(lib().object_gettype(object, &type), object, name, "object type");
    // Supports and "other" objects are not part of the solid a printer builds.
    if (type == MODELOBJECTTYPE_SUPPORT || type == MODELOBJECTTYPE_OTHER) return;
    BOOL is_mesh = false;
    call(lib().object_ismeshobject(object, &is_mesh), object, name, "object kind");
    if (is_mesh) return add_mesh_object(object, a);
    DWORD count = 0;
    call(lib().componentsobject_getcomponentcount(object, &count), object, name, "components");
    for (DWORD c = 0; c < count; ++c) {
      Handle component, part;
      call(lib().componentsobject_getcomponent(object, c, &component.p), object, name, "component");
      call(lib().component_getobjectresource(component.p, &part.p), component.p, name,
           "component object");
      MODELTRANSFORM t;
      call(lib().component_gettransform(component.p, &t), component.p, name, "component transform");
      add_object(part.p, compose(a, from_3mf(t)), depth + 1);
    }
  }
};

}  // namespace

bool have_3mf() {
  return loaded().error.empty();
}

std::string why_no_3mf() {
  return loaded().error;
}

std::string load_3mf_library(const char* soname) {
  Lib3mf api;
  return load(api, soname);
}

Mesh read_3mf(const std::string& content, const std::string& name) {
  require(name);
  Handle model, reader, items;
  call(lib().createmodel(&model.p), nullptr, name, "cannot create a 3MF model");
  call(lib().model_queryreader(model.p, "3mf", &reader.p), model.p, name, "no 3MF reader");
  std::vector<BYTE> bytes(content.begin(), content.end());
  call(lib().reader_readfrombuffer(reader.p, bytes.data(), bytes.size()), reader.p, name,
       "not a readable 3MF file");
  DWORD unit = MODELUNIT_MILLIMETER;
  call(lib().model_getunit(model.p, &unit), model.p, name, "unit");
  const Affine to_mm = identity(millimetres_per(unit));
  Reader out{name, {}};
  call(lib().model_getbuilditems(model.p, &items.p), model.p, name, "build items");
  BOOL more = false;
  std::size_t count = 0;
  while (lib().builditemiterator_movenext(items.p, &more) == LIB3MF_OK && more) {
    Handle item, object;
    call(lib().builditemiterator_getcurrent(items.p, &item.p), items.p, name, "build item");
    call(lib().builditem_getobjectresource(item.p, &object.p), item.p, name, "build object");
    MODELTRANSFORM t;
    call(lib().builditem_getobjecttransform(item.p, &t), item.p, name, "build transform");
    out.add_object(object.p, compose(to_mm, from_3mf(t)), 0);
    ++count;
  }
  if (count == 0) throw InputError(name, "3MF file without build items: nothing to read");
  return std::move(out.mesh);
}

void write_3mf(const DoubleMesh& d, std::ostream& out, const std::string& note,
               const std::string& name) {
  require(name);
  std::vector<MODELMESHVERTEX> vertices(d.points.size());
  for (std::size_t v = 0; v < d.points.size(); ++v)
    for (int c = 0; c < 3; ++c) vertices[v].m_fPosition[c] = float(d.points[v][c]);
  std::vector<MODELMESHTRIANGLE> triangles(d.triangles.size());
  for (std::size_t t = 0; t < d.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) triangles[t].m_nIndices[k] = DWORD(d.triangles[t][k]);
  Handle model, object, item, writer;
  call(lib().createmodel(&model.p), nullptr, name, "cannot create a 3MF model");
  // Micrometres: see emit (io.cpp); the mesh's unit is the millimetre, scaled by 1000 there.
  call(lib().model_setunit(model.p, MODELUNIT_MICROMETER), model.p, name, "unit");
  call(lib().model_addmeshobject(model.p, &object.p), model.p, name, "mesh object");
  call(lib().meshobject_setgeometry(object.p, vertices.data(), DWORD(vertices.size()),
                                    triangles.data(), DWORD(triangles.size())),
       object.p, name, "cannot store the mesh");
  call(lib().model_addbuilditem(model.p, object.p, nullptr, &item.p), model.p, name, "build item");
  // 3MF's well-known metadata names; a name of our own would need a declared namespace.
  call(lib().model_addmetadatautf8(model.p, "Application",
                                   (std::string("morphex ") + version()).c_str()),
       model.p, name, "metadata");
  call(lib().model_addmetadatautf8(model.p, "Description", note.c_str()), model.p, name,
       "metadata");
  call(lib().model_querywriter(model.p, "3mf", &writer.p), model.p, name, "no 3MF writer");
  ULONG64 size = 0;
  call(lib().writer_getstreamsize(writer.p, &size), writer.p, name, "cannot write 3MF");
  std::string bytes(size, '\0');
  call(lib().writer_writetobuffer(writer.p, reinterpret_cast<BYTE*>(bytes.data()), size), writer.p,
       name, "cannot write 3MF");
  // The mesh was rounded to what lib3mf prints (RoundingGrid::ThreeMf): read back, it must be
  // the same mesh, or the grid's model of lib3mf's printing is wrong for this build of it.
  const Mesh reread = read_3mf(bytes, name);  // in millimetres: back to micrometres, exactly
  bool same = reread.points.size() == d.points.size() && reread.triangles == d.triangles;
  for (std::size_t v = 0; same && v < d.points.size(); ++v)
    for (int c = 0; same && c < 3; ++c)
      same = CGAL::exact(reread.points[v]).cartesian(c) * 1000 == d.points[v][c];
  if (!same)
    throw LossyOutputError(name,
                           "lib3mf did not write the rounded mesh as it was given; "
                           "write another format");
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

#endif

}  // namespace morphex::detail
