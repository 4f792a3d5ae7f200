// Event finding: the roots in time at which exactCollision's pieces change
// (collision.h) -- a contact's end, the normal force's zero, where the
// tangential spring meets or leaves its cap. Bracketed secant, Newton and
// Illinois iterations, generic in the function.
#pragma once

#include <cmath>

namespace viscoelastic {

namespace detail {

// tau in [lo, hi] with f(tau) = 0, f(lo) and f(hi) of opposite signs or zero:
// secant steps kept inside the bracket, every third step a bisection.
template <class F>
double bracketedRoot(F f, double lo, double hi)
{
    double flo = f(lo), fhi = f(hi);
    if (flo == 0.0) return lo;
    if (fhi == 0.0) return hi;
    for (int it = 0; it < 60 && hi - lo > 1e-14 * (std::fabs(lo) + std::fabs(hi)); ++it) {
        double t = lo - flo * (hi - lo) / (fhi - flo);
        if (!(t > lo && t < hi) || it % 3 == 2) t = 0.5 * (lo + hi);
        const double ft = f(t);
        if (ft == 0.0) return t;
        if ((ft > 0) == (flo > 0)) lo = t, flo = ft;
        else hi = t, fhi = ft;
    }
    return 0.5 * (lo + hi);
}

// The same for f with its slope: (f, f') = fs(tau), given f(lo) and a first
// guess (the secant's, from f at both ends, saves a step or two). Newton
// steps kept inside the bracket, bisection when one leaves it. A Newton step
// of 1e-10 of the bracket leaves an error of order its square (the roots are
// simple, f'' / f' ~ 1 / tc): round-off. Asking for the step itself to reach
// round-off cost two to three more evaluations per root (each an exp and a
// sincos) on the dense column.
template <class FS>
double bracketedNewton(FS fs, double lo, double hi, double flo, double t)
{
    if (flo == 0.0) return lo;
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    const double tolerance = 1e-10 * (hi - lo), collapsed = 1e-15 * (std::fabs(lo) + std::fabs(hi));
    for (int it = 0; it < 60; ++it) {
        const auto [f, df] = fs(t);
        if (f == 0.0) return t;
        if ((f > 0) == (flo > 0)) lo = t, flo = f;
        else hi = t;
        const double next = t - f / df;
        if (next > lo && next < hi) {
            if (std::fabs(next - t) < tolerance) return next;
            t = next;
        } else {
            t = 0.5 * (lo + hi);
        }
        if (hi - lo < collapsed) return t;
    }
    return t;
}

// tau in [lo, hi] with f(tau) = 0, f(lo) <= 0 < f(hi): regula falsi with
// the Illinois modification (superlinear), until a step moves tau by less
// than 1e-10 of the bracket (an error of order its square: round-off).
// f(lo) = 0 (on the cap, leaving it below) bisects until f is negative.
template <class F>
double illinoisRoot(F f, double lo, double hi, double flo, double fhi)
{
    const double tolerance = 1e-10 * (hi - lo);
    double t = lo;
    int side = 0;
    for (int it = 0; it < 80; ++it) {
        double next = (flo == 0.0 || flo == fhi) ? 0.5 * (lo + hi) : lo - flo * (hi - lo) / (fhi - flo);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        const double moved = std::fabs(next - t);
        t = next;
        const double ft = f(t);
        if (ft == 0.0) return t;
        if (ft > 0.0) {
            hi = t, fhi = ft;
            if (side == -1) flo *= 0.5;
            side = -1;
        } else {
            lo = t, flo = ft;
            if (side == 1) fhi *= 0.5;
            side = 1;
        }
        if ((it > 0 && moved < tolerance) || hi - lo < tolerance) return t;
    }
    return t;
}

}  // namespace detail

}  // namespace viscoelastic
