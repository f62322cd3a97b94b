// Table 1 of Kopaničáková, Krause, Tamstorf, "Subdivision-based nonlinear multiscale cloth
// simulation", SIAM J. Sci. Comput. 2019: the denim used in all of the paper's experiments.
#include "mlshell/scene.hpp"

namespace mlshell {

ClydeMaterial denim_table1_preset() {
  constexpr double kMegapascal = 1e6;
  ClydeMaterial denim;
  denim.k = {4.79 * kMegapascal, 4.52 * kMegapascal, 9.03 * kMegapascal, 2.44 * kMegapascal};
  // Table 1 omits mu_j1. The first entry of each row below completes it so that sum_i mu_ji = 1,
  // i.e. phi_j'(0) = 1 and k_j is the small-strain stiffness (DESIGN.md, "Material and shell
  // kinematics"). The row lengths are the paper's d = [5, 1, 5, 3].
  denim.mu = {{{-4617.79, -1482.1, 276.43, 2407.67, 3416.79},
               {1.0},
               {84.882, 0.658, -185.7, -45.82, 146.98},
               {-10.87, 0.79, 11.08}}};
  denim.alpha = {{{-7.80, 10.80, 18.95, -12.89, 1.61},
                  {1.0},
                  {12.71, -12802.0, 17.91, 30.07, 24.68},
                  {2.95, -2823.9, 4.29}}};
  return denim;
}

ClydeMaterial denim_preset() {
  ClydeMaterial denim = denim_table1_preset();
  // At small strain |k2 E11 E22| / 2√(AB) = k2/√(k1 k3) = 0.687 < onset: Table 1's tangent.
  denim.coupling_limit = {true, 0.75, 0.9};
  return denim;
}

}  // namespace mlshell
