// Independent reference for the CONTINUOUS contact law (Cundall's linear
// spring-dashpot with Pournin's coefficients, Coulomb cap with Luding's spring
// reset) for one collision of a sphere with a flat wall.  Written from the
// equations only: it uses nothing from contact_models/ or the other tools, so it
// can check the time-stepped implementation.
//
// Conventions (all SI):
//  * Normal: overlap x >= 0, x' > 0 while approaching.  Fn = kn x + cn x'
//    (repulsive positive), meff = sphere mass for a wall.  kn = meff (pi^2 +
//    ln^2 en)/tc^2, cn = -2 meff ln(en)/tc, so x(t) = v/wd e^{-b t} sin(wd t)
//    with wd = pi/tc, b = -ln(en)/tc: the overlap closes at exactly tc with
//    x'(tc) = -en v.
//  * Tangential: spring xi with xi' = w (w: contact point's tangential velocity
//    relative to the wall), trial T = kt xi + ct w, force on the contact point
//    -T, m_t w' = force.  kt, ct as kn, cn with m_t and et.  Cap |T| <= mu |Fn(t)|;
//    while the cap binds the spring is slaved to it (xi = (mu|Fn| s - ct w)/kt).
//  * Only 1D tangential motion: a sphere without initial spin hitting a flat
//    wall keeps w, xi and the force on one line (the line of vt).
//  * Everything scales with meff (and the tangential part with m_t/meff only),
//    so no mass enters the API.
//
// Method: between events both motions are closed form (the normal motion and the
// sticking tangential motion are damped oscillators with the same damped
// frequency pi/tc; while sliding w' = -mu|Fn| s/m_t integrates to the normal
// velocity change).  Only the event times are found numerically: the event
// functions are sampled on a grid of step ~ 0.1 tc tolerance^(1/4) and
// bracketed roots are bisected to tolerance * tc.  No error accumulates
// between events.
#pragma once

#include <cstdint>

namespace continuous {

struct Material {
  double tc;  // contact duration of the (unlimited) normal law [s]
  double en;  // normal restitution, (0, 1]
  double et;  // tangential "restitution" of the tangential oscillator, (0, 1]
  double mu;  // Coulomb friction; +infinity means no cap at all
};

struct WallImpact {
  double vn;                // approach speed, > 0
  double vt;                // contact point's tangential velocity, no spin
  bool limitForce;          // Fn = max(0, kn x + cn x'): force ends when Fn reaches 0
  double tangentialMassRatio = 2.0 / 7.0;  // m_t / meff (solid sphere, rigid arm R)
};

struct Exit {
  double vn;        // normal rate after the collision, positive away from the wall
  double vt;        // contact point's tangential velocity after the collision
  double duration;  // time the contact force acts: tc, or the time Fn reaches 0 (limitForce)
  double overlapDuration;  // until the overlap is 0 again (= duration without limitForce)
  int slides;       // number of stick->slide transitions (a slide from t = 0 counts)
};

// Throws std::invalid_argument on bad input and std::runtime_error if the
// event logic chatters (more than 10000 stick/slide transitions).
Exit wallImpact(const Material&, const WallImpact&, double tolerance = 1e-10);

// Two solid spheres, central impact with a tangential relative velocity of the
// contact points, rigid arms R1, R2 and the rotation of the normal ignored.
// 1/m_t = 1/meff + R1^2/I1 + R2^2/I2 = 7/(2 meff) for any masses and radii,
// so it is wallImpact with m_t/meff = 2/7 and meff = m1 m2/(m1+m2).
struct PairImpact {
  double m1, r1, m2, r2;  // masses and radii (inertia 2/5 m r^2)
  double vn, vt;          // relative approach speed and contact points' relative tangential velocity
  bool limitForce;
};
Exit pairImpact(const Material&, const PairImpact&, double tolerance = 1e-10);

// Closed forms of the normal motion used by the tests and the sweep.
// Effective restitution with limitForce: en^(1 - (2/pi) atan(-ln(en)/pi)).
double limitedRestitution(double en);
// Time the unlimited force kn x + cn x' crosses 0 (limitForce's end): (pi - 2 atan(-ln(en)/pi)) tc/pi.
double forceZeroTime(double tc, double en);

// Seeded random sweep over en, et in [0.1, 0.95], mu log-uniform in
// [0.05, 1e6], vt/vn in [0, 5], limitForce on/off (vn = 1, tc = 1e-4).  Each
// case is also run at tolerance/10 to measure convergence.
struct SweepCase {
  Material material;
  WallImpact impact;
  Exit exit;
};
struct SweepResult {
  int cases = 0;
  int failures = 0;                 // exceptions (chattering); worstFailure holds one
  double maxTangentialGain = 0;     // max |vt_out| / |vt_in| (vt_in != 0)
  double maxNormalRatio = 0;        // max vn_out / vn_in
  double maxConvergenceChange = 0;  // max |delta vt_out| + |delta vn_out|, over max(|vt_in|, vn_in)
  int maxSlides = 0;
  SweepCase worstGain, worstConvergence, worstFailure;
};
SweepResult randomSweep(std::uint64_t seed, int cases, double tolerance = 1e-10);

}  // namespace continuous
