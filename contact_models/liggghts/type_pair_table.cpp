#include "type_pair_table.h"

#include "core/discrete.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "comm.h"
#include "error.h"
#include "fix_property_global.h"
#include "lammps.h"
#include "modify.h"
#include "update.h"

namespace viscoelastic {

namespace {

struct PropertySpec {
    const char* name;
    const char* range;
    bool (*valid)(double);
};

const PropertySpec kDuration{"contactDuration", "> 0 s", [](double v) { return v > 0.0; }};
const PropertySpec kRestitution{"coefficientRestitution", "in (0, 1]",
                                [](double v) { return v > 0.0 && v <= 1.0; }};
const PropertySpec kRestitutionTangential{"coefficientRestitutionTangential", "in (0, 1]",
                                          [](double v) { return v > 0.0 && v <= 1.0; }};
const PropertySpec kFriction{"coefficientFriction", ">= 0", [](double v) { return v >= 0.0; }};

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...)
{
    char buf[1024];
    va_list args;
    va_start(args, fmt);
    vsnprintf(buf, sizeof buf, fmt, args);
    va_end(args);
    return buf;
}

// Fills values[i*stride+j] for 1 <= i,j <= maxType from a peratomtypepair
// property, after checking every entry the property defines (also for types
// not in use yet). A missing property, a too small or an asymmetric matrix
// are reported by LIGGGHTS itself, naming the property.
void readProperty(LAMMPS_NS::LAMMPS* lmp, const PropertySpec& spec, int maxType, const char* caller,
                  std::vector<double>& values)
{
    auto* fix = static_cast<LAMMPS_NS::FixPropertyGlobal*>(lmp->modify->find_fix_property(
        spec.name, "property/global", "peratomtypepair", maxType, maxType, caller));
    const int defined = fix->size_array_rows;
    for (int i = 1; i <= defined; ++i)
        for (int j = 1; j <= defined; ++j) {
            const double v = fix->compute_array(i - 1, j - 1);
            if (!std::isfinite(v) || !spec.valid(v))
                lmp->error->all(FLERR, format("%s: %s of type pair (%d,%d) is %g; it must be %s",
                                              caller, spec.name, i, j, v, spec.range)
                                           .c_str());
        }
    const int stride = maxType + 1;
    values.assign(stride * stride, 0.0);
    for (int i = 1; i <= maxType; ++i)
        for (int j = 1; j <= maxType; ++j) values[i * stride + j] = fix->compute_array(i - 1, j - 1);
}

// Above this predicted relative restitution error the run is warned.
constexpr double kAccuracyWarning = 0.01;
// A bead with many simultaneous contacts oscillates faster than a binary
// contact: a settled column fails from 0.72-0.77 of the binary limit
// (benchmarks/README.md, stability map). Runs stop above half of it.
constexpr double kMultiContactFactor = 0.5;

// `exactRestitution on` solves for the coefficients once per type pair and
// timestep; the pair style and every wall ask for the same ones at every run.
const ExactSolution& exactSolution(const ContactParameters& p, double dt, bool limitForce)
{
    static std::map<std::tuple<double, double, double, double, bool>, ExactSolution> cache;
    const auto key = std::make_tuple(p.tc, p.en, p.et, dt, limitForce);
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, exactUnitCoefficients(p, dt, limitForce)).first;
    return it->second;
}

}  // namespace

