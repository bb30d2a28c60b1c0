#pragma once
// Dual-horizon form of the linear peridynamic solid: every family membership "j in H(i)" carries
// the force state of its owner, t_ij (from i's weighted volume and dilatation), acting on both
// ends; node i collects its own memberships and, through the transpose, those of the families
// that contain it (its dual horizon), each with that owner's partial volume and influence. This
// is the ordinary state-based sum  f_i = sum (T_i<xi> - T_j<-xi>) V_j  taken over the actual
// memberships, so Newton's third law holds for any mix of horizons; on a uniform grid it equals
// the plain LPS kernel. Bonds break (owner's s0) before the forces are evaluated, in a separate
// pass, so the sums read fixed bond states and do not depend on the threads.
#include <cstdint>
#include <vector>

#include "material/dual_rows.hpp"
#include "material/lps.hpp"

namespace periadapt {

// Needs bonds.t_* (build_transpose). Same contract as lps_forces; `split`: a distributed pass's
// share (its rows' breaks, made every rank's by split.gather_breaks before the dilatations; the
// forces of split.rows; every rank's breaks applied and logged here).
std::size_t lps_dual_forces(NodeSet& nodes, BondFamilies& bonds, InfluenceShape shape,
                            const LpsConstants& c, bool allow_breaking, LpsScratch& scratch,
                            std::vector<std::uint64_t>* broken_log, std::vector<double>* W,
                            const DualRows& split = {});

}  // namespace periadapt
