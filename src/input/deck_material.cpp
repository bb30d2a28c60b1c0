// Deck sections model and material.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/expression.hpp"
#include "input/deck_sections.hpp"
#include "material/formulation.hpp"
#include "input/yaml_section.hpp"

namespace periadapt::deck_sections {

void parse_model_and_material(Section& top, Deck& dk) {
  // --- model
  {
    Section m = top.section("model");
    dk.dim = static_cast<int>(m.integer("dimension", std::nullopt, [](long v) {
      return (v >= 1 && v <= 3) ? std::string() : std::string("must be 1, 2 or 3");
    }));
    if (dk.dim == 2) {
      std::string p = m.choice("plane", {"stress", "strain"}, "stress");
      dk.plane = p == "stress" ? PlaneCondition::Stress : PlaneCondition::Strain;
    } else if (m.has("plane")) {
      m.fail("plane", "only 2D models have a plane condition");
    }
    dk.thickness = m.number("thickness", 1.0, positive());
    if (dk.dim == 3 && m.has("thickness")) m.fail("thickness", "3D models have no thickness key");
    dk.formulation = m.choice("formulation", Formulation::names(), "pmb");
    if (dk.dim == 1 && !Formulation::named(dk.formulation)->works_in_1d())
      m.fail("formulation", "the state-based LPS model is for 2D and 3D; use pmb in 1D");
    m.finish();
  }
  // --- material
  {
    Section s = top.section("material");
    dk.material_name = s.text("name", "material");
    dk.E = s.number("youngs_modulus", std::nullopt, positive());
    dk.rho = s.number("density", std::nullopt, positive());
    const double nu_bb = bond_based_poisson(dk.dim, dk.plane);
    const Formulation f = *Formulation::named(dk.formulation);
    if (!f.bond_based()) {
      dk.nu = s.number("poisson_ratio", std::nullopt, [](double v) {
        return (v > -1.0 && v < 0.5) ? std::string()
                                     : std::string("must be in (-1, 0.5) for the LPS model");
      });
    } else if (s.has("poisson_ratio")) {
      dk.nu = check_bond_based_poisson(s, nu_bb, "");
    }
    parse_fracture_keys(s, dk.G0, dk.s0);
    dk.thermal_strain = s.number("thermal_strain", 0.0, [](double v) {
      return std::abs(v) < 0.1 ? std::string()
                               : std::string("alpha dT is a small strain: |value| < 0.1");
    });
    if (const BondLaw* law = f.law) {
      dk.law_stress = s.number(std::string(law->stress_key), std::nullopt, positive());
      if (law->needs_fracture_energy && !s.has("fracture_energy"))
        s.fail("fracture_energy", "formulation " + dk.formulation +
                                      " needs the fracture energy G0 (J/m^2): its bonds soften "
                                      "until they have dissipated it");
      if (s.has("critical_stretch"))
        s.fail("critical_stretch", "formulation " + dk.formulation +
                                       " derives its breaking stretch from fracture_energy; give "
                                       "that instead");
    }
    std::string sh = s.choice("micromodulus", {"constant", "triangular", "inverted_triangular"},
                              "constant");
    dk.shape = sh == "constant"     ? InfluenceShape::Constant
               : sh == "triangular" ? InfluenceShape::Triangular
                                    : InfluenceShape::InvertedTriangular;
    s.finish();
  }
}

}  // namespace periadapt::deck_sections
