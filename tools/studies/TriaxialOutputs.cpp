#include "studies/TriaxialOutputs.h"

#include "lsdem/core/AtomicFile.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

namespace lsdem {

void writeTriaxialCsv(const TriaxialStudyResult& r, const std::string& path)
{
    std::ostringstream out;
    out.precision(10);
    out << "formulation,sdp,seed,nodes_per_grain,stage,step,time,axial_strain,volumetric_strain,"
           "sigma_x,sigma_y,sigma_z,p,q,q_over_p,friction_angle,void_ratio,coordination,"
           "inertial_number,kinetic_energy,size_x,size_y,size_z,love_weber_x,love_weber_y,"
           "love_weber_z,mechanical_coordination,fabric_anisotropy,nodes_per_contact\n";
    for (const TriaxialRun& run : r.runs)
        for (const TriaxialRow& row : run.test.rows) {
            const TriaxialState& s = row.state;
            out << formulationName(run.formulation) << ',' << run.sdp << ',' << run.seed << ','
                << run.nodesPerGrain << ',' << (row.stage == 0 ? "consolidation" : "shearing")
                << ',' << row.step << ',' << row.time << ',' << row.axialStrain << ','
                << row.volumetricStrain << ',' << s.stress.x() << ',' << s.stress.y() << ','
                << s.stress.z() << ',' << s.p << ',' << s.q << ','
                << (s.p > 0.0 ? s.q / s.p : 0.0) << ',' << row.frictionAngle << ','
                << s.voidRatio << ',' << s.coordination << ',' << row.inertialNumber << ','
                << row.kinetic << ',' << s.size.x() << ',' << s.size.y() << ',' << s.size.z()
                << ',' << s.loveWeberStress.x() << ',' << s.loveWeberStress.y() << ','
                << s.loveWeberStress.z() << ',' << s.mechanicalCoordination << ','
                << s.fabricAnisotropy << ',' << s.nodesPerContact << '\n';
        }
    writeTextFileAtomically(path, out.str());
}

void writeTriaxialRunsCsv(const TriaxialStudyResult& r, const std::string& path)
{
    std::ostringstream out;
    out.precision(17);  // exact: the spacing and kn extend a study (--lattice-spacing)
    out << "formulation,sdp,seed,vdp,nodes_per_grain,grains,lattice_spacing,stiffness,time_step,stability_limit,strain_rate,"
           "consolidation_steps,consolidated,shear_steps,void_ratio_0,coordination_0,"
           "peak_friction_angle,peak_axial_strain,critical_friction_angle,critical_void_ratio,"
           "max_inertial_number,secant_modulus_50,bake_seconds,run_seconds,ms_per_step,path,"
           "unload_reload_modulus\n";
    for (const TriaxialRun& run : r.runs) {
        const TriaxialTestResult& t = run.test;
        out << formulationName(run.formulation) << ',' << run.sdp << ',' << run.seed << ','
            << run.vdp << ','
            << run.nodesPerGrain << ',' << r.grains << ',' << r.spacing << ',' << run.stiffness << ',' << run.dt
            << ',' << run.stabilityLimit << ',' << run.strainRate << ',' << t.consolidationSteps << ','
            << (t.consolidatedWithinTolerance ? "yes" : "no") << ',' << t.shearSteps << ','
            << t.consolidated.voidRatio << ',' << t.consolidated.coordination << ','
            << t.peakFrictionAngle << ',' << t.peakAxialStrain << ','
            << t.criticalFrictionAngle << ',' << t.criticalVoidRatio << ','
            << t.maxInertialNumber << ',' << t.secantModulus50 << ',' << run.bakeSeconds << ',' << run.runSeconds << ','
            << run.msPerStep << ',' << triaxialPathName(run.path) << ','
            << t.unloadReloadModulus << '\n';
    }
    writeTextFileAtomically(path, out.str());
}

std::vector<TriaxialSeedMean> triaxialSeedMeans(const TriaxialStudyResult& r)
{
    std::vector<TriaxialSeedMean> means;
    for (const TriaxialRun& run : r.runs) {
        auto same = [&](const TriaxialSeedMean& m) {
            return m.formulation == run.formulation && m.sdp == run.sdp;
        };
        if (std::find_if(means.begin(), means.end(), same) != means.end()) continue;
        // This formulation and SDP's runs, one per seed, in the study's order.
        std::vector<double> peaks, moduli;
        for (const TriaxialRun& other : r.runs)
            if (other.formulation == run.formulation && other.sdp == run.sdp) {
                peaks.push_back(other.test.peakFrictionAngle);
                moduli.push_back(other.test.secantModulus50);
            }
        TriaxialSeedMean m;
        m.formulation = run.formulation;
        m.sdp = run.sdp;
        m.seeds = int(peaks.size());
        auto meanAndSpread = [](const std::vector<double>& v, double& mean, double& spread) {
            double sum = 0.0;
            for (double x : v) sum += x;
            mean = sum / double(v.size());
            if (v.size() < 2) return;  // spread stays NaN: one sample has none
            double squares = 0.0;
            for (double x : v) squares += (x - mean) * (x - mean);
            spread = std::sqrt(squares / double(v.size() - 1));
        };
        meanAndSpread(peaks, m.peakFrictionAngle, m.peakFrictionAngleSpread);
        meanAndSpread(moduli, m.secantModulus50, m.secantModulus50Spread);
        means.push_back(m);
    }
    return means;
}

namespace {

/// The mean, sample standard deviation and standard error of @a v (spreads NaN below two).
void meanSpreadError(const std::vector<double>& v, double& mean, double& spread, double& error)
{
    double sum = 0.0;
    for (double x : v) sum += x;
    mean = v.empty() ? 0.0 : sum / double(v.size());
    if (v.size() < 2) return;
    double squares = 0.0;
    for (double x : v) squares += (x - mean) * (x - mean);
    spread = std::sqrt(squares / double(v.size() - 1));
    error = spread / std::sqrt(double(v.size()));
}

} // namespace

std::vector<TriaxialPairedChange> triaxialPairedChanges(const TriaxialStudyResult& r)
{
    // Each formulation's SDPs, coarsest first, in the order the runs give them.
    std::vector<std::pair<Formulation, std::vector<double>>> sdps;
    for (const TriaxialRun& run : r.runs) {
        auto it = std::find_if(sdps.begin(), sdps.end(),
                               [&](const auto& f) { return f.first == run.formulation; });
        if (it == sdps.end()) it = sdps.insert(sdps.end(), {run.formulation, {}});
        if (std::find(it->second.begin(), it->second.end(), run.sdp) == it->second.end())
            it->second.push_back(run.sdp);
    }
    std::vector<TriaxialPairedChange> changes;
    for (auto& [formulation, list] : sdps) {
        std::sort(list.begin(), list.end(), std::greater<double>());
        for (size_t k = 0; k + 1 < list.size(); ++k) {
            TriaxialPairedChange c;
            c.formulation = formulation;
            c.coarseSdp = list[k];
            c.fineSdp = list[k + 1];
            std::vector<double> phi, modulus;
            double coarseNodes = 0.0, fineNodes = 0.0;
            for (const TriaxialRun& coarse : r.runs) {
                if (coarse.formulation != formulation || coarse.sdp != c.coarseSdp) continue;
                for (const TriaxialRun& fine : r.runs) {
                    if (fine.formulation != formulation || fine.sdp != c.fineSdp ||
                        fine.seed != coarse.seed)
                        continue;
                    phi.push_back(fine.test.peakFrictionAngle - coarse.test.peakFrictionAngle);
                    modulus.push_back(fine.test.secantModulus50 / coarse.test.secantModulus50 - 1.0);
                    coarseNodes += coarse.test.consolidated.nodesPerContact;
                    fineNodes += fine.test.consolidated.nodesPerContact;
                }
            }
            c.seeds = int(phi.size());
            if (c.seeds == 0) continue;
            c.coarseNodesPerContact = coarseNodes / c.seeds;
            c.fineNodesPerContact = fineNodes / c.seeds;
            meanSpreadError(phi, c.peakFrictionAngle, c.peakFrictionAngleSpread,
                            c.peakFrictionAngleError);
            meanSpreadError(modulus, c.secantModulus50, c.secantModulus50Spread,
                            c.secantModulus50Error);
            changes.push_back(c);
        }
    }
    return changes;
}

void writeTriaxialConvergenceCsv(const TriaxialStudyResult& r, const std::string& path)
{
    std::ostringstream out;
    out.precision(17);
    out << "formulation,coarse_sdp,fine_sdp,seeds,coarse_nodes_per_contact,"
           "fine_nodes_per_contact,peak_friction_angle_change,peak_friction_angle_change_sd,"
           "peak_friction_angle_change_se,secant_modulus_50_change,secant_modulus_50_change_sd,"
           "secant_modulus_50_change_se\n";
    for (const TriaxialPairedChange& c : triaxialPairedChanges(r))
        out << formulationName(c.formulation) << ',' << c.coarseSdp << ',' << c.fineSdp << ','
            << c.seeds << ',' << c.coarseNodesPerContact << ',' << c.fineNodesPerContact << ','
            << c.peakFrictionAngle << ',' << c.peakFrictionAngleSpread << ','
            << c.peakFrictionAngleError << ',' << c.secantModulus50 << ','
            << c.secantModulus50Spread << ',' << c.secantModulus50Error << '\n';
    writeTextFileAtomically(path, out.str());
}

namespace {

/// The means of @a f at the finest SDP and the one before it (null where there is none).
std::pair<const TriaxialSeedMean*, const TriaxialSeedMean*>
twoFinest(const std::vector<TriaxialSeedMean>& means, Formulation f)
{
    const TriaxialSeedMean* finest = nullptr;
    const TriaxialSeedMean* next = nullptr;
    for (const TriaxialSeedMean& m : means) {
        if (m.formulation != f) continue;
        if (!finest || m.sdp < finest->sdp) {
            next = finest;
            finest = &m;
        } else if (!next || m.sdp < next->sdp) {
            next = &m;
        }
    }
    return {finest, next};
}

} // namespace

double finestPeakChange(const TriaxialStudyResult& r, Formulation f)
{
    const std::vector<TriaxialSeedMean> means = triaxialSeedMeans(r);
    const auto [finest, next] = twoFinest(means, f);
    if (!finest || !next) return std::numeric_limits<double>::quiet_NaN();
    return finest->peakFrictionAngle - next->peakFrictionAngle;
}

double finestModulusChange(const TriaxialStudyResult& r, Formulation f)
{
    const std::vector<TriaxialSeedMean> means = triaxialSeedMeans(r);
    const auto [finest, next] = twoFinest(means, f);
    if (!finest || !next || !(next->secantModulus50 > 0.0))
        return std::numeric_limits<double>::quiet_NaN();
    return finest->secantModulus50 / next->secantModulus50 - 1.0;
}

} // namespace lsdem
