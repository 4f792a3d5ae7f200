// The independent continuous-law reference (tools/collide/continuous_law.*)
// against analytic results, against a direct integration of the ODEs that
// shares no code with it, and over a random sweep of invariants.
#include "continuous_law.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace {

using continuous::Exit;
using continuous::Material;
using continuous::WallImpact;

constexpr double pi = 3.14159265358979323846;
constexpr double tc = 1e-4;
constexpr double r = 2.0 / 7.0;  // m_t / meff, sphere on a wall

// Pournin's coefficients per unit mass: k/m and c/m.
double kOverM(double e) { return (pi * pi + std::log(e) * std::log(e)) / (tc * tc); }
double cOverM(double e) { return -2 * std::log(e) / tc; }

// Classic RK4 of y'' = -(k y + c y')/m from (y, v) over time T in n steps.
void rk4(double k, double c, double T, int n, double& y, double& v) {
  const double dt = T / n;
  auto acc = [&](double yy, double vv) { return -(k * yy + c * vv); };
  for (int i = 0; i < n; ++i) {
    const double a1 = acc(y, v), y2 = y + 0.5 * dt * v, v2 = v + 0.5 * dt * a1;
    const double a2 = acc(y2, v2), y3 = y + 0.5 * dt * v2, v3 = v + 0.5 * dt * a2;
    const double a3 = acc(y3, v3), y4 = y + dt * v3, v4 = v + dt * a3;
    const double a4 = acc(y4, v4);
    y += dt / 6 * (v + 2 * v2 + 2 * v3 + v4);
    v += dt / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
  }
}

// The claims the reference rests on, checked by integrating the normal ODE:
// the overlap closes at exactly tc with rate -en v, and the force kn x + cn x'
// reaches 0 at forceZeroTime with rate -limitedRestitution v.
TEST(ContinuousLaw, NormalClosedFormsMatchTheOde) {
  for (double en : {0.05, 0.3, 0.7, 0.95}) {
    double x = 0, v = 1;
    rk4(kOverM(en), cOverM(en), tc, 200000, x, v);
    EXPECT_NEAR(x / tc, 0.0, 1e-12) << en;
    EXPECT_NEAR(v, -en, 1e-11) << en;

    const double ts = continuous::forceZeroTime(tc, en);
    x = 0, v = 1;
    rk4(kOverM(en), cOverM(en), ts, 200000, x, v);
    EXPECT_NEAR((kOverM(en) * x + cOverM(en) * v) * tc, 0.0, 1e-10) << en;
    EXPECT_NEAR(v, -continuous::limitedRestitution(en), 1e-11) << en;
  }
}

// (a) head-on: restitution en and duration tc, or with limitForce the
// closed-form effective restitution and force duration.
TEST(ContinuousLaw, HeadOnRestitutionAndDuration) {
  for (double en : {0.1, 0.3, 0.5, 0.8, 0.95, 1.0}) {
    const Material mat{tc, en, 0.5, 0.5};
    const Exit off = continuous::wallImpact(mat, {2.0, 0.0, false});
    EXPECT_NEAR(off.vn, 2 * en, 2e-9 * en) << en;
    EXPECT_NEAR(off.duration, tc, 1e-9 * tc) << en;
    EXPECT_EQ(off.vt, 0.0);
    EXPECT_EQ(off.slides, 0);

    const Exit on = continuous::wallImpact(mat, {2.0, 0.0, true});
    const double eEff = continuous::limitedRestitution(en);
    EXPECT_NEAR(on.vn, 2 * eEff, 2e-9) << en;
    EXPECT_NEAR(on.duration, continuous::forceZeroTime(tc, en), 1e-9 * tc) << en;
    EXPECT_GE(on.overlapDuration, on.duration);
    if (en < 1) {
      EXPECT_GT(eEff, en);  // the attractive tail is cut off
      EXPECT_LT(on.duration, tc);
    }
  }
  // 0.5^(1 - (2/pi) atan(ln 2/pi)) = 0.5^0.861753 = 0.550283
  EXPECT_NEAR(continuous::limitedRestitution(0.5), 0.550283, 1e-6);
}

// Sticking spring w(t) from xi = xi0, w = w0 by direct integration.
double stickVelocity(double et, double xi0, double w0, double T) {
  double y = xi0, v = w0;
  rk4(kOverM(et), cOverM(et), T, 200000, y, v);
  return v;
}

