#pragma once
// A swung NURBS surface (Qin & Terzopoulos, Dynamic NURBS swung surfaces for physics-based shape
// design, CAD 27(2) 1995) as what the tessellations see of a surface: its parameter domain with
// seams and poles, the orientation of its outward normal and the exact unit normal
// (surface/parametric_surface.h). The swung D-NURBS model gives these through the Model
// contract (DNurbsSwungSurface::parameter_domain, normal_orientation, parametric_surface).

#include "dnurbs/nurbs/swung_surface.h"
#include "dnurbs/surface/parametric_surface.h"

namespace dnurbs {

/// The domain [u_start, u_end] x [v_start, v_end] with its closures, those of the tensor-product
/// twin (nurbs_parameter_domain(surface.to_nurbs_surface())): a periodic profile or trajectory,
/// or a clamped one whose ends meet, is periodic; an edge that collapses to one point (an open
/// profile ending on the z axis, p_x = 0: the pole of a sphere, the apex of a cone or a hat) is
/// a pole.
ParameterDomain swung_parameter_domain(const SwungSurface& surface);

/// Which tangent cross product points outward, judged on the whole surface: the side of
/// S_u x S_v away from the z axis on average,
///   I_r = integral (S_x, S_y, 0) . (S_u x S_v) du dv
///       = -alpha^2 [integral p_x^2 p_z' du] [integral (t_x t_y' - t_y t_x') dv]
/// (S_u x S_v = alpha p_x (-p_z' t_y', p_z' t_x', alpha p_x' (t x t')), SwungSurface::unit_normal),
/// kSuCrossSv if I_r > 0 and kSvCrossSu if I_r < 0. A flat profile (p_z' = 0 everywhere, a
/// disk or an annulus: I_r = 0) has no side away from the axis; its normal then points up,
/// along +z: the sign of I_z = alpha^2 [integral p_x p_x' du] [integral (t x t') dv]. Both
/// integrals by Gauss-Legendre rules of 8 points per non-empty span (only their signs count).
/// The swung sphere (profile from south to north, counter-clockwise trajectory) gives
/// kSvCrossSu, the swung hat (from the apex down to the brim) kSuCrossSv. Throws Error if both
/// integrals vanish (a surface with no area).
NormalOrientation swung_normal_orientation(const SwungSurface& surface);

/// The surface over `domain` with the exact unit normal SwungSurface::unit_normal (its pole
/// limit included), turned to follow `orientation`: +unit_normal for kSuCrossSv, -unit_normal
/// for kSvCrossSu. The surface is copied into the returned object.
ParametricSurface swung_parametric_surface(const SwungSurface& surface,
                                           const ParameterDomain& domain,
                                           NormalOrientation orientation);

}  // namespace dnurbs
