// `tangential pournin`: the thesis' own tangential law (Eq. 3.5, 3.18-3.21).
// It differs from stock `history` in two ways: the Coulomb cap bounds the
// total force kt xi + ct dxi/dt (history caps the elastic part and drops the
// dashpot while sliding), and the tangential overlap is rotated with the
// contact frame (history projects it, which shortens it). Needs
// `model viscoelastic`, which supplies kt and ct.
#ifdef TANGENTIAL_MODEL
TANGENTIAL_MODEL(TANGENTIAL_POURNIN,pournin,20)
#else
#ifndef TANGENTIAL_MODEL_POURNIN_H_
#define TANGENTIAL_MODEL_POURNIN_H_

#include "contact_models.h"
#include "tangential_model_base.h"
#include "update.h"
#include "core/collision.h"
#include "core/law.h"
#include "spring_drive.h"
#include "type_pair_table.h"

namespace LIGGGHTS::ContactModels {

// Per contact: kt and ct from `model viscoelastic` (sidata), mu from the registry.
template<>
class TangentialModel<TANGENTIAL_POURNIN> : public TangentialModelBase
{
public:
    TangentialModel(LAMMPS* lmp, IContactHistorySetup* hsetup, class ContactModelBase* c)
        : TangentialModelBase(lmp, hsetup, c), cmb(c)
    {
        // xi and the normal it is expressed in; both flip sign seen from j.
        history_offset = hsetup->add_history_value("pournin_xi_x", "1");
        hsetup->add_history_value("pournin_xi_y", "1");
        hsetup->add_history_value("pournin_xi_z", "1");
        hsetup->add_history_value("pournin_n_x", "1");
        hsetup->add_history_value("pournin_n_y", "1");
        hsetup->add_history_value("pournin_n_z", "1");
        hsetup->add_history_value("pournin_fn", "0");  // the unclipped normal force: the same seen from j
        c->add_history_offset("pournin_xi", history_offset);
    }

    void registerSettings(Settings&) {}
    // exactCollision (model viscoelastic registered its state first): the
    // normal force the step foresaw for the next (and the pull it took), the continuous rate's
    // offset from the samples' where the cap bound within a
    // step (h[6], unused then, flags it: 1, and 2 if it ended the step
    // sliding), and the spring's force a slide ended the step with (where
    // the next step's slide turns from). Only then: restart files of the
    // other settings keep their contact history.
    void postSettings(IContactHistorySetup* hsetup, ContactModelBase*)
    {
        if (cmb->get_history_offset("viscoelastic_phase") < 0) return;
        rate_offset = hsetup->add_history_value("pournin_rate_x", "1");
        hsetup->add_history_value("pournin_rate_y", "1");
        hsetup->add_history_value("pournin_rate_z", "1");
        hsetup->add_history_value("pournin_forecast", "0");
        hsetup->add_history_value("pournin_slide_x", "1");  // sliding: the spring's force at the step's end
        hsetup->add_history_value("pournin_slide_y", "1");
        hsetup->add_history_value("pournin_slide_z", "1");
        hsetup->add_history_value("pournin_forecast_pull", "0");  // the pull the forecast was made with
    }

    void connectToProperties(PropertyRegistry& registry)
    {
        // coefficientFriction as the registry read it once (model viscoelastic checked it)
        registry.registerProperty("coeffFrict", &MODEL_PARAMS::createCoeffFrict);
        registry.connect("coeffFrict", coeffFrict, "tangential_model pournin");
    }

