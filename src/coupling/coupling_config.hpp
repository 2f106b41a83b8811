#pragma once
// Configuration of the two-way CFD-DEM coupling (paper section 2.1.1).
#include "closures/drag.hpp"

namespace fluidbed {

/// How particle volume is shared among grid cells.
enum class VoidageMethod {
  Centre,    ///< the paper's counting: all of a particle's volume in the cell holding its centre
  Bilinear,  ///< cloud-in-cell: shared among the four nearest cell centres, smooth as a particle crosses a face
};

struct CouplingConfig {
  VoidageMethod voidage = VoidageMethod::Bilinear;
  /// Depth of the 2D bed that turns particle volume into a volume fraction, m (0: one diameter of species 0,
  /// a monolayer of spheres).
  double depth = 0.0;
  /// Smallest voidage the gas and the drag law see: soft contacts can overlap enough to push the counted
  /// voidage to impossible values (paper, section 2.1).
  double eps_min = 0.3;
  int dem_substeps = 1;        ///< DEM steps per gas step
  DragLaw drag_law = DragLaw::ErgunWenYu;   ///< the paper's Eqs. 13-14 by default
  DragSwitch drag_switch = DragSwitch::Sharp;  ///< Ergun/Wen-Yu join of ErgunWenYu and Gidaspow
  bool pressure_gradient_force = true;  ///< -V_p grad P on each particle (implied by -eps grad P in Eq. 12)
};

}  // namespace fluidbed
