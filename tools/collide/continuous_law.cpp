#include "continuous_law.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace continuous {
namespace {

constexpr double pi = 3.14159265358979323846;

// y'' + 2 b y' + (wd^2 + b^2) y = 0, advanced by tau from (y0, v0).  Pournin's
// coefficients make every oscillator here have wd = pi/tc and b = -ln(e)/tc.
struct Oscillator {
  double b, wd;
  void advance(double tau, double y0, double v0, double& y, double& v) const {
    const double e = std::exp(-b * tau), c = std::cos(wd * tau), s = std::sin(wd * tau);
    y = e * (y0 * c + (v0 + b * y0) / wd * s);
    v = e * (v0 * c - ((wd * wd + b * b) * y0 + b * v0) / wd * s);
  }
};

// Normal motion per unit meff from x = 0, x' = v: x = v/wd e^{-bt} sin(wd t).
// Fn/meff = w0^2 x + 2 b x' = w0^2 v/wd e^{-bt} sin(wd t + phi) with
// phi = 2 atan(b/wd) ((wd + i b)^2 has argument phi and modulus w0^2), so Fn
// is positive on [0, tsep), negative on (tsep, tc], tsep = (pi - phi)/wd.
struct Normal {
  double v, b, wd, w0sq, phi, tsep;
  Normal(double tc, double en, double v_)
      : v(v_), b(-std::log(en) / tc), wd(pi / tc), w0sq(wd * wd + b * b),
        phi(2 * std::atan(b / wd)), tsep((pi - phi) / wd) {}
  double overlap(double t) const { return v / wd * std::exp(-b * t) * std::sin(wd * t); }
  double rate(double t) const {
    return v * std::exp(-b * t) * (std::cos(wd * t) - b / wd * std::sin(wd * t));
  }
  double force(double t) const { return w0sq * v / wd * std::exp(-b * t) * std::sin(wd * t + phi); }
  double forceRate(double t) const {
    const double a = wd * t + phi;
    return w0sq * v / wd * std::exp(-b * t) * (wd * std::cos(a) - b * std::sin(a));
  }
  // integral_0^t |Fn|/meff dt: Fn = -meff x'', and Fn changes sign once, at tsep.
  double absImpulse(double t) const {
    return t <= tsep ? v - rate(t) : v - 2 * rate(tsep) + rate(t);
  }
};

// First grid point t0 + k h (the last one is t1) where `holds` is true; the
// crossing is then bisected between it and the previous point (at t0 the
// predicate is taken as false: the caller has just made it so) to width eps.
// Returns the right end, where `holds` is true.
template <class Pred>
bool firstCrossing(double t0, double t1, double h, double eps, Pred holds, double& event) {
  double a = t0;
  for (long k = 1; a < t1; ++k) {
    const double b = std::min(t0 + k * h, t1);
    if (holds(b)) {
      double lo = a, hi = b;
      while (hi - lo > eps) {
        const double mid = 0.5 * (lo + hi);
        (holds(mid) ? hi : lo) = mid;
      }
      event = hi;
      return true;
    }
    a = b;
  }
  return false;
}

int sign(double x) { return x > 0 ? 1 : -1; }

}  // namespace

double forceZeroTime(double tc, double en) {
  return (pi - 2 * std::atan(-std::log(en) / pi)) * tc / pi;
}

// x'(tsep) = -v e^{-b tsep}: at tsep cos(wd t) = -cos(phi), sin(wd t) = sin(phi).
double limitedRestitution(double en) {
  return std::pow(en, 1 - 2 / pi * std::atan(-std::log(en) / pi));
}

