#include "continuous_pair.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace continuous {
namespace {

constexpr double pi = 3.14159265358979323846;

struct V3 {
  double x = 0, y = 0, z = 0;
  V3() = default;
  V3(double a, double b, double c) : x(a), y(b), z(c) {}
  explicit V3(const Vector& a) : x(a[0]), y(a[1]), z(a[2]) {}
  Vector array() const { return {x, y, z}; }
  V3 operator+(const V3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  V3 operator-(const V3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  V3 operator-() const { return {-x, -y, -z}; }
  V3 operator*(double s) const { return {s * x, s * y, s * z}; }
  V3 operator/(double s) const { return {x / s, y / s, z / s}; }
  double dot(const V3& o) const { return x * o.x + y * o.y + z * o.z; }
  V3 cross(const V3& o) const { return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x}; }
  double norm() const { return std::sqrt(dot(*this)); }
};
V3 operator*(double s, const V3& a) { return a * s; }

// Relative state of the pair: r = xi - xj as its change dr since the touch
// (the overlap is a small difference of the distance and Ri + Rj; kept this
// way, neither the steps nor the overlap round at the scale of the radii),
// V = vi - vj, the spins, the spring.
struct State {
  V3 dr, v, wi, wj, xi;
  State operator+(const State& o) const { return {dr + o.dr, v + o.v, wi + o.wi, wj + o.wj, xi + o.xi}; }
  State operator*(double s) const { return {dr * s, v * s, wi * s, wj * s, xi * s}; }
};

struct Law {
  V3 r0;                        // xi - xj at the touch, |r0| = ri + rj
  double meff, ri, rj, ii, ij;  // masses enter as meff and the inertias
  double kn, cn, kt, ct, mu;
  bool capped;

  // The quantities of the law at a state.
  struct At {
    V3 n, vt, u, phi;
    double d, x, f, mt, ci, cj, cap, trial;  // trial = |kt xi + ct U|
  };
  At at(const State& y) const {
    At a;
    const V3 r = r0 + y.dr;
    a.d = r.norm();
    a.n = r / a.d;
    a.x = -(2 * r0.dot(y.dr) + y.dr.dot(y.dr)) / (ri + rj + a.d);  // ri + rj - d
    a.f = kn * a.x - cn * y.v.dot(a.n);
    a.vt = y.v - a.n * y.v.dot(a.n);
    const double s = a.d / (ri + rj);
    a.u = s * a.vt - (ri * y.wi + rj * y.wj).cross(a.n);
    a.ci = ri - 0.5 * a.x, a.cj = rj - 0.5 * a.x;
    a.mt = 1 / (s / meff + ri * a.ci / ii + rj * a.cj / ij);
    const V3 t = kt * y.xi + ct * a.u;
    a.trial = t.norm();
    a.cap = capped ? mu * meff / a.mt * std::abs(a.f) : INFINITY;
    a.phi = a.trial > a.cap ? t * (a.cap / a.trial) : t;
    return a;
  }

  State rate(const State& y) const {
    const At a = at(y);
    const V3 ft = -a.mt * a.phi;
    State dy;
    dy.dr = y.v;
    dy.v = a.f * a.n + ft / meff;
    dy.wi = -a.ci * a.n.cross(ft) / ii;
    dy.wj = -a.cj * a.n.cross(ft) / ij;
    const V3 ndot = a.vt / a.d;
    dy.xi = a.u - a.n * y.xi.dot(ndot);
    return dy;
  }

  State rk4(const State& y, double h) const {
    const State k1 = rate(y);
    const State k2 = rate(y + k1 * (0.5 * h));
    const State k3 = rate(y + k2 * (0.5 * h));
    const State k4 = rate(y + k3 * h);
    return y + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6);
  }

  // Luding's reset: the spring slaved to the force projected onto the cap.
  // Returns whether it slides.  `onset`: the state is where the spring
  // reaches the cap (to the root's tolerance): put it on the cap.
  // `zero`: F is 0 there (to its round-off, which a large mu would turn
  // into a spring force): the cap is 0.
  bool reset(State& y, const At& a, bool onset = false, bool zero = false) const {
    const double cap = zero ? 0.0 : a.cap;
    if (!(a.trial > cap) && !(onset && a.trial > 0)) return false;
    const V3 phi = (kt * y.xi + ct * a.u) * (std::min(cap, a.trial) / a.trial);
    y.xi = (phi - ct * a.u) / kt;
    return true;
  }
};

double maxChange(const PairExit& a, const PairExit& b, double ri, double rj) {
  const V3 dv = V3(a.v) - V3(b.v), dwi = V3(a.wi) - V3(b.wi), dwj = V3(a.wj) - V3(b.wj);
  return std::max({dv.norm(), ri * dwi.norm(), rj * dwj.norm()});
}

Vector extrapolated(const Vector& coarse, const Vector& fine) {
  return {2 * fine[0] - coarse[0], 2 * fine[1] - coarse[1], 2 * fine[2] - coarse[2]};
}

}  // namespace

