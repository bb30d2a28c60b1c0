#include "discretize/gmsh_library.hpp"

#include <dlfcn.h>
#include <gmshc.h>

#include <cstdlib>
#include <mutex>
#include <stdexcept>

namespace periadapt {

namespace {

// The entry points this reader uses; decltype of the declarations only, so nothing here links
// against libgmsh.
struct GmshApi {
  decltype(&gmshInitialize) initialize = nullptr;
  decltype(&gmshFinalize) finalize = nullptr;
  decltype(&gmshOptionSetNumber) set_number = nullptr;
  decltype(&gmshOpen) open = nullptr;
  decltype(&gmshModelMeshGenerate) generate = nullptr;
  decltype(&gmshModelMeshGetElementsByType) elements_by_type = nullptr;
  decltype(&gmshModelMeshGetNodes) nodes = nullptr;
  decltype(&gmshLoggerGetLastError) last_error = nullptr;
  decltype(&gmshFree) free = nullptr;
};

template <class F>
void bind(void* lib, const char* name, F& f) {
  f = reinterpret_cast<F>(dlsym(lib, name));
  if (!f) throw std::runtime_error(std::string("the Gmsh library has no ") + name);
}

// Loaded once per process and kept: unloading a C++ library with static state is not safe.
const GmshApi& api() {
  static GmshApi a;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    void* lib = dlopen(PERIADAPT_GMSH_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
      const char* e = dlerror();
      failure = std::string("cannot load the Gmsh library ") + PERIADAPT_GMSH_LIBRARY + ": " +
                (e ? e : "unknown error");
      return;
    }
    try {
      bind(lib, "gmshInitialize", a.initialize);
      bind(lib, "gmshFinalize", a.finalize);
      bind(lib, "gmshOptionSetNumber", a.set_number);
      bind(lib, "gmshOpen", a.open);
      bind(lib, "gmshModelMeshGenerate", a.generate);
      bind(lib, "gmshModelMeshGetElementsByType", a.elements_by_type);
      bind(lib, "gmshModelMeshGetNodes", a.nodes);
      bind(lib, "gmshLoggerGetLastError", a.last_error);
      bind(lib, "gmshFree", a.free);
    } catch (const std::exception& e) {
      failure = e.what();
    }
  });
  if (!failure.empty()) throw std::runtime_error(failure);
  return a;
}

void check(int ierr) {
  if (ierr == 0) return;
  const GmshApi& a = api();
  char* text = nullptr;
  int e2 = 0;
  a.last_error(&text, &e2);
  std::string message = (e2 == 0 && text && *text) ? text : "Gmsh reported an error";
  if (text) a.free(text);
  throw std::runtime_error(message);
}

// Copies a Gmsh-allocated array into `out` and frees it.
template <class T>
void take(T* data, std::size_t n, std::vector<T>& out) {
  out.assign(data, data + n);
  if (data) api().free(data);
}

}  // namespace

GmshSession::GmshSession() {
  const GmshApi& a = api();
  int ierr = 0;
  a.initialize(0, nullptr, 0, &ierr);
  check(ierr);
  a.set_number("General.Terminal", 0, &ierr);
  if (ierr != 0) {
    int ignored = 0;
    a.finalize(&ignored);
    check(ierr);
  }
}

GmshSession::~GmshSession() {
  int ierr = 0;
  api().finalize(&ierr);
}

void GmshSession::open(const std::string& path) {
  int ierr = 0;
  api().open(path.c_str(), &ierr);
  check(ierr);
}

void GmshSession::generate(int dim) {
  int ierr = 0;
  api().generate(dim, &ierr);
  check(ierr);
}

void GmshSession::elements_by_type(int type, std::vector<std::size_t>& tags,
                                   std::vector<std::size_t>& nodes) {
  std::size_t *t = nullptr, *n = nullptr, nt = 0, nn = 0;
  int ierr = 0;
  api().elements_by_type(type, &t, &nt, &n, &nn, -1, 0, 1, &ierr);
  take(t, nt, tags);
  take(n, nn, nodes);
  check(ierr);
}

void GmshSession::nodes(std::vector<std::size_t>& tags, std::vector<double>& coords) {
  std::size_t* t = nullptr;
  double *c = nullptr, *p = nullptr;
  std::size_t nt = 0, nc = 0, np = 0;
  int ierr = 0;
  // Every entity (dim, tag = -1), boundary nodes included, no parametric coordinates.
  api().nodes(&t, &nt, &c, &nc, &p, &np, -1, -1, 1, 0, &ierr);
  take(t, nt, tags);
  take(c, nc, coords);
  if (p) api().free(p);
  check(ierr);
}

}  // namespace periadapt
