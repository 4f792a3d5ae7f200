// exactCollision's tangential spring drive (core/exact_tangential.h's
// springDrive) from a LIGGGHTS contact: `tangential pournin` steps the spring
// with it, `model viscoelastic` foresees a pair's first step with it.
#pragma once

#include "contact_models.h"
#include "core/collision.h"

namespace LIGGGHTS::ContactModels {

// From LIGGGHTS' contact-point velocity vtr and the contact normal n.
inline viscoelastic::SpringDrive contactSpringDrive(const SurfacesIntersectData& d, const viscoelastic::Vec3& n,
                                                    const viscoelastic::Vec3& vtr)
{
    using viscoelastic::Vec3;
    const Vec3 wi(d.omega_i[0], d.omega_i[1], d.omega_i[2]);
    if (d.is_wall) return viscoelastic::springDrive(vtr, n, d.deltan, d.meff, d.mi, d.radi, d.cri, wi, 0.0, 0.0, 0.0, wi);
    return viscoelastic::springDrive(vtr, n, d.deltan, d.meff, d.mi, d.radi, d.cri, wi, d.mj, d.radj, d.crj,
                                     Vec3(d.omega_j[0], d.omega_j[1], d.omega_j[2]));
}

}  // namespace LIGGGHTS::ContactModels
