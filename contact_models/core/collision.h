// `exactCollision on`: every single binary collision restitutes what the
// continuous law restitutes, whatever the phase at which it starts within a
// step and whatever the timestep (below the stability limit).
//
// The error of a single collision comes from three places, each removed here:
//  - inside the contact the leapfrog map of the linear law is not the exact
//    flow over a step. The linear law F = kStep x_n + cStep v_{n-1/2} (per
//    unit mass) whose leapfrog map IS the exact flow exists in closed form:
//    two samples of a damped oscillator obey x_{n+1} = a x_n - b x_{n-1}
//    with a = 2 e^(-c dt/2) cos(w dt), b = e^(-c dt), so
//    kStep = (1 + b - a) / dt^2 and cStep = (1 - b) / dt;
//  - the contact starts between two steps: at its first overlapping step
//    the overlap x1 and the approach rate v0 give the time since first
//    touch, s = x1 / v0 (free flight), and the continuous contact X from
//    (0, v0) is at X(s), not x1, as the flight felt no force. The first
//    force puts the next sample on X(s + dt); the second step takes X(s) as
//    its previous sample (one number kept for one step);
//  - it ends between two steps: the samples give the continuous state, and
//    when the overlap (or, with limitForce, the force) reaches zero within the
//    coming step at s_e, the last force makes the rate after the step the
//    exit rate X'(s_e).
// Friction follows the law's instantaneous cap mu |Fn(t)| through the step
// (cappedFlow, below): where the spring stays clear of the cap one step on,
// and its excess over the cap, extrapolated from either end of the step at
// its rate there, too, the step is the plain law and a check; a step that
// may reach the cap runs out of line and finds every event inside it. A
// contact between two steps is otherwise untouched: a few multiplications
// and comparisons per step more than the plain law (more with a pull,
// between two spheres); the start and end need a few transcendental
// evaluations, once per contact.
//
// Per unit mass; the LIGGGHTS model multiplies by meff. State per contact:
// its phase (fresh, touching, ended), kept in the contact history.
#pragma once

// The pieces, each including what it uses:
#include "free_flow.h"         // the free damped oscillator's closed-form flow
#include "roots.h"             // event finding
#include "step_law.h"          // the normal step law: exactCollisionStep, stepLaw
#include "capped_flow.h"       // the tangential law under its cap, through a step
#include "exact_tangential.h"  // the tangential force per step; stepped single collisions

// (not used by the pieces: kept for what included it through this header)
#include "exact.h"