PairExit pairCollisionSteps(const Material& m, const Sphere& si, const Sphere& sj, const PairTouch& touch,
                            long steps) {
  if (!(m.tc > 0) || !(m.en > 0 && m.en <= 1) || !(m.et > 0 && m.et <= 1) || !(m.mu >= 0))
    throw std::invalid_argument("continuous::pairCollision: bad material");
  if (!(si.m > 0 && sj.m > 0 && si.r > 0 && sj.r > 0) || !(steps >= 100))
    throw std::invalid_argument("continuous::pairCollision: bad spheres or steps");
  const V3 r0(touch.r);
  State y{V3(), V3(touch.v), V3(touch.wi), V3(touch.wj), V3()};
  const double reach = si.r + sj.r;
  if (!(std::abs(r0.norm() - reach) <= 1e-9 * reach) || !(y.v.dot(r0) < 0))
    throw std::invalid_argument("continuous::pairCollision: the pair is not at its touch, approaching");

  const double ln = std::log(m.en), lt = std::log(m.et);
  Law law;
  law.r0 = r0 * (reach / r0.norm());  // exactly at the touch
  law.meff = si.m * sj.m / (si.m + sj.m);
  law.ri = si.r, law.rj = sj.r;
  law.ii = 0.4 * si.m * si.r * si.r, law.ij = 0.4 * sj.m * sj.r * sj.r;
  law.kn = (pi * pi + ln * ln) / (m.tc * m.tc), law.cn = -2 * ln / m.tc;
  law.kt = (pi * pi + lt * lt) / (m.tc * m.tc), law.ct = -2 * lt / m.tc;
  law.mu = m.mu, law.capped = std::isfinite(m.mu);

  const double h = m.tc / static_cast<double>(steps);
  const long maxSteps = 100 * steps;
  PairExit out{};
  double t = 0;
  // The step length tau in (0, len] at which g(RK4 step of length tau) is 0,
  // g(y) and g(RK4 step of length len) of opposite signs: bracketed secant
  // (Illinois) on the step map, to 1e-15 h.  Returns the end of the bracket
  // past the root.
  auto root = [&](const State& from, double len, double g0, double g1, auto g) {
    double lo = 0, hi = len, flo = g0, fhi = g1;
    int side = 0;
    for (int it = 0; it < 200 && hi - lo > 1e-15 * h; ++it) {
      double tau = (lo * fhi - hi * flo) / (fhi - flo);
      if (!(tau > lo && tau < hi)) tau = 0.5 * (lo + hi);
      const double f = g(law.rk4(from, tau));
      if (f == 0) return tau;
      if ((f > 0) == (flo > 0)) {
        lo = tau, flo = f;
        if (side == 1) fhi *= 0.5;
        side = 1;
      } else {
        hi = tau, fhi = f;
        if (side == -1) flo *= 0.5;
        side = -1;
      }
    }
    return hi;
  };
  auto overlap = [&](const State& s) { return law.at(s).x; };
  auto force = [&](const State& s) { return law.at(s).f; };
  // how far the spring's force lies above the cap (sticking: <= 0)
  auto excess = [&](const State& s) {
    const Law::At a = law.at(s);
    return a.trial - a.cap;
  };
  bool sliding = law.reset(y, law.at(y));  // a slide from the touch: ct |U| over the cap
  Law::At ay = law.at(y);  // the law's quantities at y, and below at `next`
  out.slides = sliding ? 1 : 0;
  for (long k = 0;; ++k) {
    if (k >= maxSteps) throw std::runtime_error("continuous::pairCollision: the contact does not end");
    // The step ends at the first of three events inside it, located on the
    // step map: the end of the contact; a zero of F, where the cap is 0 and
    // the law slaves the spring to phi = 0 however short the slide around
    // it (mu large); the spring reaching the cap, where the force's rate
    // jumps (by kappa |F'| at a large mu: a corner the steps must not straddle).
    double len = h;
    State next = law.rk4(y, len);
    Law::At an = law.at(next);
    bool ends = false, onset = false, zero = false;
    if (an.x <= 0) {
      len = root(y, len, ay.x, an.x, overlap);
      next = law.rk4(y, len), an = law.at(next);
      ends = true;
    }
    const double f0 = ay.f, f1 = an.f;
    if (law.capped && f0 != 0 && (f0 > 0) != (f1 > 0)) {  // (mu infinite: no cap, not even at F = 0)
      len = root(y, len, f0, f1, force);
      next = law.rk4(y, len), an = law.at(next);
      ends = false, zero = true;
    }
    const double e0 = ay.trial - ay.cap, e1 = an.trial - an.cap;
    if (!sliding && e0 < 0 && e1 > 0) {
      const double at = root(y, len, e0, e1, excess);
      if (at > 1e-9 * h) {  // (else: at the step's start, the corner does no harm)
        len = at;
        next = law.rk4(y, len), an = law.at(next);
        ends = zero = false;
      }
      onset = true;
    }
    y = next, ay = an;
    t += len;
    // (en = 1: F = kn x, its zero is the end)
    if (ends || ay.x <= 0) break;
    const bool slides = law.reset(y, ay, onset, zero);
    if (slides) ay = law.at(y);  // (the reset moved the spring)
    if (slides && !sliding) ++out.slides;
    sliding = slides;
  }
  out.r = (law.r0 + y.dr).array(), out.v = y.v.array(), out.wi = y.wi.array(), out.wj = y.wj.array();
  out.duration = t;
  out.change = 0;
  return out;
}

PairExit pairCollision(const Material& m, const Sphere& si, const Sphere& sj, const PairTouch& touch, long steps) {
  const PairExit a = pairCollisionSteps(m, si, sj, touch, steps);
  PairExit b = pairCollisionSteps(m, si, sj, touch, 2 * steps);
  b.change = maxChange(a, b, si.r, sj.r);
  b.r = extrapolated(a.r, b.r), b.v = extrapolated(a.v, b.v);
  b.wi = extrapolated(a.wi, b.wi), b.wj = extrapolated(a.wj, b.wj);
  b.duration = 2 * b.duration - a.duration;
  return b;
}

}  // namespace continuous
