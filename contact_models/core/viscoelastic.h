// Physics core of the viscoelastic (linear spring-dashpot) contact law with
// Pournin et al. (2001) coefficients: the whole core in one include. Pure C++
// (Eigen only): the LIGGGHTS models, the tools and the tests all call these
// functions, so each formula exists once. Equation numbers refer to the
// thesis chapter (Eq. 3.x).
//
//   pournin.h      Eq. 3.22-3.25: (tc, en, et) -> kn, cn, kt, ct per unit meff, and back
//   law.h          the force law per step: Eq. 3.20 normal, 3.18 Coulomb, 3.5/3.18-3.21 tangential
//   stability.h    binary timestep limit (Jury) and the multi-contact guard
//   restitution.h  restitution of the continuous law with limitForce (Schwager & Poeschel)
//   discrete.h     a binary collision as LIGGGHTS integrates it, phase averages
//   exact.h        coefficients that restitute exactly at a given timestep (phase average)
//   collision.h    every single collision exact: step-exact law, start and end within a step
#pragma once

#include "pournin.h"
#include "law.h"
#include "stability.h"
#include "restitution.h"
#include "discrete.h"
#include "exact.h"
#include "collision.h"
