/// @file TriaxialOptions.h
/// @brief The options of the triaxial study (`lsdem-study triaxial`): the sample (grain meshes,
///        count, seeds), the resolutions (one VDP, several SDPs), the contact law, and the test
///        (confining stress, inertial number, axial strain). Units: mm, tonne, s, N (stresses in
///        N/mm² = MPa).
#pragma once

#include "studies/TriaxialPath.h"

#include "lsdem/contact/ContactModel.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lsdem {

struct TriaxialOptions
{
    /// Grain meshes: files, or folders whose .obj/.stl/.ply/.off files are all used.
    std::vector<std::string> meshes = {"assets/meshes/sand"};
    long long grains = 1000;       ///< grains in the sample, the meshes used in turn
    /// Spacing of the starting lattice, mm (0: 2.2 times the largest bounding radius at the
    /// coarsest SDP). Give it to extend a study with finer SDPs on the same lattice.
    double latticeSpacing = 0.0;
    /// The starting lattice's height over its width (1: as near a cube as the count allows;
    /// 2: a tall sample, room for a shear band across it).
    double heightRatio = 1.0;
    /// The axial strain the shear scene for lsdem-run goes to (0: --axial-strain's), so a study
    /// can consolidate a large sample, shear it a little, and leave the rest to lsdem-run.
    double sceneStrain = 0.0;
    /// Samples, one per seed: which mesh and orientation each grain gets (each >= 0, no two
    /// alike). Every formulation and SDP is run on each; the summary takes their means.
    std::vector<long long> seeds = {1};
    double vdp = 0.03;             ///< voxel size, mm (the same for every run)
    std::vector<double> sdps = {0.1, 0.07, 0.05};  ///< node spacings, mm, coarsest first
    std::vector<Formulation> formulations = {Formulation::Adapted, Formulation::Original};
    double density = 2.65e-9;      ///< tonne/mm³ (quartz)
    double knStar = 1e3;           ///< adapted kn*, N/mm³
    /// original kn, N/mm (0: kn* times the mean node area at the coarsest SDP, so both
    /// formulations are the same law there and part as the nodes are refined)
    double knOriginal = 0.0;
    double shearRatio = 0.5;       ///< ks/kn (ks*/kn* for adapted)
    double friction = 0.5;         ///< grain–grain μ while shearing
    double consolidationFriction = 0.0;  ///< grain–grain μ while consolidating (0: dense)
    double wallFriction = 0.0;     ///< grain–wall μ (smooth platens)
    double globalDamping = 0.2;
    double confiningStress = 0.1;  ///< σ₃, MPa (100 kPa)
    double inertialNumber = 1e-3;  ///< I = ε̇·d·sqrt(ρ/σ₃): sets the axial strain rate
    double maxAxialStrain = 0.2;   ///< the path's end (its amplitude for cycles)
    TriaxialPath path = TriaxialPath::Compression;  ///< the loading path after consolidation
    /// What bounds the sample: six servo walls, or a periodic cell (no walls: its axes are
    /// strained and stress-controlled as the walls would be), or (membrane) a rubber membrane
    /// round a cylinder cut from the sample consolidated between walls, between the top and
    /// bottom walls as platens (TriaxialMembrane.h).
    bool periodic = false;
    bool membrane = false;
    double membraneYoungs = 1.4;     ///< E of the membrane's rubber, MPa (latex)
    /// Its thickness, mm; 0: half the grains' mean diameter (TriaxialMembrane.h says why).
    double membraneThickness = 0.0;
    double b = 0.5;                ///< true triaxial: (σ₂ − σ₃)/(σ₁ − σ₃)
    double unloadStrain = 0.0;     ///< unload–reload: where unloading starts (0: half the end)
    int cycles = 2;                ///< cyclic: cycles of ±maxAxialStrain
    double stressTolerance = 0.02; ///< consolidated when every |σ_i/σ₃ − 1| is below this
    int records = 200;             ///< rows written over the shearing
    long long threads = 0;
    std::string outDir = "results/triaxial";
    bool plots = true, quiet = false;
    bool estimateOnly = false;     ///< plan the runs, print their cost (TriaxialCost.h), stop
};

/// @throw Error naming the option and the fix for anything out of range, or for meshes that
///        triaxialMeshFiles refuses.
void checkTriaxialOptions(const TriaxialOptions& o);

/// The mesh files of o.meshes (folders expanded, sorted by name). @throw Error if a path does
/// not exist, nothing is found, or a file is given twice (however spelt).
std::vector<std::string> triaxialMeshFiles(const TriaxialOptions& o);

} // namespace lsdem
