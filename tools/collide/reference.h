// collide's reference side: the two-body impact case, how an outcome is
// measured from the body states before and after contact (the same function
// for the reference solution and for LIGGGHTS output, see runner.h), the
// closed forms, and the RK4 integration of the contact ODE.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/collision.h"
#include "core/viscoelastic.h"

namespace collide {

using viscoelastic::Vec3;

enum class Geometry { Pair, Wall, MeshWall };
// NoHistory (stock, a dashpot only): for LIGGGHTS runs of its settings; no reference models it.
enum class Tangential { History, Pournin, NoHistory };

Geometry parseGeometry(const std::string& s);
Tangential parseTangential(const std::string& s);
std::string name(Geometry g);
std::string name(Tangential t);

// Sphere i hits sphere j (or a wall at x = 0 with normal +x) along x.
// Velocities are relative (i with respect to j, at the centres) and split
// between the spheres so the total momentum is zero; the impact lies in the
// x-y plane. Spins are given per sphere. The numeric defaults are Table 3.1's
// glass beads, for the tests; the `collide` CLI takes its defaults from
// inputs/materials.in instead.
struct Case {
    Geometry geometry = Geometry::Pair;
    Tangential tangential = Tangential::Pournin;
    bool limitForce = false;
    bool exactRestitution = false;  // the model's exactRestitution setting
    // exactCollision's continuous law: the spring is driven by
    // viscoelastic::springDrive's rate (the spins at the rigid arms R, the
    // orbital part scaled by d / (R1 + R2)) and its force is the per-unit-mass
    // oscillator times the drive's mass; the spring does not slide where Fn
    // passes through zero. The same law as exactCollision
    // where friction never binds (the ODE caps at mu |Fn| at each instant,
    // exactCollision at mu times the mean |Fn| over a step). (The ODE only;
    // LIGGGHTS runs take the setting from their options.)
    bool rigidArmSpring = false;
    viscoelastic::ContactParameters params{1e-4, 0.56, 0.46, 0.5};
    double radius1 = 1.5e-3, radius2 = 1.5e-3;    // [m]
    double density1 = 2500.0, density2 = 2500.0;  // [kg/m^3]
    double normalSpeed = 1.0;                     // approach speed, > 0 [m/s]
    double tangentialSpeed = 0.0;                 // of i relative to j along +y [m/s]
    Vec3 spin1 = Vec3::Zero(), spin2 = Vec3::Zero();  // [rad/s]
    double dt = 1e-6;                                 // LIGGGHTS timestep [s]

    double mass1() const;
    double mass2() const;  // infinite (0 returned) for walls
    double effectiveMass() const;
    bool isWall() const { return geometry != Geometry::Pair; }
};

// Positions, velocities and spins of both bodies at one instant.
struct BodyStates {
    double time = 0.0;
    Vec3 x1, v1, w1;
    Vec3 x2 = Vec3::Zero(), v2 = Vec3::Zero(), w2 = Vec3::Zero();
};

// What a collision did, in the quantities of Chung & Ooi (2011).
struct Outcome {
    double restitution = 0.0;          // -(post normal rel. velocity)/(pre)
    double duration = 0.0;             // time with positive overlap [s]
    double peakOverlap = 0.0;          // [m]
    double tangentialRestitution = 0;  // -(post contact-point tangential velocity)/(pre)
    double spin1 = 0.0;                // z spin of sphere i after impact [rad/s]
    double reboundAngle = 0.0;         // atan(contact-point tangential / normal speed) after [deg]
};

// Overlap, normal (j to i) and contact-point tangential velocity of i
// relative to j, with LIGGGHTS' lever arm R - overlap/2.
struct ContactKinematics {
    double overlap;
    Vec3 normal;
    double normalVelocity;  // (v1 - v2).n, negative while approaching
    Vec3 tangentialVelocity;
};
ContactKinematics kinematics(const Case& c, const BodyStates& s);

// Outcome from the states before and after contact plus the duration and
// peak overlap recorded in between.
Outcome outcomeOf(const Case& c, const BodyStates& before, const BodyStates& after, double duration,
                  double peakOverlap);

// The bodies moved in free flight (both ways in time) to the nearest instant
// at which they just touch: what outcomeOf reads. Unchanged if the line of
// relative motion never reaches the touching distance.
BodyStates atTouch(const Case& c, const BodyStates& s);

// Initial state: touching (zero overlap), approaching, the line of centres
// along x; with `gap`, the same bodies gap / normalSpeed earlier in their
// free flight (they touch in exactly this state).
BodyStates initialState(const Case& c, double gap = 0.0);

// Continuous solution by RK4 with `stepsPerTc` steps per contact duration;
// the Coulomb switch is applied after every step (error O(1/stepsPerTc)).
// `after`, if given, receives the bodies at the first step past separation.
Outcome integrateContactOde(const Case& c, int stepsPerTc = 20000, BodyStates* after = nullptr);

// Closed forms, where they exist for the case (head-on impacts; the sticking
// and gross-sliding regimes of oblique impacts on a wall or a pair).
struct ClosedForm {
    Outcome outcome;
    bool hasTangential = false;
    std::string regime;  // "normal", "sticking", "sliding"
};
std::optional<ClosedForm> closedForm(const Case& c);

// The reference: closed form where it exists, the ODE otherwise. With
// exactRestitution the restitution and duration are the requested en and tc.
struct Reference {
    Outcome outcome;
    std::string source;  // "closed form (...)" or "ODE"
};
Reference reference(const Case& c);

// The continuous law with its instantaneous Coulomb cap for a wall collision
// in 1D, solved independently of cappedFlow: the normal motion in closed form
// from (0, 1), the spring free while sticking and on the cap while sliding,
// each event found by scanning the whole contact in `scan` intervals for a
// change of regime and bisecting it to 1e-17 tc. Normal per unit meff = 1,
// the spring per unit m_t (kappa: the cap per unit Fn). Returns the contact
// point's rate after the contact; NaN where stick and slide alternate
// without end (more than 1,000 events: 3 of benchmarks/friction_sweep's
// 20,000 random cases).
double cappedLawExit(const viscoelastic::FreeOscillator& n, const viscoelastic::FreeOscillator& s, bool limitForce,
                     double kappa, double vt0, int scan = 200000);

// A wall collision (approach 1 m/s, the contact point at vt along x) stepped
// by exactCollision's core at each start phase, the tangential law built as
// the model builds it, against cappedLawExit: the law's exit rate and the
// worst deviation from it, in units of vt, and its phase. Empty where the law
// has no oscillators (limitForce with an en a cut contact cannot restitute);
// NaN exit and worst where cappedLawExit does not finish.
struct AgainstTheLaw {
    double exit, worst, worstPhase;
};
std::optional<AgainstTheLaw> wallFrictionAgainstTheLaw(const viscoelastic::ContactParameters& p, double vt,
                                                       double tcOverDt, bool limitForce,
                                                       const std::vector<double>& phases);

}  // namespace collide
