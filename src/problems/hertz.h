// `hertz-3d` (docs/problems.md): the closed-form Hertz contact of an elastic half-space and a
// rigid sphere, and the same two quantities measured on a solution of the problem, so that a
// test and the docs compare them the same way.
#pragma once

#include "problems/problem.h"

namespace cb {

struct HertzContact {
  double radius = 0.0;         // a = (3 P R / (4 E*))^(1/3), E* = E / (1 - nu^2)
  double peak_pressure = 0.0;  // p0 = 3 P / (2 pi a^2)
};

// The closed form for a total force P, sphere radius R, Young's modulus E and Poisson's ratio
// nu of the block.
HertzContact HertzClosedForm(double force, double sphere_radius, double youngs_modulus,
                             double poisson_ratio);

// Measured on the contact reactions r of a `hertz-3d` solution (the quarter model: the contact
// point at the origin, pressure p(rho) = p0 sqrt(1 - rho^2 / a^2)):
//   radius: from the second moment, sum |r_p| rho_p^2 / sum |r_p| = 2 a^2 / 5 for Hertz;
//   peak_pressure: the reaction of the node at the origin over its tributary area (h_x h_y / 4
//   of the first cell).
HertzContact MeasureHertzContact(const Problem& problem, const Vec& r);

}  // namespace cb