// (b) no cap (mu = inf): the tangential oscillator has the same damped period
// as the normal one, so after tc from xi = 0 it returns w(tc) = -et w(0).
// With a finite cap, however large, the cap mu|Fn| passes through 0 at tsep
// (without limitForce Fn turns attractive there): the spring unloads to T = 0
// at tsep and restarts from there, so w(tc) != -et w(0).
TEST(ContinuousLaw, StickingTangentialRestitution) {
  for (double en : {0.2, 0.6, 0.9}) {
    for (double et : {0.1, 0.46, 0.9}) {
      const double vt = 0.7;
      const Exit free = continuous::wallImpact({tc, en, et, INFINITY}, {1.0, vt, false});
      EXPECT_NEAR(free.vt, -et * vt, 1e-9 * vt) << en << " " << et;
      EXPECT_EQ(free.slides, 0);

      const double ts = continuous::forceZeroTime(tc, en);
      const double ws = stickVelocity(et, 0, vt, ts);
      const double kt = r * kOverM(et), ct = r * cOverM(et);
      const double expectedOff = stickVelocity(et, -ct * ws / kt, ws, tc - ts);
      const Exit off = continuous::wallImpact({tc, en, et, 1e9}, {1.0, vt, false});
      EXPECT_NEAR(off.vt, expectedOff, 1e-7 * vt) << en << " " << et;
      // the short slide into tsep (none if en = et: then T = 0 at tsep too, see below)
      if (en != et) EXPECT_EQ(off.slides, 1);

      // limitForce: the contact ends at tsep, still sticking (up to ~1e-9 tsep).
      const Exit on = continuous::wallImpact({tc, en, et, 1e9}, {1.0, vt, true});
      EXPECT_NEAR(on.vt, ws, 1e-7 * vt) << en << " " << et;
    }
  }
}

// en = et: sticking, the tangential motion is the normal one scaled, w = vt x'/vn,
// so T/Fn = (m_t/meff) vt/vn at all times: the contact sticks throughout iff
// mu >= (m_t/meff) vt/vn, and then leaves with -et vt (or -vt times the
// limited restitution with limitForce).
TEST(ContinuousLaw, EqualRestitutionsKeepForcesProportional) {
  for (double e : {0.3, 0.46, 0.8}) {
    for (double ratio : {0.2, 1.0}) {
      const double vt = ratio, muStick = r * ratio * 1.01;
      const Exit off = continuous::wallImpact({tc, e, e, muStick}, {1.0, vt, false});
      EXPECT_NEAR(off.vt, -e * vt, 1e-9 * vt) << e << " " << ratio;
      const Exit on = continuous::wallImpact({tc, e, e, muStick}, {1.0, vt, true});
      EXPECT_NEAR(on.vt, -continuous::limitedRestitution(e) * vt, 1e-9 * vt) << e << " " << ratio;
      const Exit slides = continuous::wallImpact({tc, e, e, r * ratio * 0.99}, {1.0, vt, false});
      EXPECT_GE(slides.slides, 1);
      EXPECT_GT(slides.vt, -e * vt);
    }
  }
}

// (c) sliding throughout (mu small, vt/vn large): the friction impulse is
// mu integral |Fn| dt, which is meff (vn + vsep) with limitForce and
// meff (vn (1 - en) + 2 vsep) without (vsep: rate where Fn = 0).
TEST(ContinuousLaw, SlidingThroughout) {
  const double mu = 0.01, vn = 1.0, vt = 5.0;
  for (double en : {0.1, 0.46, 0.9}) {
    for (double et : {0.1, 0.46, 0.9}) {
      const Material mat{tc, en, et, mu};
      ASSERT_GT(r * std::abs(std::log(et)) * vt, mu * std::abs(std::log(en)) * vn);  // slides at t = 0
      const double vsep = continuous::limitedRestitution(en) * vn;

      const Exit on = continuous::wallImpact(mat, {vn, vt, true});
      EXPECT_EQ(on.slides, 1);
      EXPECT_NEAR(on.vt, vt - mu / r * (vn + vsep), 1e-9 * vt) << en << " " << et;

      const Exit off = continuous::wallImpact(mat, {vn, vt, false});
      EXPECT_EQ(off.slides, 1);
      EXPECT_NEAR(off.vt, vt - mu / r * (vn * (1 - en) + 2 * vsep), 1e-9 * vt) << en << " " << et;
    }
  }
}

// The discrete law as a time-stepping code applies it (spring += w dt, cap
// with Luding's reset, then w += F/m_t dt), with the normal force in closed
// form, at dt = tc/2e5: converges at O(dt) to the continuous law.  It shares
// no code with the event-based reference, so it checks its event logic.
Exit bruteForce(const Material& m, const WallImpact& in, int steps) {
  const double en = m.en, b = -std::log(en) / tc, wd = pi / tc;
  const double rate0 = in.vn;
  auto x = [&](double t) { return rate0 / wd * std::exp(-b * t) * std::sin(wd * t); };
  auto xd = [&](double t) {
    return rate0 * std::exp(-b * t) * (std::cos(wd * t) - b / wd * std::sin(wd * t));
  };
  const double kt = r * kOverM(m.et), ct = r * cOverM(m.et);
  const double tend = in.limitForce ? continuous::forceZeroTime(tc, en) : tc;
  const double dt = tend / steps;
  double xi = 0, w = in.vt;
  for (int i = 0; i < steps; ++i) {
    const double t = (i + 1) * dt;
    xi += w * dt;
    double T = kt * xi + ct * w;
    const double cap = m.mu * std::abs(kOverM(en) * x(t) + cOverM(en) * xd(t));
    if (std::abs(T) > cap) {
      T = T > 0 ? cap : -cap;
      xi = (T - ct * w) / kt;
    }
    w -= T / r * dt;
  }
  return {-xd(tend), w, tend, tend, 0};
}

