// The packing's container and the check of its options (private to lsdem_scene; Packing.cpp
// deposits the grains).
#pragma once

#include "lsdem/scene/Packing.h"

namespace lsdem {

/// The corners of the container's bounding box.
Vec3 containerMin(const PackingOptions& o);
Vec3 containerMax(const PackingOptions& o);
double containerVolume(const PackingOptions& o);

/// @throw Error with the fix if @a o cannot make a packing: no assets, fractions that are not
/// numbers >= 0 or add up to 0, an empty container, a negative friction, a tolerance <= 0, a
/// count out of range, or a grain that does not fit.
void checkPackingOptions(const PackingOptions& o);

} // namespace lsdem
