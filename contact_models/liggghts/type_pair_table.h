// Per type-pair material data of the viscoelastic law, read from
// `fix property/global` at init, validated, and turned into the core's
// unit coefficients once, so a contact only multiplies by its meff.
#pragma once

#include <vector>

#include "core/viscoelastic.h"

namespace LAMMPS_NS { class LAMMPS; }

namespace viscoelastic {

class TypePairTable {
public:
    // Reads contactDuration, coefficientRestitution,
    // coefficientRestitutionTangential and coefficientFriction for types
    // 1..maxType, stops with an ERROR naming the property and type pair on a
    // bad value, and checks the timestep against the stability limit. With
    // `exact` the coefficients are those for which a binary collision at
    // this timestep restitutes en, et and lasts tc (core/discrete.h).
    void load(LAMMPS_NS::LAMMPS* lmp, int maxType, bool limitForce, bool exact, const char* caller);

    const UnitCoefficients& unit(int i, int j) const { return unit_[i * stride_ + j]; }
    const ContactParameters& params(int i, int j) const { return params_[i * stride_ + j]; }

private:
    int stride_ = 0;
    std::vector<ContactParameters> params_;
    std::vector<UnitCoefficients> unit_;
};

}  // namespace viscoelastic