Exit wallImpact(const Material& m, const WallImpact& in, double tolerance) {
  const double r = in.tangentialMassRatio;
  if (!(m.tc > 0) || !(m.en > 0 && m.en <= 1) || !(m.et > 0 && m.et <= 1) || !(m.mu >= 0) ||
      !(in.vn > 0) || !std::isfinite(in.vt) || !(r > 0) || !(tolerance >= 1e-14 && tolerance <= 1e-3))
    throw std::invalid_argument("continuous::wallImpact: bad material, impact or tolerance");

  const Normal n(m.tc, m.en, in.vn);
  const double lt = std::log(m.et);
  const double kt = r * (pi * pi + lt * lt) / (m.tc * m.tc), ct = -2 * r * lt / m.tc;
  const Oscillator spring{-lt / m.tc, pi / m.tc};  // sticking: r xi'' + ct xi' + kt xi = 0
  const bool capped = std::isfinite(m.mu);
  // The grid only has to resolve the shapes of the event functions (smooth on
  // the scale tc); tightening the tolerance refines it too, so a convergence
  // check also catches events the coarser grid stepped over.
  const double h = 0.1 * std::pow(tolerance, 0.25) * m.tc, eps = tolerance * m.tc;

  // The cap mu|Fn| on a branch of known sign of Fn (+1 before tsep, -1 after):
  // using the branch rather than the computed sign keeps roundoff at tsep out.
  auto cap = [&](double t, int branch) { return std::max(0.0, m.mu * branch * n.force(t)); };
  auto capRate = [&](double t, int branch) { return m.mu * branch * n.forceRate(t); };

  struct Segment { double end; int branch; };
  std::vector<Segment> segments{{in.limitForce ? n.tsep : std::min(n.tsep, m.tc), 1}};
  if (!in.limitForce && n.tsep < m.tc) segments.push_back({m.tc, -1});

  double t = 0, xi = 0, w = in.vt;
  int s = 0, slides = 0, transitions = 0;
  bool sliding = capped && std::abs(ct * w) > cap(0, 1);  // at t = 0, T = ct w
  if (sliding) s = sign(w), ++slides;

  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment seg = segments[i];
    while (t < seg.end) {
      if (++transitions > 10000)
        throw std::runtime_error("continuous::wallImpact: stick/slide chattering");
      const double t0 = t;
      double te;
      if (!sliding) {
        // Stick: closed-form oscillator from (xi0, w0); slide once |T| exceeds the cap.
        const double xi0 = xi, w0 = w;
        auto over = [&](double tt) {
          double x, v;
          spring.advance(tt - t0, xi0, w0, x, v);
          return std::abs(kt * x + ct * v) > cap(tt, seg.branch);
        };
        const bool hit = capped && firstCrossing(t0, seg.end, h, eps, over, te);
        if (!hit) te = seg.end;
        spring.advance(te - t0, xi0, w0, xi, w);
        if (hit) sliding = true, s = sign(kt * xi + ct * w), ++slides;
      } else {
        // Slide: w' = -mu|Fn| s/m_t integrates to the normal impulse.  Stick
        // again once the free spring, loaded at the cap, would unload faster
        // than the cap falls: d/dt (s T)|free = kt w s - ct C/m_t < C'.
        const double w0 = w, i0 = n.absImpulse(t0);
        auto vel = [&](double tt) { return w0 - s * m.mu * (n.absImpulse(tt) - i0) / r; };
        auto unloads = [&](double tt) {
          return kt * vel(tt) * s - ct * cap(tt, seg.branch) / r < capRate(tt, seg.branch);
        };
        const bool hit = firstCrossing(t0, seg.end, h, eps, unloads, te);
        if (!hit) te = seg.end;
        w = vel(te);
        xi = (cap(te, seg.branch) * s - ct * w) / kt;  // spring slaved to the cap
        if (hit) sliding = false;
      }
      t = te;
    }
    // At tsep (no limitForce) the cap is 0 and its slope jumps from -mu|Fn'|
    // to +mu|Fn'|: a slide may stop there, with the spring unloaded (T = 0), and
    // the unloaded spring may at once load the other way faster than the cap rises.
    if (i + 1 < segments.size() && sliding) {
      const double rise = capRate(t, segments[i + 1].branch);
      if (kt * w * s < rise) {
        sliding = false;
        xi = -ct * w / kt;
        if (-s * kt * w > rise) sliding = true, s = -s, ++slides;
      }
    }
  }

  Exit out;
  out.vn = -n.rate(t);
  out.vt = w;
  out.duration = t;
  // With limitForce the overlap closes in free flight after the force ends.
  out.overlapDuration = in.limitForce ? t + n.overlap(t) / out.vn : t;
  out.slides = slides;
  return out;
}

Exit pairImpact(const Material& m, const PairImpact& p, double tolerance) {
  if (!(p.m1 > 0 && p.m2 > 0 && p.r1 > 0 && p.r2 > 0))
    throw std::invalid_argument("continuous::pairImpact: bad masses or radii");
  const double meff = p.m1 * p.m2 / (p.m1 + p.m2);
  const double i1 = 0.4 * p.m1 * p.r1 * p.r1, i2 = 0.4 * p.m2 * p.r2 * p.r2;
  const double invMt = 1 / meff + p.r1 * p.r1 / i1 + p.r2 * p.r2 / i2;
  return wallImpact(m, {p.vn, p.vt, p.limitForce, 1 / (invMt * meff)}, tolerance);
}

SweepResult randomSweep(std::uint64_t seed, int cases, double tolerance) {
  std::mt19937_64 gen(seed);
  // Portable uniform [0, 1) (std distributions differ between libraries).
  auto u = [&] { return (gen() >> 11) * 0x1.0p-53; };
  SweepResult res;
  for (int k = 0; k < cases; ++k) {
    SweepCase c;
    c.material = {1e-4, 0.1 + 0.85 * u(), 0.1 + 0.85 * u(), 0.05 * std::pow(2e7, u())};
    c.impact = {1.0, 5 * u(), (gen() & 1) != 0};
    ++res.cases;
    try {
      c.exit = wallImpact(c.material, c.impact, tolerance);
      const Exit fine = wallImpact(c.material, c.impact, tolerance / 10);
      const double scale = std::max(std::abs(c.impact.vt), c.impact.vn);
      const double change = (std::abs(fine.vt - c.exit.vt) + std::abs(fine.vn - c.exit.vn)) / scale;
      if (change >= res.maxConvergenceChange) res.maxConvergenceChange = change, res.worstConvergence = c;
      if (c.impact.vt != 0) {
        const double gain = std::abs(c.exit.vt / c.impact.vt);
        if (gain >= res.maxTangentialGain) res.maxTangentialGain = gain, res.worstGain = c;
      }
      res.maxNormalRatio = std::max(res.maxNormalRatio, c.exit.vn / c.impact.vn);
      res.maxSlides = std::max(res.maxSlides, c.exit.slides);
    } catch (const std::runtime_error&) {
      ++res.failures;
      res.worstFailure = c;
    }
  }
  return res;
}

}  // namespace continuous
