#include "reference.h"

#include <array>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>

namespace collide {

using namespace viscoelastic;

Geometry parseGeometry(const std::string& s)
{
    if (s == "pair") return Geometry::Pair;
    if (s == "wall") return Geometry::Wall;
    if (s == "mesh") return Geometry::MeshWall;
    throw std::invalid_argument("geometry must be pair, wall or mesh, not '" + s + "'");
}

Tangential parseTangential(const std::string& s)
{
    if (s == "history") return Tangential::History;
    if (s == "pournin") return Tangential::Pournin;
    throw std::invalid_argument("tangential model must be history or pournin, not '" + s + "'");
}

std::string name(Geometry g)
{
    return g == Geometry::Pair ? "pair" : g == Geometry::Wall ? "wall" : "mesh";
}

std::string name(Tangential t)
{
    return t == Tangential::History ? "history" : t == Tangential::Pournin ? "pournin" : "no_history";
}

double Case::mass1() const { return viscoelastic::sphereMass(2.0 * radius1, density1); }
double Case::mass2() const { return isWall() ? 0.0 : viscoelastic::sphereMass(2.0 * radius2, density2); }
double Case::effectiveMass() const { return viscoelastic::effectiveMass(mass1(), mass2()); }

ContactKinematics kinematics(const Case& c, const BodyStates& s)
{
    ContactKinematics k;
    Vec3 d;
    double reach;
    if (c.isWall()) {
        d = Vec3(s.x1.x(), 0.0, 0.0);
        reach = c.radius1;
    } else {
        d = s.x1 - s.x2;
        reach = c.radius1 + c.radius2;
    }
    const double dist = d.norm();
    k.overlap = reach - dist;
    k.normal = d / dist;
    const Vec3 vrel = s.v1 - s.v2;
    k.normalVelocity = vrel.dot(k.normal);
    // lever arm to the contact point; the full radius when apart
    const double cr1 = c.radius1 - 0.5 * std::max(k.overlap, 0.0);
    const double cr2 = c.radius2 - 0.5 * std::max(k.overlap, 0.0);
    const Vec3 spinArm = c.isWall() ? Vec3(cr1 * s.w1) : Vec3(cr1 * s.w1 + cr2 * s.w2);
    const Vec3 vt = vrel - k.normalVelocity * k.normal;
    k.tangentialVelocity = vt - spinArm.cross(k.normal);
    return k;
}

BodyStates atTouch(const Case& c, const BodyStates& s)
{
    // free flight: positions linear in time, velocities and spins constant
    const Vec3 r = c.isWall() ? Vec3(s.x1.x(), 0.0, 0.0) : Vec3(s.x1 - s.x2);
    const Vec3 v = c.isWall() ? Vec3(s.v1.x(), 0.0, 0.0) : Vec3(s.v1 - s.v2);
    const double reach = c.isWall() ? c.radius1 : c.radius1 + c.radius2;
    // |r + tau v| = reach: tau^2 v.v + 2 tau r.v + r.r - reach^2 = 0, the root nearest 0
    const double a = v.squaredNorm(), b = r.dot(v), q = r.squaredNorm() - reach * reach;
    const double disc = b * b - a * q;
    if (!(a > 0.0) || disc < 0.0) return s;  // at rest, or the line of motion misses the touching distance
    const double root = std::sqrt(disc);
    // the two roots (-b -+ root) / a, written so that neither cancels
    if (q == 0.0) return s;  // touching now
    const double t1 = b > 0.0 ? -q / (b + root) : (root - b) / a, t2 = b > 0.0 ? -(b + root) / a : q / (root - b);
    const double tau = std::fabs(t1) < std::fabs(t2) ? t1 : t2;
    BodyStates m = s;
    m.time += tau;
    m.x1 += tau * s.v1;
    if (!c.isWall()) m.x2 += tau * s.v2;
    return m;
}

Outcome outcomeOf(const Case& c, const BodyStates& before, const BodyStates& after, double duration,
                  double peakOverlap)
{
    // Read at the instants of touch and separation: apart, the line of
    // centres of a pair still turns (by about vt dt / 2R in a step), and with
    // it the split of the relative velocity into normal and tangential parts
    // (a frame one step after separation would shift et by up to vn dt / 2R).
    const ContactKinematics k0 = kinematics(c, atTouch(c, before));
    const ContactKinematics k1 = kinematics(c, atTouch(c, after));
    Outcome o;
    o.restitution = -k1.normalVelocity / k0.normalVelocity;
    o.duration = duration;
    o.peakOverlap = peakOverlap;
    const double u0 = k0.tangentialVelocity.norm();
    if (u0 > 0.0) {
        const Vec3 t0 = k0.tangentialVelocity / u0;
        o.tangentialRestitution = -k1.tangentialVelocity.dot(t0) / u0;
        o.reboundAngle = std::atan2(k1.tangentialVelocity.dot(t0), k1.normalVelocity) * 180.0 / kPi;
    }
    o.spin1 = after.w1.z();
    return o;
}

BodyStates initialState(const Case& c, double gap)
{
    BodyStates s;
    const double m1 = c.mass1(), m2 = c.mass2();
    const Vec3 vrel(-c.normalSpeed, c.tangentialSpeed, 0.0);
    if (c.isWall()) {
        s.x1 = Vec3(c.radius1, 0.0, 0.0);
        s.v1 = vrel;
    } else {
        // centre of mass at rest at the origin
        const double reach = c.radius1 + c.radius2;
        s.x1 = Vec3(reach * m2 / (m1 + m2), 0.0, 0.0);
        s.x2 = Vec3(-reach * m1 / (m1 + m2), 0.0, 0.0);
        s.v1 = vrel * m2 / (m1 + m2);
        s.v2 = -vrel * m1 / (m1 + m2);
        s.w2 = c.spin2;
    }
    s.w1 = c.spin1;
    // Back along the free flight that ends in this touch: the bodies then
    // touch with the line of centres along x and the requested normal and
    // tangential speeds. (Placed `gap` apart along x instead, a pair drifts
    // sideways by vt gap / vn before it touches: its normal turns by that
    // over the reach, and at vt/vn 4 the approach slows to about half.)
    const double before = gap / c.normalSpeed;
    s.x1 -= before * s.v1;
    s.x2 -= before * s.v2;
    return s;
}

namespace {

// State for the ODE: x1 v1 w1 x2 v2 w2 xi.
using State = std::array<double, 21>;

Vec3 get(const State& y, int k) { return Vec3(y[3 * k], y[3 * k + 1], y[3 * k + 2]); }
void put(State& y, int k, const Vec3& v)
{
    for (int d = 0; d < 3; ++d) y[3 * k + d] = v[d];
}

BodyStates bodyStates(const State& y, double t)
{
    BodyStates s;
    s.time = t;
    s.x1 = get(y, 0), s.v1 = get(y, 1), s.w1 = get(y, 2);
    s.x2 = get(y, 3), s.v2 = get(y, 4), s.w2 = get(y, 5);
    return s;
}

// The continuous law: normal force, and the tangential force capped as the
// chosen model caps it (pournin: total force against mu max(Fn,0); history:
// elastic force against mu |Fn|, dashpot dropped while sliding).
struct Law {
    const Case& c;
    Coefficients k;
    // rigidArmSpring: the tangential oscillator per unit mass, and the mass
    // springDrive gives it (set per state)
    double unitKt = 0, unitCt = 0;
    mutable double rigidMass = 0;

