// `model viscoelastic`: linear spring-dashpot normal force with Pournin et
// al. (2001) coefficients from contactDuration, coefficientRestitution and
// coefficientRestitutionTangential (Eq. 3.20, 3.22-3.25). It also hands kt
// and ct to the tangential model (stock `history` or `pournin`).
#ifdef NORMAL_MODEL
NORMAL_MODEL(VISCOELASTIC,viscoelastic,20)
#else
#ifndef NORMAL_MODEL_VISCOELASTIC_H_
#define NORMAL_MODEL_VISCOELASTIC_H_

#include <algorithm>
#include <cstdio>

#include "contact_models.h"
#include "normal_model_base.h"
#include "atom.h"
#include "comm.h"
#include "core/collision.h"
#include "core/law.h"
#include "error.h"
#include "messages.h"
#include "spring_drive.h"
#include "type_pair_table.h"

namespace LIGGGHTS::ContactModels {

// Per contact: the type pair's constants (table, derived once per run) times
// this contact's meff, as Eq. 3.22-3.25 scale with meff.
template<>
class NormalModel<VISCOELASTIC> : public NormalModelBase
{
public:
    NormalModel(LAMMPS* lmp, IContactHistorySetup* hsetup, class ContactModelBase* c)
        : NormalModelBase(lmp, hsetup, c), cmb(c)
    {}

    void registerSettings(Settings& settings)
    {
        settings.registerOnOff("limitForce", limitForce, false);
        // YADE gives a mass-less facet the mass of the body it touches, so a
        // sphere-wall contact has meff = m/2 there (off: meff = m).
        settings.registerOnOff("wallMassAsParticle", wallMassAsParticle, false);
        // Coefficients for which a binary collision integrated at this
        // timestep restitutes en, et and lasts tc (core/exact.h).
        settings.registerOnOff("exactRestitution", exactRestitution, false);
        // Every single collision restitutes en, et and lasts tc, whatever its
        // start within a step (core/collision.h).
        settings.registerOnOff("exactCollision", exactCollision, false);
    }

    void postSettings(IContactHistorySetup* hsetup, ContactModelBase*)
    {
        // exactCollision's per-contact state (what a step decides for
        // `tangential pournin` goes through the table). Only then: the
        // contact history of restart files stays as it was.
        if (!exactCollision) return;
        history_offset = hsetup->add_history_value("viscoelastic_phase", "0");
        hsetup->add_history_value("viscoelastic_offset", "0");
        hsetup->add_history_value("viscoelastic_pull", "0");
        cmb->add_history_offset("viscoelastic_phase", history_offset);  // tangential pournin then keeps more
    }

    void connectToProperties(PropertyRegistry& registry)
    {
        const char* caller = cmb->is_wall() ? "fix wall/gran model viscoelastic" : "pair gran model viscoelastic";
        if (wallMassAsParticle && !cmb->is_wall())
            error->all(FLERR, "pair gran model viscoelastic: wallMassAsParticle applies to wall contacts only (YADE's "
                              "facet mass): set it on fix wall/gran, not on pair_style");
        if (exactCollision && cmb->get_history_offset("pournin_xi") < 0)
            error->all(FLERR, (std::string(caller) + ": exactCollision on needs `tangential pournin` (it "
                               "corrects the tangential spring at the start and end of each contact)").c_str());
        // `pournin` starts a contact's spring at its first touch, stock `history` a step earlier
        const viscoelastic::SpringStart start = cmb->get_history_offset("pournin_xi") >= 0
                                                    ? viscoelastic::SpringStart::atTouch
                                                    : viscoelastic::SpringStart::wholeStep;
        table.load(lmp, registry, registry.max_type(), limitForce, exactRestitution, caller,
                   wallMassAsParticle && cmb->is_wall(), exactCollision, start);
        if (exactCollision) table.loadCollision(lmp, limitForce, wallMassAsParticle, exactRestitution, caller, cmb);
    }

    double stressStrainExponent() { return 1.0; }

    // Out of line (GCC 12 keeps it there anyway): benchmarks/collision.py
    // counts its calls, the contact-steps, under callgrind.
    [[gnu::noinline]] void surfacesIntersect(SurfacesIntersectData& sidata, ForceData& i_forces, ForceData& j_forces)
    {
        if (sidata.contact_flags) *sidata.contact_flags |= CONTACT_NORMAL_MODEL;
        const double overlapBound = kOverlapBound * (sidata.is_wall ? sidata.radi : std::min(sidata.radi, sidata.radj));
        if (sidata.deltan > overlapBound) overlapError(sidata, overlapBound);
        const double meff = (sidata.is_wall && wallMassAsParticle) ? 0.5 * sidata.meff : sidata.meff;
        const viscoelastic::Coefficients c = viscoelastic::scaled(table.unit(sidata.itype, sidata.jtype), meff);
        const double Fn = exactCollision ? collisionForce(sidata, meff)
                                         : viscoelastic::normalForce(c, sidata.deltan, -sidata.vn, limitForce);

        sidata.Fn = Fn;
        sidata.kn = c.kn;
        sidata.gamman = c.cn;
        sidata.kt = c.kt;
        sidata.gammat = c.ct;  // absolute damping, as `history` expects it

        const double* const normal = sidata.en;  // LIGGGHTS' name for the contact normal, j to i
        const double F = sidata.is_wall ? Fn * sidata.area_ratio : Fn;
        for (int d = 0; d < 3; ++d) {
            i_forces.delta_F[d] += F * normal[d];
            if (!sidata.is_wall) j_forces.delta_F[d] -= F * normal[d];
        }
    }

