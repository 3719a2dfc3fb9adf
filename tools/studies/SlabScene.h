/// @file SlabScene.h
/// @brief The scene of one slab run, and the same scene as a TOML file for lsdem-run.
#pragma once

#include "studies/SlabOptions.h"

#include "lsdem/ls/GrainAsset.h"
#include "lsdem/scene/Scene.h"

#include <memory>
#include <string>

namespace lsdem {

/// The scene of one run: the panel's blocks (free), the frame (level-set obstacles of the
/// same asset, fixed), the indenter (a sphere touching the central block's top, moving down at
/// o.speed) and the contact models, with the block asset @a block (held in memory by the
/// scene) posed from its principal frame. The time step is @a dt and the run ends when the
/// indenter has moved δ_max.
Scene makeSlabScene(const SlabStudyOptions& o, Formulation formulation,
                    std::shared_ptr<const GrainAsset> block, double dt);

/// Write @a scene to @a path as a commented TOML file that lsdem-run reads. Its block asset
/// must have been saved: scene.assets[0].file names the file (written relative to the
/// scene's folder when below it).
void writeSlabScene(const Scene& scene, const SlabStudyOptions& o, const std::string& path);

} // namespace lsdem