    // pournin's spring and dashpot: the type pair's, or (rigidArmSpring) the
    // oscillator per unit mass times the drive's mass
    bool pournin() const { return c.rigidArmSpring || c.tangential == Tangential::Pournin; }
    double kt() const { return c.rigidArmSpring ? rigidMass * unitKt : k.kt; }
    double ct() const { return c.rigidArmSpring ? rigidMass * unitCt : k.ct; }

    double normalForce(const ContactKinematics& ck) const
    {
        return viscoelastic::normalForce(k, ck.overlap, -ck.normalVelocity, c.limitForce);
    }

    // Returns the tangential force; `sliding` tells whether the cap binds.
    Vec3 tangentialForce(const Vec3& xi, const Vec3& vt, double Fn, bool& sliding) const
    {
        if (pournin()) {
            Vec3 f = -(kt() * xi + ct() * vt);
            const double limit = frictionLimit(c.params.mu, Fn);
            sliding = f.norm() > limit;
            if (sliding) f *= limit / f.norm();
            return f;
        }
        // After the Coulomb switch the spring sits exactly on the cap. That is
        // still sliding: history's dashpot, unbounded while sticking, must not
        // come back for a round-off (LIGGGHTS advances the spring before it
        // tests, so it never sees the boundary).
        const Vec3 elastic = -k.kt * xi;
        const double limit = c.params.mu * std::fabs(Fn);
        sliding = elastic.norm() > 0.0 && elastic.norm() >= limit * (1.0 - 1e-9);
        if (sliding) return elastic.norm() > 0.0 ? Vec3(elastic * (limit / elastic.norm())) : Vec3::Zero();
        return elastic - k.ct * vt;
    }

