// Deck list blocks: parts of the body with their own material.
#include <cmath>
#include <string>

#include "input/deck_sections.hpp"
#include "material/formulation.hpp"
#include "input/yaml_section.hpp"

namespace periadapt::deck_sections {

namespace {
// Block ids are one byte per node; far more than any deck names.
constexpr std::size_t kMaxBlocks = 63;
}  // namespace

void parse_blocks(Section& top, Deck& dk) {
  std::vector<Section> list = top.list("blocks");
  if (list.empty()) return;
  const Formulation f = *Formulation::named(dk.formulation, dk.dual_horizon);
  if (f.kind == Formulation::Kind::HistoryLaw)
    top.fail("blocks", "several materials work with formulation pmb or lps; formulation " +
                           dk.formulation + " keeps one law for the whole body");
  if (dk.dual_horizon)
    top.fail("blocks", "several materials work with bond_pairing: source_horizon (the bond "
                       "between two blocks takes the harmonic mean of their moduli on both ends)");
  if (dk.pdro.enabled)
    top.fail("blocks", "the refinement overlay (damage.overlay) re-checks bonds of one material; "
                       "remove it or the blocks");
  if (list.size() > kMaxBlocks)
    top.fail("blocks", "at most " + std::to_string(kMaxBlocks) + " blocks (this deck has " +
                           std::to_string(list.size()) + ")");
  const double nu_bb = bond_based_poisson(dk.dim, dk.plane);
  for (Section b : list) {
    BlockSpec bs;
    bs.name = b.text("name", b.path());
    if (b.has("region")) {
      const YAML::Mark mark = b.raw("region").Mark();
      if (!mark.is_null()) bs.line = mark.line + 1, bs.column = mark.column + 1;
    }
    bs.region = parse_region(b.section("region"), dk.dim);
    Section s = b.section("material");
    bs.E = s.number("youngs_modulus", std::nullopt, positive());
    bs.rho = s.number("density", std::nullopt, positive());
    if (!f.bond_based()) {
      bs.nu = s.number("poisson_ratio", dk.nu, [](double v) {
        return (v > -1.0 && v < 0.5) ? std::string()
                                     : std::string("must be in (-1, 0.5) for the LPS model");
      });
    } else if (s.has("poisson_ratio")) {
      check_bond_based_poisson(s, nu_bb, "of every block ");
    }
    parse_fracture_keys(s, bs.G0, bs.s0);
    if (dk.damage && !bs.G0 && !bs.s0)
      s.fail("", "damage is enabled: give this block's fracture_energy (G0) or critical_stretch "
                 "(a part that must not crack is a damage.no_fail region)");
    s.finish();
    b.finish();
    dk.blocks.push_back(std::move(bs));
  }
}

}  // namespace periadapt::deck_sections
