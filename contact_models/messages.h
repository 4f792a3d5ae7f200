// Words for the physics core's results, shared by the LIGGGHTS glue and the
// tools: the core returns numbers and reasons, this header turns them into
// the sentences users read. Pure C++, no LIGGGHTS types.
#pragma once

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <string>

#include "core/exact.h"

namespace viscoelastic {

// printf into a std::string.
inline std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
inline std::string format(const char* fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    va_list again;
    va_copy(again, args);
    const int n = std::vsnprintf(nullptr, 0, fmt, args);
    va_end(args);
    std::string s(n > 0 ? n : 0, '\0');
    if (n > 0) std::vsnprintf(&s[0], s.size() + 1, fmt, again);
    va_end(again);
    return s;
}

// Under wallMassAsParticle (halvedMassCoefficients) what the solve was for:
// YADE's halved law of the request, which the texts below then speak of.
inline std::string halvedLawText(const ExactSolution& s)
{
    if (!s.halvedFrom) return "";
    const ContactParameters& a = *s.halvedFrom;
    return format("wallMassAsParticle on: the wall contact's law is YADE's, Pournin's coefficients of tc %g s, en %g, "
                  "et %g (tc/dt %.2f) at meff/2, which restitutes en %.6g, et %.6g over %.6g s; ",
                  a.tc, a.en, a.et, a.tc / s.dt, s.requested.en, s.tangentialTarget, s.requested.tc);
}

// A text about the solve (empty: nothing to say), preceded by what it was
// for where that is YADE's halved law.
inline std::string aboutTheLaw(const ExactSolution& s, const std::string& text)
{
    return text.empty() ? text : halvedLawText(s) + text;
}

namespace detail {

// The texts below of the solve's own request (`requested`).
inline std::string failureText(const ExactSolution& s)
{
    const ContactParameters& p = s.requested;
    switch (s.failure) {
    case ExactFailure::none:
        return "";
    case ExactFailure::normalUnreachable:
        return format("no normal coefficients reach en %g in %g s at dt %g s (tc/dt %.2f)%s; the closest found "
                      "restitutes %+.3g%% off and lasts %+.3g%% off: use a smaller timestep or exactRestitution off",
                      p.en, p.tc, s.dt, p.tc / s.dt,
                      s.limitForce ? " with limitForce on (forbidding attraction bounds the restitution from below)"
                                   : "",
                      100.0 * std::expm1(s.closestLnRestitutionError), 100.0 * s.closestDurationError);
    case ExactFailure::tangentialUnreachable:
        return format("et %g is below what any tangential dashpot reaches at dt %g s (tc/dt %.2f)", p.et, s.dt,
                      p.tc / s.dt);
    }
    return "";
}

inline std::string warningText(const ExactSolution& s)
{
    const ContactParameters& p = s.requested;
    std::string w;
    if (s.undampedRestitution)
        w = format("en %g at dt %g s (tc/dt %.2f) would need a negative normal dashpot (the undamped discrete "
                   "contact restitutes %.6f): the dashpot is off",
                   p.en, s.dt, p.tc / s.dt, *s.undampedRestitution);
    if (s.undampedTangentialRestitution)
        w += format("%set %g at dt %g s (tc/dt %.2f) would need a negative tangential dashpot (the undamped "
                    "sticking contact restitutes %.6f): the tangential dashpot is off",
                    w.empty() ? "" : "; ", p.et, s.dt, p.tc / s.dt, *s.undampedTangentialRestitution);
    return w;
}

inline std::string contradictionText(const ExactSolution& s, double tolerance)
{
    const ContactParameters& p = s.requested;
    const auto far = [&](double achieved, double wanted) {
        return !(achieved > 0.0) || std::fabs(achieved / wanted - 1.0) > tolerance;
    };
    const char* why = s.limitForce ? ": with limitForce on the normal force, and with it the friction limit, is cut "
                                     "before the contact ends, so even undamped the spring restitutes no more"
                                   : "";
    if (s.undampedRestitution && far(*s.undampedRestitution, p.en))
        return format("en %g cannot be reached at dt %g s (tc/dt %.2f): with no normal dashpot at all the contact "
                      "restitutes %.4f%s; use a smaller timestep or another en",
                      p.en, s.dt, p.tc / s.dt, *s.undampedRestitution, why);
    if (s.undampedTangentialRestitution && far(*s.undampedTangentialRestitution, s.tangentialTarget))
        return format("et %g cannot be reached at dt %g s (tc/dt %.2f): with no tangential dashpot at all a sticking "
                      "contact restitutes %.4f%s%s",
                      p.et, s.dt, p.tc / s.dt, *s.undampedTangentialRestitution, why,
                      s.limitForce ? "; set limitForce off, raise en, or use exactCollision on (its tangential spring "
                                     "lasts as long as the force)"
                                   : "");
    return "";
}

}  // namespace detail

// Why exactUnitCoefficients found no coefficients; empty when it did.
inline std::string failureText(const ExactSolution& s)
{
    if (s.halvedFrom && s.failure == ExactFailure::tangentialUnreachable && !(s.tangentialTarget > 0.0))
        return halvedLawText(s) + "a sticking contact point does not even reverse under it, so no tangential "
                                  "coefficients restitute it: set exactRestitution off, or raise en";
    return aboutTheLaw(s, detail::failureText(s));
}

// A dashpot switched off because the request needed a negative one; empty
// when none was.
inline std::string warningText(const ExactSolution& s) { return aboutTheLaw(s, detail::warningText(s)); }

// A dashpot switched off whose contact then restitutes farther than
// `tolerance` (relative) from the request, or not even reverses: the
// settings contradict the request. Empty when they do not.
inline std::string contradictionText(const ExactSolution& s, double tolerance)
{
    return aboutTheLaw(s, detail::contradictionText(s, tolerance));
}

}  // namespace viscoelastic
