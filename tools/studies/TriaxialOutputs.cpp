#include "studies/TriaxialOutputs.h"

#include "lsdem/ls/AtomicFile.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace lsdem {

void writeTriaxialCsv(const TriaxialStudyResult& r, const std::string& path)
{
    std::ostringstream out;
    out.precision(10);
    out << "formulation,sdp,nodes_per_grain,stage,step,time,axial_strain,volumetric_strain,"
           "sigma_x,sigma_y,sigma_z,p,q,q_over_p,friction_angle,void_ratio,coordination,"
           "inertial_number,kinetic_energy,size_x,size_y,size_z\n";
    for (const TriaxialRun& run : r.runs)
        for (const TriaxialRow& row : run.test.rows) {
            const TriaxialState& s = row.state;
            out << formulationName(run.formulation) << ',' << run.sdp << ','
                << run.nodesPerGrain << ',' << (row.stage == 0 ? "consolidation" : "shearing")
                << ',' << row.step << ',' << row.time << ',' << row.axialStrain << ','
                << row.volumetricStrain << ',' << s.stress.x() << ',' << s.stress.y() << ','
                << s.stress.z() << ',' << s.p << ',' << s.q << ','
                << (s.p > 0.0 ? s.q / s.p : 0.0) << ',' << row.frictionAngle << ','
                << s.voidRatio << ',' << s.coordination << ',' << row.inertialNumber << ','
                << row.kinetic << ',' << s.size.x() << ',' << s.size.y() << ',' << s.size.z()
                << '\n';
        }
    writeTextFileAtomically(path, out.str());
}

void writeTriaxialRunsCsv(const TriaxialStudyResult& r, const std::string& path)
{
    std::ostringstream out;
    out.precision(17);  // exact: the spacing and kn extend a study (--lattice-spacing)
    out << "formulation,sdp,vdp,nodes_per_grain,grains,lattice_spacing,stiffness,time_step,stability_limit,strain_rate,"
           "consolidation_steps,consolidated,shear_steps,void_ratio_0,coordination_0,"
           "peak_friction_angle,peak_axial_strain,critical_friction_angle,critical_void_ratio,"
           "max_inertial_number,secant_modulus_50,bake_seconds,run_seconds,ms_per_step\n";
    for (const TriaxialRun& run : r.runs) {
        const TriaxialTestResult& t = run.test;
        out << formulationName(run.formulation) << ',' << run.sdp << ',' << run.vdp << ','
            << run.nodesPerGrain << ',' << r.grains << ',' << r.spacing << ',' << run.stiffness << ',' << run.dt
            << ',' << run.stabilityLimit << ',' << run.strainRate << ',' << t.consolidationSteps << ','
            << (t.consolidatedWithinTolerance ? "yes" : "no") << ',' << t.shearSteps << ','
            << t.consolidated.voidRatio << ',' << t.consolidated.coordination << ','
            << t.peakFrictionAngle << ',' << t.peakAxialStrain << ','
            << t.criticalFrictionAngle << ',' << t.criticalVoidRatio << ','
            << t.maxInertialNumber << ',' << t.secantModulus50 << ',' << run.bakeSeconds << ',' << run.runSeconds << ','
            << run.msPerStep << '\n';
    }
    writeTextFileAtomically(path, out.str());
}

namespace {

/// The runs of @a f at the finest SDP and the one before it (null where there is none).
std::pair<const TriaxialRun*, const TriaxialRun*> twoFinest(const TriaxialStudyResult& r,
                                                            Formulation f)
{
    const TriaxialRun* finest = nullptr;
    const TriaxialRun* next = nullptr;
    for (const TriaxialRun& run : r.runs) {
        if (run.formulation != f) continue;
        if (!finest || run.sdp < finest->sdp) {
            next = finest;
            finest = &run;
        } else if (!next || run.sdp < next->sdp) {
            next = &run;
        }
    }
    return {finest, next};
}

} // namespace

double finestPeakChange(const TriaxialStudyResult& r, Formulation f)
{
    const auto [finest, next] = twoFinest(r, f);
    if (!finest || !next) return std::numeric_limits<double>::quiet_NaN();
    return finest->test.peakFrictionAngle - next->test.peakFrictionAngle;
}

double finestModulusChange(const TriaxialStudyResult& r, Formulation f)
{
    const auto [finest, next] = twoFinest(r, f);
    if (!finest || !next || !(next->test.secantModulus50 > 0.0))
        return std::numeric_limits<double>::quiet_NaN();
    return finest->test.secantModulus50 / next->test.secantModulus50 - 1.0;
}

} // namespace lsdem
