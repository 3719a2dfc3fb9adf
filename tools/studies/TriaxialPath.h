/// @file TriaxialPath.h
/// @brief The loading paths of the triaxial test's second stage, from the consolidated state
///        at σ₃ (TriaxialTest.h). Each drives the cell's six walls: the end walls (z) at the
///        axial strain rate, the side walls by servo to a target stress or by prescribed motion.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace lsdem {

enum class TriaxialPath
{
    Compression,    ///< drained compression: ends close, sides hold σ₃
    Extension,      ///< drained extension: ends open, sides hold σ₃ (axial strain < 0)
    ConstantP,      ///< ends close, sides keep the mean stress p at σ₃: σ_r = (3σ₃ − σ_a)/2
    TrueTriaxial,   ///< ends close, x sides hold σ₃, y sides σ₂ = σ₃ + b·(σ_a − σ₃)
    Undrained,      ///< constant volume: ends close, the sides open to keep the cell's volume
    UnloadReload,   ///< compression to a strain, unloading until q falls to a tenth, reloading
    Cyclic,         ///< drained strain cycles: 0 → +A → −A → 0, the sides holding σ₃
};

/// The path's name on the command line and in the outputs ("compression", "constant-p", ...).
std::string triaxialPathName(TriaxialPath path);
/// The path of @a name, if it is one.
std::optional<TriaxialPath> triaxialPathNamed(const std::string& name);
const std::vector<TriaxialPath>& allTriaxialPaths();

} // namespace lsdem
