/// @file ExactDistance.h
/// @brief A signed distance known in closed form (an analytic shape's), which a level set may
///        carry to be sampled instead of its voxels: then every sampler of that level set
///        returns the exact φ and ∇φ. The reference force fixtures use it, so what they expect
///        depends on the contact laws and the geometry alone, not on how voxels are stored.
///        Light header: no OpenVDB.
#pragma once

#include "lsdem/core/Vec3.h"

namespace lsdem {

class ExactDistance
{
public:
    virtual ~ExactDistance() = default;
    /// The signed distance at @a p (asset frame), negative inside.
    virtual double phi(const Vec3& p) const = 0;
    /// Its gradient at @a p (unit length wherever the distance is differentiable).
    virtual Vec3 gradient(const Vec3& p) const = 0;
};

} // namespace lsdem
