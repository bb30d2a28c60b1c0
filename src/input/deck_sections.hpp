#pragma once
// The deck loader's parts (input/deck.cpp reads the YAML and calls these in order): one parser
// per group of sections, each filling its part of the Deck from the top-level mapping, and the
// helpers they share.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "input/deck.hpp"
#include "input/yaml_section.hpp"
#include "model/time_function.hpp"

namespace periadapt::deck_sections {

void parse_model_and_material(Section& top, Deck& dk);
void parse_discretization_and_cracks(Section& top, Deck& dk);
void parse_loading_and_damage(Section& top, Deck& dk);
void parse_solver(Section& top, Deck& dk);  // also the rules joining solver, material and damage
void parse_blocks(Section& top, Deck& dk);  // after the solver (pairing, solver type)
void parse_adapt(Section& top, Deck& dk);
void parse_output(Section& top, Deck& dk);  // after the loads and motions it may name

Vec3 to_vec(const std::vector<double>& v);
// A region: box, disk, polygon, cylinder, sphere, surface, gmsh or all (optionally `outside`).
Shape parse_region(Section s, int dim);
// `dim` components: numbers, expressions of x, y, z, t, or null (free).
// `at`, when given, receives where each component was written.
std::array<std::optional<std::string>, 3> parse_components(Section& s, const std::string& key,
                                                           int dim,
                                                           std::array<DeckPlace, 3>* at = nullptr);
TimeFunction parse_time(std::optional<Section> s);
// A material mapping's poisson_ratio under a bond-based model: only its fixed value nu_bb
// (`whose`: words naming the material in the message, e.g. "of every block "); returns it.
double check_bond_based_poisson(Section& s, double nu_bb, const std::string& whose);
// A material mapping's fracture_energy or critical_stretch (not both).
void parse_fracture_keys(Section& s, std::optional<double>& G0, std::optional<double>& s0);
bool segment_meets_body(const Box& body, const Vec3& a, const Vec3& b, int dim);

// Files a deck names are found relative to its folder.
void set_deck_folder(const std::filesystem::path& folder);
void set_grid_spacing(double dx);
std::filesystem::path deck_folder();

}  // namespace periadapt::deck_sections
