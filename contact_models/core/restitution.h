// Restitution coefficient of the continuous law (no time discretisation).
#pragma once

#include <cmath>

#include "pournin.h"

namespace viscoelastic {

// Without limitForce it is en by construction (Eq. 3.22-3.23); with it the
// contact ends when the force, not the overlap, reaches zero (Schwager &
// Poeschel 2007, three damping regimes).
inline double continuousRestitution(double tc, double en, bool limitForce)
{
    if (!limitForce || en >= 1.0) return en;
    const double beta = -std::log(en) / tc;
    const double w0 = std::sqrt(kPi * kPi + std::log(en) * std::log(en)) / tc;
    const double w = kPi / tc;  // damped frequency sqrt(w0^2 - beta^2)
    // With the Pournin constants beta < w0 always, so the overdamped branch
    // beta > w0 of Schwager & Poeschel is never reached.
    if (beta < w0 / std::sqrt(2.0))
        return std::exp(-(beta / w) * (kPi - std::atan(2.0 * beta * w / (w * w - beta * beta))));
    return std::exp(-(beta / w) * std::atan(2.0 * beta * w / (beta * beta - w * w)));
}

}  // namespace viscoelastic
