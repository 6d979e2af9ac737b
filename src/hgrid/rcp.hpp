// Random close packing estimate of a polydisperse size distribution.
//
// Idea of Farr & Groot, J. Chem. Phys. 131, 244104 (2009): map the spheres
// onto rods on a line (rod length = sphere diameter, each size class keeping
// its share of the particle volume) and pack the rods largest first, each
// size class filling the gaps the larger ones left. The 1-D packing fraction
// estimates the 3-D random close packing fraction. Our 1-D rule (our own, a
// simplification of theirs): a gap of length g takes n = floor(phi_c g / l)
// rods of length l, evenly spaced, which leaves n + 1
// equal sub-gaps; classes fill the largest gaps first. phi_c, the monodisperse
// random close packing fraction, is what a single class reaches.
#pragma once
#include "hgrid/distribution.hpp"

namespace hgrid {

/// Monodisperse random close packing: spheres (Scott & Kilgour 1969; 0.64)
/// and disks (O'Hern et al., Phys. Rev. E 68, 011306 (2003); 0.84).
inline constexpr double kMonoRcp3 = 0.64;
inline constexpr double kMonoRcp2 = 0.84;

/// Size classes (log-spaced in r) and bisection tolerance of the estimate.
inline constexpr int kRcpClasses = 240;
inline constexpr double kRcpTol = 1e-4;

/// The estimate for d = 2 or 3 (declared in generate.hpp as well).
double estimate_rcp(int d, const Distribution& dist);

}  // namespace hgrid