    // Out of line, as the normal model's (benchmarks/collision.py counts its calls).
    [[gnu::noinline]] void surfacesIntersect(const SurfacesIntersectData& sidata, ForceData& i_forces, ForceData& j_forces)
    {
        using viscoelastic::Vec3;
        if (sidata.contact_flags) *sidata.contact_flags |= CONTACT_TANGENTIAL_MODEL;

        double* const h = &sidata.contact_history[history_offset];
        viscoelastic::TangentialState state;
        state.xi = Vec3(h[0], h[1], h[2]);
        state.normal = Vec3(h[3], h[4], h[5]);
        const Vec3 normal(sidata.en[0], sidata.en[1], sidata.en[2]);  // LIGGGHTS calls the contact normal `en`
        const Vec3 vt(sidata.vtr1, sidata.vtr2, sidata.vtr3);
        const bool advance = sidata.computeflag && sidata.shearupdate;

        // exactCollision: model viscoelastic's table has the tangential law
        // and its step's outcome, with the law's mean |Fn| over the step.
        const viscoelastic::TypePairTable* const t = table();
        const bool exact = t && t->exactCollision();
        const double mu = coeffFrict[sidata.itype][sidata.jtype];
        const double limit = viscoelastic::frictionLimit(mu, exact ? t->collisionStep().friction : sidata.Fn);
        Vec3 Ft;
        double landing = 0.0;  // along the normal, where a pair lands on its exit line
        // h[6], the unclipped normal force of the step before, serves the
        // nominal spring only
        viscoelastic::ExactTangentialState e;
        if (exact) {
            const viscoelastic::SpringDrive drive = contactSpringDrive(sidata, normal, vt);
            const double* const r = &sidata.contact_history[rate_offset];
            // (the offset and the slide's force are read and kept only where
            // they count: off the path, sliding; the common step skips both)
            e.offPath = h[6] != 0.0, e.sliding = h[6] == 2.0, e.forecast = r[3], e.forecastPull = r[7];
            if (e.offPath) e.rateOffset = Vec3(r[0], r[1], r[2]);
            if (e.sliding) e.force = Vec3(r[4], r[5], r[6]);
            const auto& laws = t->collision(sidata.itype, sidata.jtype);
            const viscoelastic::CollisionStep* used = &t->collisionStep();
            double* const c = t->collisionHistory();
            const viscoelastic::TypePairTable::StepInput& in = t->stepInput();
            // (a pair's corrector, correctPull; the normal force's change goes
            // with the landing's)
            viscoelastic::CollisionStep corrected;
            viscoelastic::CollisionState collision;
            // the centres' relative velocity (the corrector's kicks and the landing start from it)
            const Vec3 v(sidata.v_i[0] - sidata.v_j[0], sidata.v_i[1] - sidata.v_j[1], sidata.v_i[2] - sidata.v_j[2]);
            const bool correct =
                !sidata.is_wall &&
                viscoelastic::correctPull(
                    laws.normal, laws.tangential, in.before, collision, *used, corrected, in.x, in.v, in.pull,
                    in.distance, v, normal,
                    [&] {
                        return viscoelastic::PairAtTouch{drive, v - v.dot(normal) * normal, used->meff, mu, sidata.rinv};
                    },
                    [&](const viscoelastic::CollisionStep& s) {
                        viscoelastic::TangentialState springAhead = state;
                        viscoelastic::ExactTangentialState exactAhead = e;
                        return viscoelastic::exactTangentialForce(springAhead, exactAhead, normal, drive.rate, drive.mass,
                                                                  laws.tangential, laws.normal, s, mu * s.meff, limit,
                                                                  false, drive.feed);
                    });
            if (correct) {
                landing = used->meff * (corrected.force - used->force);
                used = &corrected;
                if (advance) viscoelastic::storeCollisionState(c, collision);
            }
            const viscoelastic::CollisionStep& step = *used;
            const double stepLimit = correct ? viscoelastic::frictionLimit(mu, step.friction) : limit;
            Vec3 exitChange;
            Ft = viscoelastic::exactTangentialForce(state, e, normal, drive.rate, drive.mass, laws.tangential, laws.normal,
                                                    step, mu * step.meff, stepLimit, advance, drive.feed, &exitChange);
            if (step.exit.sigma > 0.0) {  // a pair ending in the next step: land on the exit line
                if (!correct) collision = viscoelastic::loadCollisionState(c);
                landing += viscoelastic::exitLineForce(laws.normal, collision, step, v - v.dot(normal) * normal, Ft,
                                                       drive.mass, exitChange);
                if (advance) viscoelastic::storeCollisionState(c, collision);
            }
        } else {
            state.normalForce = h[6];
            Ft = viscoelastic::pourninTangentialForce(state, normal, vt, sidata.kt, sidata.gammat, limit, update->dt,
                                                      advance, unclippedNormalForce(sidata),
                                                      viscoelastic::timeSinceTouch(sidata.deltan, -sidata.vn, update->dt));
        }
        if (advance) {
            for (int d = 0; d < 3; ++d) {
                h[d] = state.xi[d];
                h[3 + d] = state.normal[d];
            }
            if (!exact) h[6] = state.normalForce;
            else {
                h[6] = e.offPath ? (e.sliding ? 2.0 : 1.0) : 0.0;
                double* const r = &sidata.contact_history[rate_offset];
                r[3] = e.forecast, r[7] = e.forecastPull;
                if (e.offPath)
                    for (int d = 0; d < 3; ++d) r[d] = e.rateOffset[d];
                if (e.sliding)
                    for (int d = 0; d < 3; ++d) r[4 + d] = e.force[d];
            }
        }

        // Torque about each centre from the force at the contact point.
        const Vec3 nxF = normal.cross(Ft);
        const double scale = sidata.is_wall ? sidata.area_ratio : 1.0;
        for (int d = 0; d < 3; ++d) {
            i_forces.delta_F[d] += scale * Ft[d] + landing * normal[d];
            i_forces.delta_torque[d] -= scale * sidata.cri * nxF[d];
            if (!sidata.is_wall) {
                j_forces.delta_F[d] -= Ft[d] + landing * normal[d];
                j_forces.delta_torque[d] -= sidata.crj * nxF[d];
            }
        }
    }

    inline void surfacesClose(SurfacesCloseData& scdata, ForceData&, ForceData&)
    {
        if (scdata.contact_flags) *scdata.contact_flags &= ~CONTACT_TANGENTIAL_MODEL;
        if (!scdata.contact_history) return;
        double* const h = &scdata.contact_history[history_offset];
        for (int d = 0; d < 7; ++d) h[d] = 0.0;
        if (rate_offset >= 0)
            for (int d = 0; d < 8; ++d) scdata.contact_history[rate_offset + d] = 0.0;
    }

    void beginPass(SurfacesIntersectData&, ForceData&, ForceData&) {}
    void endPass(SurfacesIntersectData&, ForceData&, ForceData&) {}

private:
    // Eq. 3.20 before limitForce clips it, from the coefficients model viscoelastic set.
    static double unclippedNormalForce(const SurfacesIntersectData& d)
    {
        return viscoelastic::normalForce({d.kn, d.gamman, d.kt, d.gammat}, d.deltan, -d.vn, false);
    }

    // The normal model's table (registered under the contact model both belong to).
    const viscoelastic::TypePairTable* table()
    {
        if (!looked_) table_ = viscoelastic::TypePairTable::of(cmb), looked_ = true;
        return table_;
    }

    double** coeffFrict = nullptr;
    const viscoelastic::TypePairTable* table_ = nullptr;
    bool looked_ = false;
    ContactModelBase* cmb;
    int history_offset;
    int rate_offset = -1;
};

}  // namespace LIGGGHTS::ContactModels

#endif  // TANGENTIAL_MODEL_POURNIN_H_
#endif