void TypePairTable::load(LAMMPS_NS::LAMMPS* lmp, int maxType, bool limitForce, bool exact, const char* caller)
{
    std::vector<double> tc, en, et, mu;
    readProperty(lmp, kDuration, maxType, caller, tc);
    readProperty(lmp, kRestitution, maxType, caller, en);
    readProperty(lmp, kRestitutionTangential, maxType, caller, et);
    readProperty(lmp, kFriction, maxType, caller, mu);

    stride_ = maxType + 1;
    params_.assign(stride_ * stride_, ContactParameters{});
    unit_.assign(stride_ * stride_, UnitCoefficients{});
    const double dt = lmp->update->dt;
    std::string report;
    std::vector<std::string> warnings;
    for (int i = 1; i <= maxType; ++i)
        for (int j = 1; j <= maxType; ++j) {
            const int k = i * stride_ + j;
            params_[k] = {tc[k], en[k], et[k], mu[k]};
            if (j < i) {  // symmetric: done as (j,i)
                unit_[k] = unit_[j * stride_ + i];
                continue;
            }
            const double dtCrit = criticalTimestep(params_[k]);
            if (dt > kMultiContactFactor * dtCrit)
                lmp->error->all(
                    FLERR, format("%s: timestep %g s exceeds the stable timestep %g s of type pair (%d,%d) "
                                  "(tc %g s, en %g, et %g): half the binary stability limit %g s, as beads with "
                                  "many simultaneous contacts become unstable above it; use timestep < %g",
                                  caller, dt, kMultiContactFactor * dtCrit, i, j, tc[k], en[k], et[k], dtCrit,
                                  kMultiContactFactor * dtCrit)
                               .c_str());
            const DiscreteCollision nominal = phaseAveragedCollision(params_[k], dt, limitForce);
            if (!exact) {
                unit_[k] = pourninUnitCoefficients(params_[k]);
                const double eCont = continuousRestitution(tc[k], en[k], limitForce);
                const double err = nominal.restitution / eCont - 1.0;
                report += format("  (%d,%d): tc/dt %.1f, timestep limit %.4g s, kn/meff %.6g 1/s^2, "
                                 "cn/meff %.6g 1/s, kt/meff %.6g 1/s^2, ct/meff %.6g 1/s, "
                                 "restitution %.4f continuous, %.4f at this dt (%+.2f%%), duration %.4g s\n",
                                 i, j, tc[k] / dt, kMultiContactFactor * dtCrit, unit_[k].kn, unit_[k].cn, unit_[k].kt, unit_[k].ct,
                                 eCont, nominal.restitution, 100.0 * err, nominal.duration);
                if (std::fabs(err) > kAccuracyWarning)
                    warnings.push_back(format("viscoelastic: at timestep %g s (tc/dt = %.1f) type pair (%d,%d) "
                                              "restitutes %.4f instead of %.4f (%+.2f%%); a smaller timestep or "
                                              "exactRestitution on reduces this",
                                              dt, tc[k] / dt, i, j, nominal.restitution, eCont, 100.0 * err));
                continue;
            }
            const ExactSolution& x = exactSolution(params_[k], dt, limitForce);
            if (!x.ok())
                lmp->error->all(
                    FLERR, format("%s: exactRestitution: type pair (%d,%d): %s", caller, i, j, x.failure.c_str())
                               .c_str());
            unit_[k] = x.unit;
            // the corrected oscillators must be stable too
            const double dtCritExact =
                std::min(criticalTimestepOf(x.unit.kn, x.unit.cn),
                         criticalTimestepOf(x.unit.kt / kTangentialMassRatio, x.unit.ct / kTangentialMassRatio));
            if (dt > kMultiContactFactor * dtCritExact)
                lmp->error->all(FLERR, format("%s: exactRestitution: timestep %g s exceeds the stable timestep %g s "
                                              "(half the binary limit) of the corrected coefficients of type pair (%d,%d)",
                                              caller, dt, kMultiContactFactor * dtCritExact, i, j)
                                           .c_str());
            report += format("  (%d,%d): tc/dt %.1f, timestep limit %.4g s, kn/meff %.6g 1/s^2, cn/meff %.6g 1/s, "
                             "kt/meff %.6g 1/s^2, ct/meff %.6g 1/s (Pournin's for tc %.6g s, en %.6f); "
                             "restitution %.6f, tangential %.6f, duration %.6g s at this dt "
                             "(nominal coefficients: %.4f, %.4f, %.4g s)\n",
                             i, j, tc[k] / dt, kMultiContactFactor * dtCritExact, x.unit.kn, x.unit.cn, x.unit.kt, x.unit.ct,
                             x.tcNormal, x.enNormal, x.achieved.restitution, x.achieved.tangentialRestitution,
                             x.achieved.duration, nominal.restitution, nominal.tangentialRestitution,
                             nominal.duration);
            if (!x.warning.empty())
                warnings.push_back(format("viscoelastic: type pair (%d,%d): %s", i, j, x.warning.c_str()));
        }

    // Pair style and every wall load the same table, at every run: say each
    // thing once.
    static std::set<std::string> said;
    const std::string text =
        format("viscoelastic: %s per type pair (limitForce %s), outcomes averaged over the contact-start phase:\n",
               exact ? "coefficients for the exact restitution at this timestep (exactRestitution on)"
                     : "Pournin coefficients",
               limitForce ? "on" : "off") +
        report;
    if (said.insert(text).second && lmp->comm->me == 0) {
        if (lmp->screen) fputs(text.c_str(), lmp->screen);
        if (lmp->logfile) fputs(text.c_str(), lmp->logfile);
    }
    for (const std::string& w : warnings)
        if (said.insert(w).second && lmp->comm->me == 0) lmp->error->warning(FLERR, w.c_str());
}

}  // namespace viscoelastic
