#pragma once
// Gmsh's C API, loaded when a deck first reads a Gmsh file. Linking libgmsh brings OpenCASCADE,
// FLTK and X11 with it, whose relocations cost every process about 0.1 s at start-up (a program
// that links it and prints a line: 0.10 s against 0.006 s), decks that never read Gmsh included.
#include <cstddef>
#include <string>
#include <vector>

namespace periadapt {

// One Gmsh session (Gmsh keeps global state: one at a time), finalized on destruction. Every call
// throws std::runtime_error with Gmsh's own message when Gmsh reports an error, and the
// constructor when the library cannot be loaded.
class GmshSession {
 public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  void open(const std::string& path);
  void generate(int dim);
  // Elements of one type: their tags and their nodes' tags (corners per element, in order).
  void elements_by_type(int type, std::vector<std::size_t>& tags, std::vector<std::size_t>& nodes);
  // Every node of the model: tags and coordinates (x, y, z per node).
  void nodes(std::vector<std::size_t>& tags, std::vector<double>& coords);
};

// The linear elements of a Gmsh file (triangles for dim 2, tetrahedra for dim 3; a geometry
// without a mesh is meshed first) and every node, read by a child process: a script's `Exit`,
// a crash inside Gmsh or a mesh that outgrows the memory left ends that process, not the run,
// and comes back as a std::runtime_error saying so (as do Gmsh's own errors).
struct GmshMesh {
  std::vector<std::size_t> element_tags, element_nodes, node_tags;
  std::vector<double> coords;
};
GmshMesh read_gmsh_mesh(const std::string& path, int dim);

}  // namespace periadapt
