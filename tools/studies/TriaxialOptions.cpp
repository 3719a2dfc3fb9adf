#include "studies/TriaxialOptions.h"

#include "studies/FormulationList.h"
#include "studies/StudyLimits.h"

#include "common/CommandLine.h"
#include "lsdem/core/NumberText.h"

#include "lsdem/core/Error.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

namespace lsdem {

namespace {

void requirePositive(double v, const std::string& option, const std::string& fix = "")
{
    if (!(v > 0.0 && std::isfinite(v)))
        throw Error("", option + " must be positive and finite, got " + roundedText(v), fix);
}

void requireFraction(double v, const std::string& option, double upper)
{
    if (!(v >= 0.0 && v < upper))
        throw Error("", option + " must be in [0, " + roundedText(upper) + "), got " +
                            roundedText(v));
}

bool isMeshFile(const std::filesystem::path& p)
{
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".obj" || ext == ".stl" || ext == ".ply" || ext == ".off";
}

/// The sample: its meshes, its grain count, its seeds (each one sample).
void checkTriaxialSample(const TriaxialOptions& o)
{
    if (o.meshes.empty()) throw Error("", "--meshes needs at least one mesh file or folder");
    if (o.grains < 8)
        throw Error("", "--grains must be at least 8, got " + std::to_string(o.grains),
                    "a triaxial sample needs grains in every direction; 1000 is the default");
    // A scene's limit, as lsdem-pack's (SceneSections.h): checked before any memory is taken.
    constexpr long long kMaxGrains = 1000000;
    if (o.grains > kMaxGrains)
        throw Error("", "--grains " + std::to_string(o.grains) + " is over the limit of a scene (" +
                            std::to_string(kMaxGrains) + ")",
                    "give at most --grains " + std::to_string(kMaxGrains) +
                        " (1000 is the default)");
    if (o.seeds.empty()) throw Error("", "--seed needs at least one seed", "e.g. --seed 1 2 3");
    for (size_t i = 0; i < o.seeds.size(); ++i) {
        if (o.seeds[i] < 0)
            throw Error("", "--seed wants numbers >= 0, got " + std::to_string(o.seeds[i]));
        for (size_t j = 0; j < i; ++j)
            if (o.seeds[j] == o.seeds[i])
                throw Error("", "--seed " + std::to_string(o.seeds[i]) + " is given twice",
                            "give each seed once: each is one sample");
    }
}

/// The voxel size and the node spacings, coarsest first.
void checkTriaxialResolutions(const TriaxialOptions& o)
{
    requirePositive(o.vdp, "--vdp", "e.g. --vdp 0.03 (mm)");
    if (o.sdps.empty()) throw Error("", "--sdps needs at least one node spacing");
    for (double s : o.sdps) requirePositive(s, "--sdps", "e.g. --sdps 0.1 0.07 0.05 (mm)");
    for (size_t i = 1; i < o.sdps.size(); ++i)
        if (!(o.sdps[i] < o.sdps[i - 1]))
            throw Error("", "--sdps must be decreasing (coarsest first), got " +
                                roundedText(o.sdps[i - 1]) + " then " +
                                roundedText(o.sdps[i]),
                        "e.g. --sdps 0.1 0.07 0.05");
}

/// The laws: the study needs shear springs at every node and a traction that kn* sets.
void checkTriaxialFormulations(const TriaxialOptions& o)
{
    checkFormulationList(o.formulations);
    auto runnable = [](Formulation f) {
        return normalModel(f).perNodeForces() && normalModel(f).tractionStiffness(1.0, 1.0);
    };
    for (Formulation f : o.formulations)
        if (!runnable(f)) {
            std::string names, list;
            for (Formulation g : allFormulations())
                if (runnable(g)) {
                    names += (names.empty() ? "" : " and ") + formulationName(g);
                    list += " " + formulationName(g);
                }
            throw Error("", "the triaxial study runs " + names +
                                " (a shear spring at every node), not " + formulationName(f),
                        "--formulation" + list);
        }
}

/// The grains' material and contacts: density, stiffnesses, frictions, damping.
void checkTriaxialMaterial(const TriaxialOptions& o)
{
    requirePositive(o.density, "--density", "e.g. 2.65e-9 tonne/mm³ (quartz)");
    if (!(o.sceneStrain >= 0.0 && o.sceneStrain < 0.5))
        throw Error("", "--scene-strain must be in [0, 0.5), got " + roundedText(o.sceneStrain),
                    "0 takes --axial-strain's");
    const bool writesScene =
        o.path == TriaxialPath::Compression || o.path == TriaxialPath::Extension;
    if (o.sceneStrain > 0.0 && !writesScene)
        throw Error("", "--scene-strain is for the shear scene, which only drained compression "
                        "or extension writes",
                    "drop --scene-strain");
    if (!(o.heightRatio >= 0.25 && o.heightRatio <= 4.0))
        throw Error("", "--height-ratio must be from 0.25 to 4, got " + roundedText(o.heightRatio),
                    "1 is a cube, 2 a sample twice as tall as wide");
    requirePositive(o.knStar, "--kn-star", "e.g. 1e3 N/mm³");
    if (!(o.latticeSpacing >= 0.0 && std::isfinite(o.latticeSpacing)))
        throw Error("", "--lattice-spacing must be zero (derived) or positive, got " +
                            roundedText(o.latticeSpacing));
    if (!(o.knOriginal >= 0.0 && std::isfinite(o.knOriginal)))
        throw Error("", "--kn-original must be zero (derived) or positive, got " +
                            roundedText(o.knOriginal));
    requirePositive(o.shearRatio, "--shear-ratio", "0.5 is the default");
    for (const auto& [value, option] : {std::pair{o.friction, "--friction"},
                                        std::pair{o.consolidationFriction, "--consolidation-friction"},
                                        std::pair{o.wallFriction, "--wall-friction"}})
        if (!(value >= 0.0 && std::isfinite(value)))
            throw Error("", std::string(option) + " must be zero or positive, got " +
                                roundedText(value));
    requireFraction(o.globalDamping, "--damping", 1.0);
}

/// The loading: confinement, rate, the path's strains and cycles, the servo's tolerance and
/// the records.
void checkTriaxialLoading(const TriaxialOptions& o)
{
    requirePositive(o.confiningStress, "--confining-stress",
                    "a compressive stress in MPa, e.g. 0.1 for 100 kPa");
    requirePositive(o.inertialNumber, "--inertial-number", "1e-3 is quasi-static");
    if (!(o.maxAxialStrain > 0.0 && o.maxAxialStrain < 0.5))
        throw Error("", "--axial-strain must be in (0, 0.5), got " +
                            roundedText(o.maxAxialStrain), "0.2 is the default");
    if (!(o.b >= 0.0 && o.b <= 1.0))
        throw Error("", "--b must be in [0, 1], got " + roundedText(o.b),
                    "b = (σ₂ − σ₃)/(σ₁ − σ₃): 0 is compression, 1 extension-like, 0.5 between");
    if (!(o.unloadStrain >= 0.0 && o.unloadStrain < o.maxAxialStrain))
        throw Error("", "--unload-strain must be in [0, --axial-strain), got " +
                            roundedText(o.unloadStrain),
                    "0 unloads at half --axial-strain");
    if (o.cycles < 1 || o.cycles > 1000)
        throw Error("", "--cycles must be from 1 to 1000, got " + std::to_string(o.cycles));
    if (!(o.stressTolerance > 0.0 && o.stressTolerance < 0.5))
        throw Error("", "--stress-tolerance must be in (0, 0.5), got " +
                            roundedText(o.stressTolerance));
    if (o.records < 2) throw Error("", "--records must be at least 2");
    if (o.membrane && o.path == TriaxialPath::TrueTriaxial)
        throw Error("", "--boundary membrane cannot follow --path true-triaxial (a membrane's "
                        "cylinder has one lateral stress, so σ₂ cannot differ from σ₃)",
                    "use walls or periodic for this path");
    requirePositive(o.membraneYoungs, "--membrane-youngs", "latex is about 1.4 MPa");
    if (!(o.membraneThickness >= 0.0 && std::isfinite(o.membraneThickness)))
        throw Error("", "--membrane-thickness must be zero (the laboratory's proportion) or "
                        "positive, got " + roundedText(o.membraneThickness));
}

} // namespace

// The checks in groups (in their old order, so the first problem found is still the one
// reported).
void checkTriaxialOptions(const TriaxialOptions& o)
{
    checkTriaxialSample(o);
    checkTriaxialResolutions(o);
    checkTriaxialFormulations(o);
    checkTriaxialMaterial(o);
    checkTriaxialLoading(o);
    cli::checkThreads(o.threads);
    triaxialMeshFiles(o);  // a missing or twice-given mesh, before the output folder is made
}

std::vector<std::string> triaxialMeshFiles(const TriaxialOptions& o)
{
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    // A mesh given twice (a folder and one of its files too) would be two meshes of the sample
    // and two assets of one name in the shear scene: each file's canonical path and the
    // --meshes argument that gave it.
    std::map<fs::path, std::string> given;
    auto add = [&](const std::string& file, const std::string& argument) {
        std::error_code unreadable;  // the bake says what is wrong with it
        const fs::path same = fs::canonical(file, unreadable);
        if (!unreadable) {
            const auto [first, isNew] = given.emplace(same, argument);
            if (!isNew)
                throw Error(file, "--meshes gives this mesh twice: as " + first->second +
                                      " and as " + argument,
                            "give each mesh once (a folder gives all its mesh files)");
        }
        files.push_back(file);
    };
    for (const std::string& path : o.meshes) {
        std::error_code ec;
        if (fs::is_directory(path, ec)) {
            std::vector<std::string> inFolder;
            for (const fs::directory_entry& e : fs::directory_iterator(path, ec))
                if (e.is_regular_file() && isMeshFile(e.path())) inFolder.push_back(e.path().string());
            if (inFolder.empty())
                throw Error(path, "no mesh files (.obj, .stl, .ply, .off) in this folder",
                            "give --meshes a folder of grain meshes, or the files themselves");
            std::sort(inFolder.begin(), inFolder.end());
            for (const std::string& file : inFolder) add(file, "part of the folder " + path);
        } else if (fs::is_regular_file(path, ec)) {
            add(path, path);
        } else {
            throw Error(path, "no such mesh file or folder",
                        "run from lsdem's folder (the default is assets/meshes/sand), or give "
                        "--meshes");
        }
    }
    return files;
}

} // namespace lsdem
