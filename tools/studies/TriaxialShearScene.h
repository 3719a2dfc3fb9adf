/// @file TriaxialShearScene.h
/// @brief The shearing stage of a triaxial run as a scene for lsdem-run, to edit and rerun:
///        the consolidated sample (grain poses from the run, walls where consolidation left
///        them), the top and bottom walls closing (extension: opening) at the run's strain
///        rate, the side walls servo-controlled at σ₃, ParaView frames on; on a periodic cell
///        (--boundary periodic) the cell instead, x and y stress-controlled at σ₃, z strained;
///        in a membrane (--boundary membrane) the cylinder's grains, the platens, and the
///        membrane placed as consolidation left it at the cell pressure it had then.
///        (The other loading paths set their walls from the stresses step by step, which a
///        scene cannot say.) The grains start at rest with no contact
///        history, so it is the same test, not the run's bytes.
#pragma once

#include "studies/TriaxialStudy.h"

#include <string>

namespace lsdem {

/// The shear scene's step over the least stable step the run met (a margin the run's own step,
/// which it may halve and retry, does not keep).
constexpr double kShearSceneStepOverLimit = 0.6;

/// Write @a dir/triaxial_shear.toml with @a dir/grains.csv (in a membrane also
/// @a dir/membrane_state.csv) and @a dir/assets/NAME.vdb for
/// @a run of @a study (options @a o). Returns the scene's path. @throw Error if the run kept no
/// consolidated state or a file cannot be written.
std::string writeTriaxialShearScene(const TriaxialOptions& o, const TriaxialStudyResult& study,
                                    const TriaxialRun& run, const std::string& dir);

} // namespace lsdem
