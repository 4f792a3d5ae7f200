#include "type_pair_table.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <set>
#include <string>

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
// Dense packings raise a bead's highest frequency up to about twice the
// binary one (12 neighbours, fcc), which halves the stable step.
constexpr double kMultiContactFactor = 0.5;

}  // namespace

void TypePairTable::load(LAMMPS_NS::LAMMPS* lmp, int maxType, bool limitForce, const char* caller)
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
            unit_[k] = pourninUnitCoefficients(params_[k]);
            if (j < i) continue;

            const double dtCrit = criticalTimestep(params_[k]);
            if (dt > dtCrit)
                lmp->error->all(
                    FLERR, format("%s: timestep %g s exceeds the stability limit %g s of type pair "
                                  "(%d,%d) (tc %g s, en %g, et %g): use timestep < %g",
                                  caller, dt, dtCrit, i, j, tc[k], en[k], et[k], dtCrit)
                               .c_str());
            const DiscreteCollision d = discreteCollision(tc[k], en[k], dt, limitForce);
            const double eCont = continuousRestitution(tc[k], en[k], limitForce);
            const double err = d.restitution / eCont - 1.0;
            report += format("  (%d,%d): tc/dt %.1f, dt limit %.4g s, kn/meff %.6g 1/s^2, "
                             "cn/meff %.6g 1/s, kt/meff %.6g 1/s^2, ct/meff %.6g 1/s, "
                             "restitution %.4f continuous, %.4f at this dt (%+.2f%%)\n",
                             i, j, tc[k] / dt, dtCrit, unit_[k].kn, unit_[k].cn, unit_[k].kt,
                             unit_[k].ct, eCont, d.restitution, 100.0 * err);
            if (dt > kMultiContactFactor * dtCrit)
                warnings.push_back(format("viscoelastic: timestep %g s is above half the binary stability limit "
                                   "%g s of type pair (%d,%d); beads with many simultaneous "
                                   "contacts may become unstable",
                                   dt, dtCrit, i, j));
            else if (std::fabs(err) > kAccuracyWarning)
                warnings.push_back(format("viscoelastic: at timestep %g s (tc/dt = %.1f) type pair (%d,%d) "
                                   "restitutes %.4f instead of %.4f (%+.2f%%); a smaller "
                                   "timestep reduces this",
                                   dt, tc[k] / dt, i, j, d.restitution, eCont,
                                   100.0 * err));
        }

    // Pair style and every wall load the same table, at every run: say each
    // thing once.
    static std::set<std::string> said;
    const std::string text = format("viscoelastic: Pournin coefficients per type pair (limitForce %s):\n",
                                    limitForce ? "on" : "off") + report;
    if (said.insert(text).second && lmp->comm->me == 0) {
        if (lmp->screen) fputs(text.c_str(), lmp->screen);
        if (lmp->logfile) fputs(text.c_str(), lmp->logfile);
    }
    for (const std::string& w : warnings)
        if (said.insert(w).second && lmp->comm->me == 0) lmp->error->warning(FLERR, w.c_str());
}

}  // namespace viscoelastic
