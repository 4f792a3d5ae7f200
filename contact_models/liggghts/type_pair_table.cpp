// TypePairTable::load in three steps: read and validate the material data,
// derive the coefficients per type pair (with the timestep guard), report
// them.
#include "type_pair_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "comm.h"
#include "core/discrete.h"
#include "core/exact.h"
#include "core/restitution.h"
#include "core/stability.h"
#include "error.h"
#include "fix_property_global.h"
#include "global_properties.h"
#include "lammps.h"
#include "messages.h"
#include "modify.h"
#include "property_registry.h"
#include "update.h"

namespace viscoelastic {

namespace {

// ---------------------------------------------------------------------------
// Read and validate

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

void check(LAMMPS_NS::LAMMPS* lmp, const PropertySpec& spec, int i, int j, double v, const char* caller)
{
    if (!std::isfinite(v) || !spec.valid(v))
        lmp->error->all(FLERR, format("%s: %s of type pair (%d,%d) is %g; it must be %s", caller, spec.name, i, j,
                                      v, spec.range)
                                   .c_str());
}

// A peratomtypepair property as values[i*stride+j], 1 <= i,j <= maxType,
// after checking every entry it defines (also for types not in use yet). A
// missing property, a too small or an asymmetric matrix are reported by
// LIGGGHTS itself, naming the property.
std::vector<double> readProperty(LAMMPS_NS::LAMMPS* lmp, const PropertySpec& spec, int maxType, const char* caller)
{
    auto* fix = static_cast<LAMMPS_NS::FixPropertyGlobal*>(lmp->modify->find_fix_property(
        spec.name, "property/global", "peratomtypepair", maxType, maxType, caller));
    const int defined = fix->size_array_rows;
    for (int i = 1; i <= defined; ++i)
        for (int j = 1; j <= defined; ++j) check(lmp, spec, i, j, fix->compute_array(i - 1, j - 1), caller);
    const int stride = maxType + 1;
    std::vector<double> values(stride * stride, 0.0);
    for (int i = 1; i <= maxType; ++i)
        for (int j = 1; j <= maxType; ++j) values[i * stride + j] = fix->compute_array(i - 1, j - 1);
    return values;
}

// The material data of each type pair, as parameters[i*stride+j].
std::vector<ContactParameters> readParameters(LAMMPS_NS::LAMMPS* lmp, PropertyRegistry& registry, int maxType,
                                              const char* caller)
{
    const std::vector<double> tc = readProperty(lmp, kDuration, maxType, caller);
    const std::vector<double> en = readProperty(lmp, kRestitution, maxType, caller);
    const std::vector<double> et = readProperty(lmp, kRestitutionTangential, maxType, caller);
    // Friction is the registry's matrix, the one the tangential models
    // (history, pournin) connect to: read once, checked here.
    registry.registerProperty("coeffFrict", &MODEL_PARAMS::createCoeffFrict);
    double** mu = registry.getMatrixProperty("coeffFrict", caller)->data;
    const int stride = maxType + 1;
    std::vector<ContactParameters> p(stride * stride, ContactParameters{});
    for (int i = 1; i <= maxType; ++i)
        for (int j = 1; j <= maxType; ++j) {
            check(lmp, kFriction, i, j, mu[i][j], caller);
            const int k = i * stride + j;
            p[k] = {tc[k], en[k], et[k], mu[i][j]};
        }
    return p;
}

// ---------------------------------------------------------------------------
// Derive

// Above this predicted relative restitution error the run is warned.
constexpr double kAccuracyWarning = 0.01;

struct Derived {
    UnitCoefficients unit{};
    double stableTimestep = 0;           // the multi-contact guard of `unit` (stability.h)
    DiscreteCollision nominal;           // Pournin's coefficients at this dt, phase-averaged
    double continuous = 0;               // restitution of the continuous law
    std::optional<ExactSolution> exact;  // exactRestitution on
    bool halvedMass = false;             // wallMassAsParticle: the law is halvedMassLaw's
};

// The exact solve takes 1-60 ms per type pair (tc/10 to tc/200): the pair
// style and each wall solve for themselves rather than share a cache.
// `halvedMass`: a wall with wallMassAsParticle, whose contacts scale the
// table's coefficients by meff/2 (the law is halvedMassLaw's): the outcomes
// reported are that law's, and exactRestitution solves for it per unit of
// the true meff and stores twice that.
Derived derive(const ContactParameters& p, double dt, bool limitForce, bool exact, SpringStart start, bool halvedMass)
{
    Derived d;
    d.halvedMass = halvedMass;
    // per unit of the true meff
    const UnitCoefficients applied = halvedMass ? halvedMassUnit(p) : pourninUnitCoefficients(p);
    d.nominal = phaseAveragedCollision(applied, dt, limitForce, start);
    d.continuous = halvedMass ? halvedMassLaw(p, limitForce, start).restitution
                              : continuousRestitution(p.tc, p.en, limitForce);
    if (!exact) {
        d.unit = pourninUnitCoefficients(p);
        d.stableTimestep = stableTimestep(p);  // Pournin's; halved, the contact is softer
        return d;
    }
    d.exact = halvedMass ? halvedMassCoefficients(p, dt, limitForce, start)
                         : exactUnitCoefficients(p, dt, limitForce, start);
    d.unit = d.exact->unit;
    d.stableTimestep = stableTimestep(d.unit);  // the corrected oscillators, per unit of the true meff
    if (halvedMass) d.unit.kn *= 2.0, d.unit.cn *= 2.0, d.unit.kt *= 2.0, d.unit.ct *= 2.0;
    return d;
}

void guardTimestep(LAMMPS_NS::LAMMPS* lmp, const ContactParameters& p, int i, int j, double dt, const char* caller)
{
    const double dtCrit = criticalTimestep(p), stable = stableTimestep(p);
    if (dt > stable)
        lmp->error->all(FLERR, format("%s: timestep %g s exceeds the stable timestep %g s of type pair (%d,%d) "
                                      "(tc %g s, en %g, et %g; binary stability limit %g s): beads with many "
                                      "simultaneous contacts become unstable above it (the binary limit of a "
                                      "contact %g times stiffer and more damped); use timestep < %g",
                                      caller, dt, stable, i, j, p.tc, p.en, p.et, dtCrit, kCoordinationFactor, stable)
                                   .c_str());
}

void checkExact(LAMMPS_NS::LAMMPS* lmp, const Derived& d, int i, int j, double dt, const char* caller)
{
    if (!d.exact) return;
    if (!d.exact->ok())
        lmp->error->all(FLERR, format("%s: exactRestitution: type pair (%d,%d): %s", caller, i, j,
                                      failureText(*d.exact).c_str())
                                   .c_str());
    // A request the solver could only approach with a dashpot switched off:
    // within the run's accuracy level (kAccuracyWarning) it is a WARNING
    // (e.g. e = 1, a hair off); farther off, or not even reversed, the
    // setting contradicts the request.
    const std::string contradiction = contradictionText(*d.exact, kAccuracyWarning);
    if (!contradiction.empty())
        lmp->error->all(FLERR, format("%s: exactRestitution on: type pair (%d,%d): %s", caller, i, j,
                                      contradiction.c_str())
                                   .c_str());
    if (dt > d.stableTimestep)
        lmp->error->all(FLERR, format("%s: exactRestitution: timestep %g s exceeds the stable timestep %g s "
                                      "(the multi-contact limit) of the corrected coefficients of type pair (%d,%d)",
                                      caller, dt, d.stableTimestep, i, j)
                                   .c_str());
}

// ---------------------------------------------------------------------------
// Report

std::string reportHeader(bool limitForce, bool exact)
{
    return format("viscoelastic %s: %s per type pair (limitForce %s), outcomes averaged over the contact-start "
                  "phase:\n",
                  VISCOELASTIC_VERSION, exact ? "coefficients for the exact restitution at this timestep (exactRestitution on)"
                        : "Pournin coefficients",
                  limitForce ? "on" : "off");
}

std::string reportLine(const ContactParameters& p, const Derived& d, int i, int j, double dt)
{
    const UnitCoefficients& u = d.unit;
    const std::string coefficients =
        format("  (%d,%d): tc/dt %.1f, timestep limit %.4g s, kn/meff %.6g 1/s^2, cn/meff %.6g 1/s, "
               "kt/meff %.6g 1/s^2, ct/meff %.6g 1/s",
               i, j, p.tc / dt, d.stableTimestep, u.kn, u.cn, u.kt, u.ct);
    const std::string law =
        d.halvedMass ? " (wall contacts at meff/2, wallMassAsParticle: the coefficients are per unit meff/2)" : "";
    if (!d.exact)
        return coefficients + law + format(", restitution %.4f continuous, %.4f at this dt (%+.2f%%), duration %.4g s\n",
                                     d.continuous, d.nominal.restitution,
                                     100.0 * (d.nominal.restitution / d.continuous - 1.0), d.nominal.duration);
    const ExactSolution& x = *d.exact;
    if (d.halvedMass)
        return coefficients + law +
               format("; YADE's law restitutes %.6f, tangential %.6f, over %.6g s; these: %.6f, %.6f, %.6g s at "
                      "this dt (nominal coefficients: %.4f, %.4f, %.4g s)\n",
                      x.requested.en, x.tangentialTarget, x.requested.tc, x.achieved.restitution,
                      x.achieved.tangentialRestitution, x.achieved.duration, d.nominal.restitution,
                      d.nominal.tangentialRestitution, d.nominal.duration);
    return coefficients + format(" (Pournin's for tc %.6g s, en %.6f); restitution %.6f, tangential %.6f, "
                                 "duration %.6g s at this dt (nominal coefficients: %.4f, %.4f, %.4g s)\n",
                                 x.tcNormal, x.enNormal, x.achieved.restitution, x.achieved.tangentialRestitution,
                                 x.achieved.duration, d.nominal.restitution, d.nominal.tangentialRestitution,
                                 d.nominal.duration);
}

std::optional<std::string> warningOf(const ContactParameters& p, const Derived& d, int i, int j, double dt,
                                     bool limitForce)
{
    if (d.exact) {
        const std::string w = warningText(*d.exact);
        if (w.empty()) return std::nullopt;
        return format("viscoelastic: type pair (%d,%d): %s", i, j, w.c_str());
    }
    // limitForce moves the restitution itself, before any timestep error
    // (under wallMassAsParticle the law is YADE's by request: not warned)
    const double moved = d.continuous / p.en - 1.0;
    if (limitForce && !d.halvedMass && std::fabs(moved) > kAccuracyWarning)
        return format("viscoelastic: limitForce on: type pair (%d,%d) asks for en %g but, with the attractive end of "
                      "the contact cut, restitutes %.4f (%+.1f%%; %.4f at this timestep); exactRestitution on or "
                      "exactCollision on restitute en %g with limitForce on",
                      i, j, p.en, d.continuous, 100.0 * moved, d.nominal.restitution, p.en);
    const double err = d.nominal.restitution / d.continuous - 1.0;
    if (std::fabs(err) <= kAccuracyWarning) return std::nullopt;
    return format("viscoelastic: at timestep %g s (tc/dt = %.1f) type pair (%d,%d) restitutes %.4f instead of %.4f "
                  "(%+.2f%%); a smaller timestep or exactRestitution on reduces this",
                  dt, p.tc / dt, i, j, d.nominal.restitution, d.continuous, 100.0 * err);
}

}  // namespace

// ---------------------------------------------------------------------------

// The pair style and every wall own a table and load it at every run, most
// with the same settings: the same report would appear several times per
// run, and again at every run. So each table keeps what it printed at its
// last load, and a message is printed unless a live table of the same LAMMPS
// instance (this one included) has printed it. The tables find each other in
// this list, which each joins in its constructor and leaves in its
// destructor: nothing said outlives its table, so a new LAMMPS instance (or a
// redefined pair style with no wall left saying the same) reports afresh.
std::vector<const TypePairTable*> TypePairTable::live_;

TypePairTable::TypePairTable() { live_.push_back(this); }

TypePairTable::~TypePairTable() { live_.erase(std::find(live_.begin(), live_.end(), this)); }

void TypePairTable::load(LAMMPS_NS::LAMMPS* lmp, PropertyRegistry& registry, int maxType, bool limitForce,
                         bool exact, const char* caller, bool wallMassAsParticle, bool collision,
                         SpringStart start)
{
    const std::vector<ContactParameters> params = readParameters(lmp, registry, maxType, caller);
    params_ = params;
    const double dt = lmp->update->dt;
    stride_ = maxType + 1;
    unit_.assign(stride_ * stride_, UnitCoefficients{});
    // (exactCollision reports the laws it follows instead: loadCollision)
    std::string report = collision ? std::string() : reportHeader(limitForce, exact);
    std::vector<std::string> warnings;
    for (int i = 1; i <= maxType; ++i)
        for (int j = i; j <= maxType; ++j) {  // symmetric: (j,i) is (i,j)
            const ContactParameters& p = params[i * stride_ + j];
            // the guard applies to the law in use: with exactRestitution the
            // corrected coefficients (checkExact), with exactCollision its
            // step law (loadCollision)
            if (!exact && !collision) guardTimestep(lmp, p, i, j, dt, caller);
            const Derived d = derive(p, dt, limitForce, exact, start, wallMassAsParticle);
            checkExact(lmp, d, i, j, dt, caller);
            unit_[i * stride_ + j] = unit_[j * stride_ + i] = d.unit;
            if (!collision) report += reportLine(p, d, i, j, dt);
            // exactCollision replaces what the nominal law would do at this dt
            if (const auto w = collision ? std::nullopt : warningOf(p, d, i, j, dt, limitForce))
                warnings.push_back(*w);
        }
    lmp_ = lmp;
    say(report, warnings);
}

void TypePairTable::say(const std::string& report, const std::vector<std::string>& warnings)
{
    auto fresh = [this](const std::string& m) {
        for (const TypePairTable* t : live_)
            if (t->lmp_ == lmp_ && std::find(t->said_.begin(), t->said_.end(), m) != t->said_.end()) return false;
        return true;
    };
    const bool newReport = fresh(report);
    std::vector<std::string> newWarnings;
    for (const std::string& w : warnings)
        if (fresh(w)) newWarnings.push_back(w);
    said_.assign(1, report);
    said_.insert(said_.end(), warnings.begin(), warnings.end());

    if (lmp_->comm->me != 0) return;
    if (newReport && !report.empty()) {
        if (lmp_->screen) fputs(report.c_str(), lmp_->screen);
        if (lmp_->logfile) fputs(report.c_str(), lmp_->logfile);
    }
    for (const std::string& w : newWarnings) lmp_->error->warning(FLERR, w.c_str());
}

}  // namespace viscoelastic