    void surfacesClose(SurfacesCloseData& scdata, ForceData&, ForceData&)
    {
        if (scdata.contact_flags) *scdata.contact_flags |= CONTACT_NORMAL_MODEL;
        if (!exactCollision || !scdata.contact_history) return;
        double* const h = &scdata.contact_history[history_offset];
        for (int d = 0; d < 3; ++d) h[d] = 0.0;  // apart: the next touch is a fresh contact
    }

    void beginPass(SurfacesIntersectData&, ForceData&, ForceData&) {}
    void endPass(SurfacesIntersectData&, ForceData&, ForceData&) {}

private:
    // The law and its lever arm r - overlap/2 assume small overlaps (Table
    // 3.1's beads at 1 m/s: 1.6 % of r). Half the smaller radius is far past
    // any physical contact: a timestep too large for the speeds, or beads
    // created inside each other.
    static constexpr double kOverlapBound = 0.5;

    void overlapError(const SurfacesIntersectData& sidata, double bound)
    {
        const auto* tag = atom->tag;
        const std::string who = sidata.is_wall
            ? viscoelastic::format("atom %d and the wall", static_cast<int>(tag[sidata.i]))
            : viscoelastic::format("atoms %d and %d", static_cast<int>(tag[sidata.i]), static_cast<int>(tag[sidata.j]));
        const std::string msg = viscoelastic::format(
            "model viscoelastic: %s overlap by %g m, more than half the smaller radius (%g m): the law assumes small "
            "overlaps; the timestep is too large for these speeds, or the bodies were created inside each other",
            who.c_str(), sidata.deltan, bound);
        // Error::one aborts at once; its unflushed message would be lost
        for (FILE* f : {screen, logfile})
            if (f) fprintf(f, "ERROR on proc %d: %s\n", comm->me, msg.c_str()), fflush(f);
        error->one(FLERR, msg.c_str());
    }

    // exactCollision: the step of this contact's collision; its outcome for
    // the tangential model goes to the table (scaled to this contact's meff).
    double collisionForce(SurfacesIntersectData& sidata, double meff)
    {
        using namespace viscoelastic;
        double* const h = &sidata.contact_history[history_offset];
        CollisionState state = loadCollisionState(h);
        // Between two spheres their relative tangential motion pulls the
        // centres apart at |vt|^2 / d; a flat wall's normal does not turn.
        double pull = 0.0;
        if (!sidata.is_wall) {
            double vr2 = 0.0;
            for (int d = 0; d < 3; ++d) vr2 += (sidata.v_i[d] - sidata.v_j[d]) * (sidata.v_i[d] - sidata.v_j[d]);
            pull = std::max(vr2 - sidata.vn * sidata.vn, 0.0) * sidata.rinv;
        }
        const TypePairTable::CollisionLaws& laws = table.collision(sidata.itype, sidata.jtype);
        const double distance = sidata.is_wall ? 0.0 : 1.0 / sidata.rinv;
        const TypePairTable::StepInput input{state, sidata.deltan, -sidata.vn, pull, distance};
        const CollisionStep step = exactPairStep(laws.normal, laws.tangential, state, sidata.deltan, -sidata.vn, pull,
                                                 distance, [&] {
            const Vec3 n(sidata.en[0], sidata.en[1], sidata.en[2]);
            const Vec3 vr(sidata.v_i[0] - sidata.v_j[0], sidata.v_i[1] - sidata.v_j[1], sidata.v_i[2] - sidata.v_j[2]);
            return PairAtTouch{contactSpringDrive(sidata, n, Vec3(sidata.vtr1, sidata.vtr2, sidata.vtr3)),
                               vr - sidata.vn * n, meff, laws.mu, sidata.rinv};
        });
        if (sidata.computeflag && sidata.shearupdate) storeCollisionState(h, state);
        CollisionStep forTangential = step;
        forTangential.friction *= meff;  // as a force [N]
        forTangential.meff = meff;
        table.setCollisionStep(forTangential, h, input);
        return meff * step.force;
    }

    int history_offset = -1;
    bool exactCollision = false;
    bool limitForce = false;
    bool wallMassAsParticle = false;
    bool exactRestitution = false;
    ContactModelBase* cmb;
    viscoelastic::TypePairTable table;
};

}  // namespace LIGGGHTS::ContactModels

#endif  // NORMAL_MODEL_VISCOELASTIC_H_
#endif
