// Per type-pair constants of the viscoelastic law, derived at init from the
// `fix property/global` material data, so a contact only multiplies by its
// meff. One table per pair style and per wall (owned by its normal model).
#pragma once

#include <string>
#include <vector>

#include "core/collision.h"
#include "core/discrete.h"
#include "core/pournin.h"

namespace LAMMPS_NS { class LAMMPS; }
class PropertyRegistry;

namespace viscoelastic {

// A contact's CollisionState as the normal model keeps it in the contact
// history (phase, previousOffset, previousPull); the tangential model's
// landing on the exit line writes it too.
inline CollisionState loadCollisionState(const double* h)
{
    return {static_cast<CollisionPhase>(static_cast<int>(h[0])), h[1], h[2]};
}
inline void storeCollisionState(double* h, const CollisionState& s)
{
    h[0] = static_cast<double>(s.phase), h[1] = s.previousOffset, h[2] = s.previousPull;
}

class TypePairTable {
public:
    TypePairTable();
    ~TypePairTable();
    TypePairTable(const TypePairTable&) = delete;
    TypePairTable& operator=(const TypePairTable&) = delete;

    // Reads contactDuration, coefficientRestitution,
    // coefficientRestitutionTangential and coefficientFriction for types
    // 1..maxType and stops with an ERROR naming the property and type pair on
    // a bad value, or when the timestep is above the stable one. With `exact`
    // the coefficients are those for which a binary collision at this
    // timestep restitutes en, et and lasts tc (core/exact.h). Then reports
    // the coefficients in the log.
    // wallMassAsParticle (walls only): contacts scale the coefficients by
    // meff/2 (YADE's facet mass); with `exact` they are solved for that law
    // (core/exact.h, halvedMassCoefficients). With
    // `collision` (exactCollision on, loadCollision follows) the nominal
    // law's accuracy is not warned about. `start`: how the tangential model
    // begins its spring, for exactRestitution's tangential solve.
    void load(LAMMPS_NS::LAMMPS* lmp, PropertyRegistry& registry, int maxType, bool limitForce, bool exact,
              const char* caller, bool wallMassAsParticle = false, bool collision = false,
              SpringStart start = SpringStart::wholeStep);

    const UnitCoefficients& unit(int i, int j) const { return unit_[i * stride_ + j]; }

    // `exactCollision on` (core/collision.h), after load(): the step laws of
    // every type pair (normal per unit meff, tangential per unit m_t), with
    // ERRORs for settings it contradicts and for the unstable timestep; then
    // the table is found by the contact model `owner` it belongs to, for
    // `tangential pournin`.
    struct CollisionLaws {
        StepLaw normal, tangential;  // each holds the continuous oscillator it follows
        double mu = 0;               // coefficientFriction, for a pair's first step (pullRateSinceTouch)
    };
    void loadCollision(LAMMPS_NS::LAMMPS* lmp, bool limitForce, bool wallMassAsParticle, bool exactRestitution,
                       const char* caller, const void* owner);
    bool exactCollision() const { return !collision_.empty(); }
    const CollisionLaws& collision(int i, int j) const { return collision_[i * stride_ + j]; }
    static const TypePairTable* of(const void* owner);

    // What the normal step of the contact in hand decided, for `tangential
    // pournin`: LIGGGHTS calls the normal and then the tangential model of
    // one contact back to back, so it needs no place in the contact history.
    // With it, where the step plans a landing on the exit line (a pair whose
    // contact ends in the next step), the normal model's history of the
    // contact (phase, previousOffset, previousPull), which the tangential
    // model's landing writes (exitLineForce needs this step's friction).
    // And what the step was taken from, for the pull's corrector
    // (exactPairStep's pullNext, which the tangential force's kick gives).
    struct StepInput {
        CollisionState before;  // the contact's state before the step
        double x = 0, v = 0, pull = 0, distance = 0;
    };
    void setCollisionStep(const CollisionStep& s, double* history, const StepInput& input) const
    {
        step_ = s, history_ = history, input_ = input;
    }
    const CollisionStep& collisionStep() const { return step_; }
    double* collisionHistory() const { return history_; }
    const StepInput& stepInput() const { return input_; }

private:
    void say(const std::string& report, const std::vector<std::string>& warnings);

    int stride_ = 0;
    std::vector<UnitCoefficients> unit_;
    std::vector<ContactParameters> params_;  // as read, for loadCollision
    std::vector<CollisionLaws> collision_;
    const void* owner_ = nullptr;
    mutable CollisionStep step_;
    mutable double* history_ = nullptr;
    mutable StepInput input_;

    // What this table printed at its last load, so the report appears once
    // per LAMMPS instance (see say()).
    LAMMPS_NS::LAMMPS* lmp_ = nullptr;
    std::vector<std::string> said_;
    static std::vector<const TypePairTable*> live_;
};

}  // namespace viscoelastic
