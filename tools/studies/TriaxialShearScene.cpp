#include "studies/TriaxialShearScene.h"

#include "studies/TriaxialSample.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/Error.h"
#include "lsdem/scene/GrainsCsv.h"
#include "lsdem/scene/MembraneStateCsv.h"
#include "lsdem/scene/SceneWriter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <filesystem>

namespace lsdem {

std::string writeTriaxialShearScene(const TriaxialOptions& o, const TriaxialStudyResult& study,
                                    const TriaxialRun& run, const std::string& dir)
{
    namespace fs = std::filesystem;
    const TriaxialTestResult& t = run.test;
    const bool membrane = !t.consolidatedGrains.empty();
    if (t.consolidatedPoses.size() !=
            (membrane ? t.consolidatedGrains.size() : static_cast<size_t>(study.grains)) ||
        (membrane && t.consolidatedMembrane.empty()))
        throw Error(dir, "the run kept no consolidated sample to write as a scene");
    const std::vector<std::string> files = triaxialMeshFiles(o);
    const std::shared_ptr<const TriaxialAssets> assets =
        sharedTriaxialAssets(files, run.vdp, run.sdp);
    const TriaxialCloud cloud = makeTriaxialCloud(study.grains, int(files.size()), study.spacing,
                                                  static_cast<std::uint64_t>(run.seed),
                                                  o.heightRatio);
    Scene s = triaxialScene(o, *assets, cloud, run.formulation, run.stiffness);

    fs::create_directories(fs::path(dir) / "assets");
    double smallestRadius = 1e300;
    for (size_t i = 0; i < s.assets.size(); ++i) {
        const fs::path file = fs::absolute(fs::path(dir) / "assets" / (s.assets[i].name + ".vdb"));
        saveAsset(*assets->assets[i], file.string());
        s.assets[i].file = file.string();
        smallestRadius = std::min(smallestRadius, assets->assets[i]->boundingRadius);
    }
    if (membrane) {  // the cylinder's grains only
        std::vector<GrainSpec> kept;
        for (long long i : t.consolidatedGrains) kept.push_back(s.grains.at(size_t(i)));
        s.grains = std::move(kept);
    }
    for (size_t k = 0; k < s.grains.size(); ++k) s.grains[k].pose = t.consolidatedPoses[k];
    const std::string grainsFile = fs::absolute(fs::path(dir) / "grains.csv").string();
    writeGrainsCsv(s, 0, s.grains.size(), grainsFile);
    GrainFileSpec table;
    table.file = grainsFile;
    table.count = s.grains.size();
    // A consolidated sample is pressed together: its grains overlap by their elastic contact
    // deformation at σ₃, more than a loose packing's default allowance.
    table.maxOverlap = 0.1 * smallestRadius;
    s.grainFiles.push_back(table);

    const Vec3 size = t.consolidated.size;
    const double strain = o.sceneStrain > 0.0 ? o.sceneStrain : o.maxAxialStrain;
    const double opening = run.path == TriaxialPath::Extension ? -1.0 : 1.0;
    // The walls close at a constant speed; the cell shrinks at a constant rate, so its height
    // is H0·e^(−ε̇t) and the (engineering) strain ε takes −ln(1 − ε)/ε̇ (ln(1 + ε)/ε̇ opening).
    const double duration = o.periodic ? std::abs(std::log(1.0 - opening * strain)) / run.strainRate
                                       : strain / run.strainRate;
    if (o.periodic) {
        // The cell as consolidation left it (it shrinks towards its origin): z strained at the
        // run's rate (a constant rate here, where the study keeps the height's speed), x and
        // y held at σ₃ by stress control at up to twice that rate.
        s.periodicCell = size;
        s.periodicStress = Vec3(o.confiningStress, o.confiningStress, 0.0);
        s.periodicMaxStrainRate = Vec3(2.0 * run.strainRate, 2.0 * run.strainRate, 0.0);
        s.periodicStrainRate = Vec3(0.0, 0.0, -opening * run.strainRate);
        s.end.time = duration;
    }
    for (int k = 0; k < 6 && !o.periodic; ++k) {
        BoundarySpec& b = s.boundaries[size_t(k)];
        b.point = t.consolidatedWallPoints[size_t(k)];
        const int axis = k / 2;
        if (axis == 2) {
            b.velocity = opening * 0.5 * run.strainRate * size.z() * b.normal;
            continue;
        }
        b.servo.targetStress = o.confiningStress;
        b.servo.areaWalls = areaWallsOf(triaxialWalls(), axis);
        b.servo.gain = 0.5;
        b.servo.maxSpeed = run.strainRate * size[axis];
    }
    // The run's step held its own shearing, at up to 0.88 of the least stable step it met (10,000
    // grains); the scene's grains start at rest, with no history, and are sheared as far again
    // in another process's order, so a 10,000-grain scene at the run's step met a stiffer
    // contact at step 1262 (limit 1.8735e-6 s against the step's 1.8743e-6): keep a margin.
    const double limit = run.stabilityLimit > 0.0 && std::isfinite(run.stabilityLimit)
                             ? run.stabilityLimit
                             : std::numeric_limits<double>::infinity();
    s.timeStep.fixed = std::min(run.dt, kShearSceneStepOverLimit * limit);
    if (membrane) {
        // The platens alone (the side walls were taken off when the membrane was put on), and
        // the membrane as consolidation left it, at the cell pressure it had then (lsdem-run
        // holds it; the study steers it to keep the grains' radial stress at σ₃), at rest as
        // the grains are.
        s.boundaries = {s.boundaries[4], s.boundaries[5]};
        MembraneSpec m = t.consolidatedTube;
        m.name = "membrane";
        m.material = s.boundaries[0].material;
        m.hold = {0, 1};
        Membrane state;
        state.positions = t.consolidatedMembrane;
        state.velocities.assign(state.positions.size(), Vec3::Zero());
        m.state = fs::absolute(fs::path(dir) / "membrane_state.csv").string();
        writeMembraneStateCsv(state, m.state);
        s.membranes = {m};
    }
    if (!o.periodic) {
        s.end.boundary = membrane ? 1 : 5;
        s.end.displacement = 0.5 * strain * size.z();
    }
    s.output.historyPeriod = duration / o.records;
    s.output.vtkPeriod = duration / 20.0;
    // Every run writes its micromechanics (D²min and rotation in the frames); each grain drawn
    // at a quarter of its diameter (about 200 triangles: 10,000 grains in 200 MB a frame).
    s.output.micromechanics = true;
    s.output.frameSpacing = 0.25 * assets->meanDiameter;

    char header[1024];
    std::snprintf(header, sizeof header,
                  "The shearing stage of lsdem-study triaxial (%s, SDP %g mm, VDP %g mm): %lld "
                  "grains consolidated\nto sigma_3 = %g MPa, compressed to %g %% axial strain at "
                  "%g /s with the sides at sigma_3%s.\nThe grains start at rest with no "
                  "contact history. Run with\n  lsdem-run triaxial_shear.toml --out shear\n"
                  "Units: mm, tonne, s, N (MPa). See docs/triaxial.md.",
                  formulationName(run.formulation).c_str(), run.sdp, run.vdp,
                  static_cast<long long>(s.grains.size()),
                  o.confiningStress, 100.0 * strain, run.strainRate,
                  o.periodic   ? " (a periodic cell, no walls)"
                  : membrane ? " (a membrane at the cell pressure consolidation left,\nheld "
                               "constant: the study steers it to keep the grains' radial stress "
                               "at sigma_3)"
                             : "");
    const std::string path = (fs::path(dir) / "triaxial_shear.toml").string();
    writeSceneFile(s, path, header);
    return path;
}

} // namespace lsdem
