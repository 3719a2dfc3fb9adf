/// @file RunRecord.h
/// @brief What a run keeps besides the world, so that a restart continues its outputs: the
///        history rows recorded so far and the times of the ParaView frames written.
#pragma once

#include <vector>

namespace lsdem {

/// What the run driver keeps besides the world: rows of history already recorded and the
/// times of the ParaView frames written.
struct RunRecord
{
    std::vector<std::vector<double>> energyRows;
    std::vector<std::vector<std::vector<double>>> boundaryRows;  ///< per boundary
    /// Per membrane (kept in checkpoints from version 8, as the boundaries' are).
    std::vector<std::vector<std::vector<double>>> membraneRows;
    /// A periodic cell's rows (kept in checkpoints from version 9).
    std::vector<std::vector<double>> cellRows;
    std::vector<double> vtkFrameTimes;
    /// Whether each history row also records the micromechanics ([output] micromechanics).
    bool micromechanics = false;
    std::vector<std::vector<double>> micromechanicsRows;
};

} // namespace lsdem
