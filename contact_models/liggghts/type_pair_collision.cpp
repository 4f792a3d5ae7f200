// TypePairTable::loadCollision: the step laws of `exactCollision on` per type
// pair (core/collision.h), the settings it contradicts, its timestep guard
// and its report.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "comm.h"
#include "core/stability.h"
#include "error.h"
#include "lammps.h"
#include "messages.h"
#include "type_pair_table.h"
#include "update.h"

namespace viscoelastic {

void TypePairTable::loadCollision(LAMMPS_NS::LAMMPS* lmp, bool limitForce, bool wallMassAsParticle,
                                  bool exactRestitution, const char* caller, const void* owner)
{
    if (exactRestitution)
        lmp->error->all(FLERR, format("%s: exactCollision on and exactRestitution on are alternatives: "
                                      "exactCollision makes every single collision exact, exactRestitution only "
                                      "their average over start phases; set one of them off",
                                      caller)
                                   .c_str());
    if (wallMassAsParticle)
        lmp->error->all(FLERR, format("%s: exactCollision on contradicts wallMassAsParticle on: the latter "
                                      "reproduces YADE's wall contacts, whose effective mass m/2 makes them last "
                                      "sqrt(2) tc, not tc; set one of them off",
                                      caller)
                                   .c_str());
    const double dt = lmp->update->dt;
    collision_.assign(stride_ * stride_, CollisionLaws{});
    std::string report = format("%s (viscoelastic %s): exactCollision on: a single binary collision restitutes what the continuous "
                                "law does, whatever its start within a step: en, (sticking) et and tc where the law "
                                "gives them (between two spheres at incidence, or with et != en, finite friction and "
                                "limitForce off, the law's own en and et, as below; docs/law.md)\n",
                                caller, VISCOELASTIC_VERSION);
    for (int i = 1; i < stride_; ++i)
        for (int j = i; j < stride_; ++j) {
            const ContactParameters& p = params_[i * stride_ + j];
            const auto osc = exactCollisionOscillators(p, limitForce);
            if (!osc)
                lmp->error->all(FLERR, format("%s: exactCollision on with limitForce on: type pair (%d,%d) asks for "
                                              "en %g, but a contact whose attractive end is cut restitutes at "
                                              "least %.3f whatever its coefficients; set limitForce off or "
                                              "coefficientRestitution >= %.3f",
                                              caller, i, j, p.en, leastCutRestitution(), leastCutRestitution())
                                           .c_str());
            CollisionLaws& c = collision_[i * stride_ + j];
            c.normal = stepLaw(osc->normal.k, osc->normal.c, dt, limitForce);
            c.tangential = stepLaw(osc->tangential.k, osc->tangential.c, dt, false);
            c.mu = p.mu;
            collision_[j * stride_ + i] = c;
            // A binary contact under these laws is stable at any step; a bead
            // with many contacts is not: the same guard as the plain law, on
            // the stiffnesses actually applied.
            const double stable = stableTimestep(appliedCoefficients(c.normal, c.tangential));
            if (dt > stable) {
                // the applied law depends on the step: advise the coarsest step it admits
                // (rounded down to the digits printed, so the advice itself is admitted)
                const double coarsest = coarsestStableStep(osc->normal, osc->tangential, dt, limitForce);
                const double scale = std::pow(10.0, 5.0 - std::floor(std::log10(coarsest)));
                const double advised = std::floor(coarsest * scale) / scale;
                lmp->error->all(FLERR, format("%s: exactCollision: timestep %g s exceeds the stable timestep %g s of "
                                              "type pair (%d,%d) (tc %g s, en %g, et %g): the multi-contact limit of "
                                              "the applied law, which changes with the step; use timestep <= %.6g "
                                              "(tc/%.3f)",
                                              caller, dt, stable, i, j, p.tc, p.en, p.et, advised, p.tc / advised)
                                           .c_str());
            }
            // the law's sticking et on a wall: without limitForce its spring lets go at the normal force's zero
            const double etLaw = limitForce ? p.et : letGoRestitution(p);
            report += format("  (%d,%d): tc %g s, en %g, et %g%s: tc/dt %.2f; restitutes en %.6f and, sticking on a "
                             "wall, et %.6f; step law kn/meff %.6g 1/s^2, cn/meff %.6g 1/s (continuous: %.6g, %.6g)\n",
                             i, j, p.tc, p.en, p.et,
                             limitForce ? format(" (limitForce: followed law tc' %.6g s, en' %.6g)",
                                                 kPi / osc->normal.omega,
                                                 std::exp(-osc->normal.lambda * kPi / osc->normal.omega))
                                              .c_str()
                                        : "",
                             p.tc / dt, p.en, etLaw, c.normal.kStep, c.normal.cStep, osc->normal.k, osc->normal.c);
        }
    owner_ = owner;
    if (lmp->comm->me == 0) {
        if (lmp->screen) fputs(report.c_str(), lmp->screen);
        if (lmp->logfile) fputs(report.c_str(), lmp->logfile);
    }
}

const TypePairTable* TypePairTable::of(const void* owner)
{
    for (const TypePairTable* t : live_)
        if (t->owner_ == owner && t->exactCollision()) return t;
    return nullptr;
}

}  // namespace viscoelastic
