/// @file SceneValidation.h
/// @brief The rules every scene obeys, however it was made: read from TOML, built in Python or
///        by a study. The reader checks each key where it stands (naming its line); this is
///        the check of the whole: buildWorld runs validateScene before anything is built (so a
///        scene built in code meets the file's rules), the writer before it writes (so what
///        it writes holds to them), and the reader when it is done runs validateRunnableScene
///        (a scene file also says when its run ends).
#pragma once

#include "lsdem/scene/Scene.h"

namespace lsdem {

/// @throw Error naming the entry (its `where`) and the fix if @a scene breaks a rule:
///        indices out of range; a number not finite or out of its range (materials' densities,
///        the contact laws' coefficients by their schema, ContactCoefficients.h, grains'
///        states and unit orientations, boundaries' sizes, servo walls, the time step, damping,
///        the end condition, output periods); two grains or boundaries of one name; a pair of
///        materials that can meet without exactly one contact law.
void validateScene(const Scene& scene);

/// validateScene, and the scene has an end condition (end_time, end_steps or end_displacement).
void validateRunnableScene(const Scene& scene);

} // namespace lsdem
