// Resolving a scene's `where:` selections on a discretization: boundary curves become lists of
// boundary edges, points become (face, u, v) locations on the reference limit surface.
#pragma once

#include <string>
#include <vector>

#include "mlshell/scene.hpp"
#include "mlshell/subdivision/subdivision_discretization.hpp"

namespace mlshell {

/// What a generated cage looks like, for named sides, corners and point(u, v).
struct CageFrame {
  bool generated = false;
  double x0 = 0, y0 = 0, width = 0, height = 0;
  double cut_x = 0, cut_y = 0;  ///< l-shape notch (0 for a rectangle)
  static CageFrame from(const GeometrySpec& geometry);
};

/// Boundary edges selected by a curve selection; throws SceneError naming `where` if empty.
std::vector<BoundaryEdge> select_curve(const SubdivisionDiscretization& disc,
                                       const CurveSelection& sel, const CageFrame& frame,
                                       const std::string& where);

/// The surface point selected by a point selection; throws SceneError naming `where` if the
/// point does not exist (a corner the cage does not have, a point off the domain).
SurfacePoint select_point(const SubdivisionDiscretization& disc, const PointSelection& sel,
                          const CageFrame& frame, const std::string& where);

/// Nearest point of the reference limit surface to `target` (candidate faces by control-point
/// centroid, then a clamped Newton projection).
SurfacePoint nearest_surface_point(const SubdivisionDiscretization& disc, const Point3& target,
                                   double* distance = nullptr);

}  // namespace mlshell