    // Spring length consistent with the force when the cap binds.
    Vec3 slidingSpring(const Vec3& f, const Vec3& vt) const
    {
        return pournin() ? Vec3(-(f + ct() * vt) / kt()) : Vec3(-f / k.kt);
    }
};

}  // namespace

Outcome integrateContactOde(const Case& c, int stepsPerTc, BodyStates* after)
{
    Law law{c, scaled(pourninUnitCoefficients(c.params), c.effectiveMass())};
    const Oscillator unit = pourninOscillator(c.params.tc, std::log(c.params.et));
    law.unitKt = unit.k, law.unitCt = unit.c;
    if (c.rigidArmSpring && c.limitForce) {
        // exactCollision's cut law: the oscillators solved so that the cut
        // contact restitutes en and lasts tc, the spring as long as the force
        // (with the force the cap mu Fn falls to zero, and the spring with it)
        const auto o = viscoelastic::exactCollisionOscillators(c.params, true);
        if (!o) throw std::invalid_argument("en below what a cut contact restitutes");
        const double m = c.effectiveMass();
        law.k.kn = m * o->normal.k, law.k.cn = m * o->normal.c;
        law.unitKt = o->tangential.k, law.unitCt = o->tangential.c;
    }
    const double m1 = c.mass1(), m2 = c.mass2();
    const double I1 = 0.4 * m1 * c.radius1 * c.radius1;
    const double I2 = 0.4 * m2 * c.radius2 * c.radius2;
    // the spring's velocity: at LIGGGHTS' arms, or (rigidArmSpring) exactCollision's springDrive
    const auto springVelocity = [&](const BodyStates& s, const ContactKinematics& ck) {
        if (!c.rigidArmSpring) return ck.tangentialVelocity;
        const double arm1 = c.radius1 - 0.5 * ck.overlap, arm2 = c.radius2 - 0.5 * ck.overlap;
        const viscoelastic::SpringDrive drive =
            viscoelastic::springDrive(ck.tangentialVelocity, ck.normal, ck.overlap, c.effectiveMass(), m1, c.radius1,
                                      arm1, s.w1, m2, c.radius2, arm2, s.w2);
        law.rigidMass = drive.mass;
        return drive.rate;
    };

    auto rhs = [&](const State& y, State& dy, double) {
        const BodyStates s = bodyStates(y, 0.0);
        dy.fill(0.0);
        put(dy, 0, s.v1);
        if (!c.isWall()) put(dy, 3, s.v2);
        const ContactKinematics ck = kinematics(c, s);
        if (ck.overlap <= 0.0) return;
        const Vec3 n = ck.normal;
        const Vec3 xi = get(y, 6);
        const double Fn = law.normalForce(ck);
        bool sliding;
        const Vec3 w = springVelocity(s, ck);
        const Vec3 Ft = law.tangentialForce(xi, w, Fn, sliding);
        const Vec3 F = Fn * n + Ft;
        const Vec3 nxF = n.cross(Ft);
        put(dy, 1, F / m1);
        put(dy, 2, -(c.radius1 - 0.5 * ck.overlap) * nxF / I1);
        // Eq. 3.5: xi turns with the contact frame at n x dn/dt and grows
        // with the contact-point slip.
        Vec3 ndot = Vec3::Zero();
        if (!c.isWall()) {
            const Vec3 vrel = s.v1 - s.v2;
            ndot = (vrel - ck.normalVelocity * n) / (s.x1 - s.x2).norm();
            put(dy, 4, -F / m2);
            put(dy, 5, -(c.radius2 - 0.5 * ck.overlap) * nxF / I2);
        }
        put(dy, 6, n.cross(ndot).cross(xi) + w);
    };

    const double h = c.params.tc / stepsPerTc;
    State y{};
    const BodyStates s0 = initialState(c);
    put(y, 0, s0.x1), put(y, 1, s0.v1), put(y, 2, s0.w1);
    put(y, 3, s0.x2), put(y, 4, s0.v2), put(y, 5, s0.w2);

    boost::numeric::odeint::runge_kutta4<State> stepper;
    double t = 0.0, peak = 0.0, prevOverlap = 0.0, prevForce = 0.0;
    const double tMax = 50.0 * c.params.tc;
    bool touched = false;
    double duration = 0.0;
    while (t < tMax) {
        stepper.do_step(rhs, y, t, h);
        t += h;
        const ContactKinematics ck = kinematics(c, bodyStates(y, t));
        if (ck.overlap > 0.0) {
            touched = true;
            peak = std::max(peak, ck.overlap);
            // Coulomb switch: keep the spring on the sliding surface.
            Vec3 xi = get(y, 6);
            xi -= xi.dot(ck.normal) * ck.normal;
            bool sliding;
            const Vec3 w = springVelocity(bodyStates(y, t), ck);
            const Vec3 Ft = law.tangentialForce(xi, w, law.normalForce(ck), sliding);
            if (sliding) xi = law.slidingSpring(Ft, w);
            // Where kn xi + cn dxi/dt changes sign the cap mu |Fn| is zero:
            // the spring slid to zero force there, at any mu (an instant the
            // steps above would miss for large mu).
            const double force = viscoelastic::normalForce(law.k, ck.overlap, -ck.normalVelocity, false);
            if (prevForce * force < 0.0) {
                const double since = h * force / (force - prevForce);
                xi = law.slidingSpring(Vec3::Zero(), w) + since * w;
            }
            prevForce = force;
            put(y, 6, xi);
        } else if (touched) {
            // linear interpolation of the overlap's zero crossing
            duration = t - h * ck.overlap / (ck.overlap - prevOverlap);
            break;
        }
        prevOverlap = ck.overlap;
    }
    if (!touched || duration == 0.0) throw std::runtime_error("reference collision did not end within 50 tc");
    if (after) *after = bodyStates(y, t);
    return outcomeOf(c, s0, bodyStates(y, t), duration, peak);
}

std::optional<ClosedForm> closedForm(const Case& c)
{
    const double tc = c.params.tc, en = c.params.en, v0 = c.normalSpeed;
    const double beta = -std::log(en) / tc, w = kPi / tc;
    auto overlap = [&](double t) { return v0 / w * std::exp(-beta * t) * std::sin(w * t); };
    auto rate = [&](double t) {
        return v0 * std::exp(-beta * t) * (std::cos(w * t) - beta / w * std::sin(w * t));
    };

    ClosedForm cf;
    cf.regime = "normal";
    cf.outcome.peakOverlap = overlap(std::atan2(w, beta) / w);
    // The force kn xi + cn dxi/dt first vanishes at w t = pi - atan2(2 beta w, w^2 - beta^2).
    const double tForceZero = (kPi - std::atan2(2.0 * beta * w, w * w - beta * beta)) / w;
    double frictionImpulse;  // integral of |Fn| dt per unit meff
    if (c.limitForce) {
        const double separation = -rate(tForceZero);
        cf.outcome.restitution = separation / v0;
        cf.outcome.duration = tForceZero + overlap(tForceZero) / separation;
        frictionImpulse = v0 + separation;
    } else {
        cf.outcome.restitution = en;
        cf.outcome.duration = tc;
        // repulsive part v0 - rate(tF), attractive part what exceeds (1 + en) v0
        const double repulsive = v0 - rate(tForceZero);
        frictionImpulse = 2.0 * repulsive - (1.0 + en) * v0;
    }

    const bool headOn = c.tangentialSpeed == 0.0 && c.spin1.isZero() && c.spin2.isZero();
    if (headOn) return cf;

    // Oblique: closed forms for a wall (fixed normal) with the rigid lever
    // arm R, and the pournin law only.
    if (!c.isWall() || c.tangential != Tangential::Pournin) return std::nullopt;
    const BodyStates s0 = initialState(c);
    const ContactKinematics k0 = kinematics(c, s0);
    const double u0 = k0.tangentialVelocity.norm();
    if (u0 == 0.0) return cf;
    const Vec3 t0 = k0.tangentialVelocity / u0;
    const double mu = c.params.mu, R = c.radius1;
    const double zSign = Vec3(1, 0, 0).cross(t0).z();
    // Both regimes need identical normal and tangential oscillators (et = en).
    if (c.params.et != en) return std::nullopt;
    if (u0 >= 3.5 * mu * frictionImpulse) {
        // Walton: sliding throughout, tangential impulse mu * int |Fn| dt.
        const double du = 3.5 * mu * frictionImpulse;
        cf.regime = "sliding";
        cf.outcome.tangentialRestitution = -(u0 - du) / u0;
        cf.outcome.spin1 = c.spin1.z() + zSign * 2.5 * mu * frictionImpulse / R;
    } else if (!c.limitForce && viscoelastic::kTangentialMassRatio * u0 / v0 <= mu) {
        // Identical oscillators: Ft/Fn stays (2/7) u0/v0, so it sticks throughout.
        cf.regime = "sticking";
        cf.outcome.tangentialRestitution = c.params.et;
        cf.outcome.spin1 = c.spin1.z() + zSign * 5.0 / 7.0 * (1.0 + c.params.et) * u0 / R;
    } else {
        return std::nullopt;
    }
    cf.hasTangential = true;
    const double ut = -cf.outcome.tangentialRestitution * u0;
    cf.outcome.reboundAngle = std::atan2(ut, cf.outcome.restitution * v0) * 180.0 / kPi;
    return cf;
}

Reference reference(const Case& c)
{
    if (c.exactRestitution) {
        // The request (en and tc, also with limitForce) times what the
        // continuous law does to them at this incidence: between two spheres
        // their tangential motion pulls the centres apart and the normal turns,
        // which moves en and the duration off their head-on values (en at 85 deg:
        // +9 % for en 0.56, +27 % for en 0.3); head-on the factor is 1, on walls 1
        // to the ODE's accuracy. (The ratio is the nominal law's; the corrected
        // coefficients' own law differs from it by their correction.) The rest is the
        // continuous law's: its tangential restitution differs from et by the
        // lever arm's shortening with the overlap (O(overlap / R),
        // speed-dependent), which no per-type-pair coefficient can absorb.
        Case nominal = c;
        nominal.exactRestitution = false;
        Reference r = reference(nominal);
        Case headOn = nominal;
        headOn.tangentialSpeed = 0.0;
        headOn.spin1 = headOn.spin2 = Vec3::Zero();
        const Outcome h = reference(headOn).outcome;
        r.outcome.restitution = c.params.en * r.outcome.restitution / h.restitution;
        r.outcome.duration = c.params.tc * r.outcome.duration / h.duration;
        r.source = "requested en and tc (exactRestitution on) times the law's oblique-to-head-on ratio; other "
                   "quantities: " + r.source;
        return r;
    }
    const std::optional<ClosedForm> cf = closedForm(c);
    if (cf && cf->regime == "normal") return {cf->outcome, "closed form"};
    // Oblique closed forms assume the rigid lever arm R; the law acts at
    // R - overlap/2 as LIGGGHTS does, so the ODE is the reference there.
    return {integrateContactOde(c), "ODE"};
}

double cappedLawExit(const FreeOscillator& n, const FreeOscillator& s, bool limitForce, double kappa, double vt0,
                     int scan)
{
    const double end = limitForce ? n.forceZeroFrom({0.0, 1.0}, std::atan2(n.omega, n.lambda) / n.omega) : kPi / n.omega;
    const double zero = limitForce ? end : n.forceZeroFrom({0.0, 1.0}, 0.0);  // where Fn turns
    const auto motion = [&](double t) { return n.after({0.0, 1.0}, t); };
    const auto fn = [&](double t) { return n.ending(motion(t), true); };
    const auto cap = [&](double t) { return kappa * std::fabs(fn(t)); };
    const auto capRate = [&](double t) { return kappa * (fn(t) >= 0.0 ? 1.0 : -1.0) * n.forceRate(motion(t)); };
    const auto impulse = [&](double a, double b) {  // |integral of Fn| over [a, b], split at its zero
        const auto part = [&](double p, double q) { return std::fabs(motion(p).u - motion(q).u); };
        return (a < zero && b > zero) ? part(a, zero) + part(zero, b) : part(a, b);
    };
    const auto bisect = [&](auto yes, double lo, double hi) {  // yes(lo) false, yes(hi) true
        for (int i = 0; i < 200 && hi - lo > 1e-17 * end; ++i) (yes(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
        return hi;
    };
    const auto firstWhere = [&](auto yes, double from) {  // the first time after `from` where yes(t), or end
        for (double a = from; a < end;) {
            double b = std::min(a + end / scan, end);
            if (a < zero && b > zero) b = zero;
            if (yes(b)) return bisect(yes, a, b);
            a = b;
        }
        return -1.0;
    };
    double t = 0.0, xi = 0.0, u = vt0, dir = 0.0;
    bool sliding = false;
    for (int events = 0; t < end; ++events) {
        if (events > 1000) return std::nan("");  // stick and slide alternating without end
        const double t0 = t, xi0 = xi, u0 = u;
        if (!sliding) {
            const auto free = [&](double tau) { return s.after({xi0, u0}, tau - t0); };
            const double onset = firstWhere([&](double tau) {
                const Motion q = free(tau);
                return std::fabs(s.k * q.x + s.c * q.u) > cap(tau);
            }, t0);
            t = onset < 0.0 ? end : onset;
            xi = free(t).x, u = free(t).u;
            if (onset >= 0.0) sliding = true, dir = s.k * xi + s.c * u > 0.0 ? 1.0 : -1.0;
        } else {
            const double d = dir;
            const auto rate = [&](double tau) { return u0 - kappa * d * impulse(t0, tau); };
            const double restick = firstWhere([&](double tau) {
                return s.k * rate(tau) * d - s.c * cap(tau) - capRate(tau) < 0.0;
            }, t0);
            t = restick < 0.0 ? end : restick;
            u = rate(t), xi = (cap(t) * d - s.c * u) / s.k;
            if (restick >= 0.0) sliding = false;
        }
    }
    return u;
}

std::optional<AgainstTheLaw> wallFrictionAgainstTheLaw(const ContactParameters& p, double vt, double tcOverDt,
                                                       bool limitForce, const std::vector<double>& phases)
{
    const double mt = 2.0 / 7.0;  // the spring's mass per unit meff (a sphere on a wall)
    const auto o = exactCollisionOscillators(p, limitForce);
    if (!o) return std::nullopt;
    const double dt = p.tc / tcOverDt;
    const StepLaw normal = stepLaw(o->normal.k, o->normal.c, dt, limitForce);
    const StepLaw tangential = stepLaw(o->tangential.k, o->tangential.c, dt, false);  // as the model builds it
    AgainstTheLaw r{cappedLawExit(o->normal, o->tangential, limitForce, p.mu / mt, vt), 0.0, 0.0};
    if (std::isnan(r.exit)) return AgainstTheLaw{r.exit, r.exit, 0.0};
    for (double phase : phases) {
        const FrictionalExit e = exactWallCollisionAtPhase(normal, tangential, phase, vt, p.mu, [&](double) { return mt; });
        const double err = std::fabs(e.tangential - r.exit) / vt;
        if (!(err <= r.worst)) r.worst = err, r.worstPhase = phase;
    }
    return r;
}

}  // namespace collide