TEST(ContinuousLaw, AgreesWithBruteForceTimeStepping) {
  std::mt19937_64 gen(7);
  auto u = [&] { return (gen() >> 11) * 0x1.0p-53; };
  double worst = 0;
  for (int k = 0; k < 60; ++k) {
    const Material mat{tc, 0.1 + 0.85 * u(), 0.1 + 0.85 * u(), 0.05 * std::pow(200.0, u())};
    const WallImpact in{1.0, 5 * u(), k % 2 == 0};
    const Exit ref = continuous::wallImpact(mat, in);
    const Exit bf = bruteForce(mat, in, 200000);
    const double err = std::abs(ref.vt - bf.vt) / std::max(in.vt, in.vn);
    worst = std::max(worst, err);
    EXPECT_LT(err, 2e-4) << "en " << mat.en << " et " << mat.et << " mu " << mat.mu << " vt "
                         << in.vt << " limit " << in.limitForce << ": " << ref.vt << " vs " << bf.vt;
  }
  RecordProperty("worst", std::to_string(worst));
  std::printf("brute force (dt = tc/2e5) vs reference: worst |dvt|/max(vt, vn) = %.3g\n", worst);
}

// (d) invariants and convergence over a seeded random sweep.
TEST(ContinuousLaw, RandomSweepInvariants) {
  const auto res = continuous::randomSweep(2024, 4000);
  std::printf("sweep: %d cases, %d failures, max |vt_out/vt_in| = %.12f, max vn_out/vn_in = %.6f, "
              "max convergence change = %.3g, max slides = %d\n",
              res.cases, res.failures, res.maxTangentialGain, res.maxNormalRatio,
              res.maxConvergenceChange, res.maxSlides);
  const auto& g = res.worstGain;
  std::printf("  largest gain: en %.6f et %.6f mu %.6g vt %.6f limitForce %d -> vt_out %.12f vn_out %.6f\n",
              g.material.en, g.material.et, g.material.mu, g.impact.vt, g.impact.limitForce,
              g.exit.vt, g.exit.vn);
  const auto& c = res.worstConvergence;
  std::printf("  worst convergence: en %.6f et %.6f mu %.6g vt %.6f limitForce %d\n", c.material.en,
              c.material.et, c.material.mu, c.impact.vt, c.impact.limitForce);
  EXPECT_EQ(res.failures, 0);
  EXPECT_LE(res.maxTangentialGain, 1 + 1e-9);
  EXPECT_LE(res.maxNormalRatio, 1.0);
  EXPECT_LT(res.maxConvergenceChange, 1e-7);
}

TEST(ContinuousLaw, PairOfSpheresIsTheWallLawWithTwoSevenths) {
  const Material mat{tc, 0.46, 0.46, 0.5};
  for (bool limit : {false, true}) {
    const Exit pair = continuous::pairImpact(mat, {2e-3, 1e-3, 5e-3, 3e-3, 1.0, 0.8, limit});
    const Exit wall = continuous::wallImpact(mat, {1.0, 0.8, limit, 2.0 / 7.0});
    EXPECT_NEAR(pair.vt, wall.vt, 1e-12);
    EXPECT_NEAR(pair.vn, wall.vn, 1e-12);
  }
}

TEST(ContinuousLaw, RejectsBadInput) {
  EXPECT_THROW(continuous::wallImpact({tc, 0.0, 0.5, 0.5}, {1, 0, false}), std::invalid_argument);
  EXPECT_THROW(continuous::wallImpact({tc, 0.5, 1.5, 0.5}, {1, 0, false}), std::invalid_argument);
  EXPECT_THROW(continuous::wallImpact({tc, 0.5, 0.5, -1}, {1, 0, false}), std::invalid_argument);
  EXPECT_THROW(continuous::wallImpact({tc, 0.5, 0.5, 0.5}, {-1, 0, false}), std::invalid_argument);
  EXPECT_THROW(continuous::wallImpact({tc, 0.5, 0.5, 0.5}, {1, 0, false}, 0.1), std::invalid_argument);
}

}  // namespace
