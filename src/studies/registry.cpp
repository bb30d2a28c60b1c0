#include "studies/registry.hpp"

#include "studies/bobaru_1d_static.hpp"
#include "studies/bobaru_1d_wave.hpp"
#include "studies/bobaru_density_jump.hpp"
#include "studies/bobaru_jumps.hpp"
#include "studies/pdro_bar.hpp"
#include "studies/pdro_disk.hpp"
#include "studies/pdro_sent.hpp"
#include "studies/static_plate_2d.hpp"
#include "studies/static_plate_refined.hpp"
#include "studies/wave_levels_2d.hpp"
#include "studies/wave_patch_2d.hpp"
#include "studies/weak_directions.hpp"

namespace periadapt {

namespace {
template <class O>
O with_overlay_flags(O o, const StudyOptions& s) {
  o.pim = s.pim;
  o.gaussian = s.gaussian;
  o.whole_bond = s.whole_bond;
  return o;
}
}  // namespace

const std::vector<Study>& studies() {
  static const std::vector<Study> table = {
      {"bobaru-1d-static", "Bobaru et al. 2009, sections 2-5: static 1D bar, uniform and adaptive grids",
       [](const StudyOptions& o) { return run_bobaru_1d_study(o.out_dir); }},
      {"bobaru-1d-jumps", "Bobaru et al. 2009, 3.2: the inverted-triangle bar's jumps and load spikes against Eqs. 29-34",
       [](const StudyOptions& o) { return run_bobaru_jumps_study(o.out_dir); }},
      {"bobaru-1d-wave", "Bobaru et al. 2009, 6.2: half-Gaussian wave in a 1D bar, Tables IV-V",
       [](const StudyOptions& o) { return run_bobaru_1d_wave_study(o.out_dir); }},
      {"bobaru-1d-density-jump", "Bobaru et al. 2009, 6.2.1: a wave through a denser middle third at constant horizon, Table III",
       [](const StudyOptions& o) { return run_bobaru_density_jump_study(o.out_dir, o.quick); }},
      {"static-plate-2d", "thesis 4.1: static plate in tension on the uniform grid, with and without surface correction",
       [](const StudyOptions& o) { return run_static_plate_study(o.out_dir); }},
      {"static-plate-refined", "thesis 4.1, models A-C: the static plate with its left half refined to levels 1-3",
       [](const StudyOptions& o) { return run_static_plate_refined_study(o.out_dir); }},
      {"static-plate-upper", "thesis 4.1, models D-F: the static plate with its upper half refined to levels 1-3",
       [](const StudyOptions& o) { return run_static_plate_upper_study(o.out_dir); }},
      {"wave-patch-2d", "thesis 4.2, models A-C: a Gaussian wave crossing a level-1 patch",
       [](const StudyOptions& o) { return run_wave_patch_study(o.out_dir); }},
      {"wave-levels-2d", "thesis 4.2, Tables 4.4-4.6: a Gaussian wave through regions refined to levels 1-3",
       [](const StudyOptions& o) { return run_wave_levels_study(o.out_dir); }},
      {"weak-directions", "thesis 5.2: the weak bond directions of regular grids",
       [](const StudyOptions& o) { return run_weak_directions_study(o.out_dir); }},
      {"pdro-bar", "Stewart & Jeon 2019, 3.1: bar strain at failure, native grids against the overlay",
       [](const StudyOptions& o) {
         PdroBarOptions bar = with_overlay_flags(PdroBarOptions{}, o);
         if (o.quick) bar.targets = {0.9e-3, 0.5e-3, 0.2e-3};
         return run_pdro_bar_study(o.out_dir, bar);
       }},
      {"pdro-sent", "Stewart & Jeon 2019, 3.2: SENT failure stress against LEFM",
       [](const StudyOptions& o) {
         PdroSentOptions sent = with_overlay_flags(PdroSentOptions{}, o);
         if (!o.deck.empty()) sent.deck = o.deck;
         if (o.quick) sent.native_spacings = {1.0e-3}, sent.overlay_n = {2.0, 5.0};
         return run_pdro_sent_study(o.out_dir, sent);
       }},
      {"pdro-disk", "Stewart & Jeon 2019, 3.3: crack bifurcation in the cooled disk with the overlay",
       [](const StudyOptions& o) {
         PdroDiskOptions disk = with_overlay_flags(PdroDiskOptions{}, o);
         if (!o.deck.empty()) disk.deck = o.deck;
         if (o.quick) disk.overlay_n = {2.0};
         return run_pdro_disk_study(o.out_dir, disk);
       }},
  };
  return table;
}

const Study* find_study(const std::string& name) {
  for (const Study& s : studies())
    if (name == s.name) return &s;
  return nullptr;
}

}  // namespace periadapt
