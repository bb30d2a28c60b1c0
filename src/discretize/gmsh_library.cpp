#include "discretize/gmsh_library.hpp"

#include <dlfcn.h>
#include <gmshc.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
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

namespace {

bool write_all(int fd, const void* data, std::size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

template <class T>
bool write_vector(int fd, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  return write_all(fd, &n, sizeof n) && write_all(fd, v.data(), n * sizeof(T));
}

template <class T>
bool read_vector(const std::string& buf, std::size_t& at, std::vector<T>& v) {
  std::uint64_t n = 0;
  if (buf.size() - at < sizeof n) return false;
  std::memcpy(&n, buf.data() + at, sizeof n);
  at += sizeof n;
  if (n > (buf.size() - at) / sizeof(T)) return false;
  v.resize(n);
  if (n > 0) std::memcpy(v.data(), buf.data() + at, n * sizeof(T));
  at += n * sizeof(T);
  return true;
}

// The child's work: its answer is a status byte, then the mesh or Gmsh's message.
[[noreturn]] void mesh_and_report(int fd, const std::string& path, int dim) {
  char status = 1;
  std::string message;
  GmshMesh mesh;
  try {
    const int type = dim == 2 ? 2 : 4;
    GmshSession gmsh;
    gmsh.open(path);
    gmsh.elements_by_type(type, mesh.element_tags, mesh.element_nodes);
    if (mesh.element_tags.empty()) {
      gmsh.generate(dim);
      gmsh.elements_by_type(type, mesh.element_tags, mesh.element_nodes);
    }
    gmsh.nodes(mesh.node_tags, mesh.coords);
    status = 0;
  } catch (const std::exception& e) {
    message = e.what();
  } catch (...) {
    message = "Gmsh failed";
  }
  bool ok = write_all(fd, &status, 1);
  if (status == 0)
    ok = ok && write_vector(fd, mesh.element_tags) && write_vector(fd, mesh.element_nodes) &&
         write_vector(fd, mesh.node_tags) && write_vector(fd, mesh.coords);
  else
    ok = ok && write_all(fd, message.data(), message.size());
  ::close(fd);
  std::_Exit(ok ? 0 : 1);  // no atexit handlers or destructors of the parent's state
}

// What the child may allocate: the memory the machine has available now (at least 1 GB), so
// that a runaway mesh fails in the child instead of pushing the run out of memory. Not under
// AddressSanitizer, whose shadow memory needs the address space.
void limit_child_memory() {
#if !defined(__SANITIZE_ADDRESS__)
  const long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) {
    const double avail = static_cast<double>(pages) * static_cast<double>(page);
    const rlim_t cap = static_cast<rlim_t>(std::max(avail, 1e9));
    const rlimit r{cap, cap};
    setrlimit(RLIMIT_AS, &r);
  }
#endif
}

}  // namespace

GmshMesh read_gmsh_mesh(const std::string& path, int dim) {
  api();  // a library that cannot be loaded is said here, in the parent
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(std::string("cannot start Gmsh: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("cannot start Gmsh: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    limit_child_memory();
    mesh_and_report(fds[1], path, dim);
  }
  ::close(fds[1]);
  std::string buf;
  char chunk[1 << 16];
  for (;;) {
    const ssize_t r = ::read(fds[0], chunk, sizeof chunk);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) break;
    buf.append(chunk, static_cast<std::size_t>(r));
  }
  ::close(fds[0]);
  int wstatus = 0;
  while (::waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  if (!buf.empty() && buf[0] == 1) throw std::runtime_error(buf.substr(1));
  GmshMesh mesh;
  std::size_t at = 1;
  const bool complete = !buf.empty() && buf[0] == 0 && read_vector(buf, at, mesh.element_tags) &&
                        read_vector(buf, at, mesh.element_nodes) &&
                        read_vector(buf, at, mesh.node_tags) && read_vector(buf, at, mesh.coords) &&
                        at == buf.size() && WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0;
  if (complete) return mesh;
  if (WIFSIGNALED(wstatus))
    throw std::runtime_error(
        "Gmsh stopped on signal " + std::to_string(WTERMSIG(wstatus)) +
        " (" + strsignal(WTERMSIG(wstatus)) +
        ") before giving a mesh: an invalid geometry, or a mesh too large for the memory "
        "available (check Mesh.MeshSizeMax and the geometry's units)");
  throw std::runtime_error("Gmsh ended (exit code " +
                           std::to_string(WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1) +
                           ") before giving a mesh; does the file call Exit?");
}

}  // namespace periadapt
