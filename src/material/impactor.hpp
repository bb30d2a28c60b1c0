#pragma once
// Rigid impactors: a sphere (a disk in 2D) or a finite cylinder with a mass and a velocity, which
// pushes the nodes it meets. A node of spacing h touches the impactor when its centre lies within
// h/2 of the surface (its cell's face reaches it); it is pushed along the surface normal with
//   F_i = stiffness_factor c_i / delta_i V_i^2 p,   p = h_i / 2 - (signed distance to the surface),
// the contact forces' pair law (material/contact.hpp) with the impactor as the partner, and the
// impactor takes the sum of the opposite forces: momentum of body and impactor together is kept
// to round-off. The impactor moves as a rigid body (no rotation) under that force.
#include <cstdint>
#include <vector>

#include "core/geometry.hpp"

namespace periadapt {

struct NodeSet;

struct Impactor {
  enum class Shape { Sphere, Cylinder } shape = Shape::Sphere;
  Vec3 center{0, 0, 0};  // sphere: centre; cylinder: midpoint of its axis
  Vec3 axis{1, 0, 0};    // cylinder: unit axis
  double radius = 0;
  double half_length = 0;  // cylinder
  double mass = 0;         // kg (2D: for the model's thickness)
  Vec3 velocity{0, 0, 0};
  double stiffness_factor = 15.0;
  Vec3 force{0, 0, 0};  // the nodes' push on it at the latest force pass
  double contact_energy = 0;  // sum of 1/2 k p^2 at the latest force pass

  double kinetic_energy() const {
    return 0.5 * mass * dot(velocity, velocity);
  }
};

// Adds the impactors' push to nodes.f (for `rows` only when given; every active node counts for
// the impactors' forces), and with W each node's contact energy 1/2 k p^2 / V_i to W (the rows').
void add_impactor_forces(std::vector<Impactor>& impactors, NodeSet& nodes,
                         const std::vector<std::uint32_t>* rows = nullptr,
                         std::vector<double>* W = nullptr);

// Each node's impactor contact energy density, added to W.
void add_impactor_energy(const std::vector<Impactor>& impactors, const NodeSet& nodes,
                         std::vector<double>& W);

// Node i's impactor stiffness for the stable-step sum: stiffness_factor c_i / delta_i V_i.
double impactor_stiffness_bound(const std::vector<Impactor>& impactors, const NodeSet& nodes,
                                std::size_t i);

}  // namespace periadapt
