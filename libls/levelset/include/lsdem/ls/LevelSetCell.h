/// @file LevelSetCell.h
/// @brief The eight corner values of one voxel cell of a level set, as a sampler read them,
///        kept by a caller that samples near the same place again and again. A grain's level
///        set never changes during a run, so a node that is still in the same cell at the next
///        step can be interpolated from these values without finding its bricks or touching
///        their data (scattered in memory) again; the result is the same to the bit.
#pragma once

#include <array>
#include <climits>

namespace lsdem {

struct LevelSetCell
{
    /// Index coordinates of the cell's lower corner; INT_MIN: nothing read yet.
    std::array<int, 3> base = {INT_MIN, INT_MIN, INT_MIN};
    /// The corner values, indexed (z<<2)|(y<<1)|x, as stored in the grid (float).
    std::array<float, 8> value = {};
};

} // namespace lsdem
