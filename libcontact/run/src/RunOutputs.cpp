#include "lsdem/run/RunOutputs.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/CsvText.h"
#include "lsdem/simulation/GhostDecomposition.h"
#include "lsdem/simulation/Membrane.h"
#include "lsdem/simulation/Micromechanics.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace lsdem {

namespace {

const std::string kBoundaryHistoryPrefix = "boundary_", kMembraneHistoryPrefix = "membrane_",
                  kHistorySuffix = ".csv";

/// The first lines of the text outputs (isRunTextOutput knows a run's files by them).
const std::string kEnergyHeader =
    "step,time,kinetic,elastic,potential,boundary_work,dissipated,contact_nodes,"
    "dissipated_friction,dissipated_dashpot,dissipated_global_damping";
const std::string kBoundaryHeader = "step,time,ux,uy,uz,fx,fy,fz";
const std::string kServoBoundaryHeader =
    "step,time,ux,uy,uz,fx,fy,fz,px,py,pz,area,stress,target_stress,speed";
const std::string kMembraneHeader =
    "step,time,pressure,volume,strain_energy,kinetic,grain_fx,grain_fy,grain_fz,"
    "grain_force_magnitude_sum";
const std::string kCellHeader =
    "step,time,size_x,size_y,size_z,strain_rate_x,strain_rate_y,strain_rate_z,stress_x,"
    "stress_y,stress_z";
const std::string kGrainsHeader = "name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,moved";
const std::string kMicromechanicsHeader =
    "step,time,mxx,mxy,mxz,myx,myy,myz,mzx,mzy,mzz,fxx,fyy,fzz,fxy,fxz,fyz,fabric_anisotropy,"
    "bxx,byy,bzz,bxy,bxz,byz,branch_anisotropy,nxx,nyy,nzz,nxy,nxz,nyz,force_anisotropy,"
    "mean_normal_force,grain_contacts,boundary_contacts,free_grains,rattlers,"
    "mechanical_coordination";

void appendNumber(std::string& line, double v)
{
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    if (!line.empty() && line.back() != ',') line += ',';
    line += buffer;
}

std::string rowsToCsv(const std::string& header, const std::vector<std::vector<double>>& rows)
{
    std::string text = header + "\n";
    for (const auto& row : rows) {
        std::string line;
        for (double v : row) appendNumber(line, v);
        text += line + "\n";
    }
    return text;
}

/// A membrane's history row now (the header kMembraneHeader names its columns).
std::vector<double> membraneRow(const World& w, const Membrane& m)
{
    Vec3 push = Vec3::Zero();
    double magnitudes = 0.0;
    for (const Vec3& f : m.grainForces) {
        push += f;
        magnitudes += f.norm();
    }
    return {static_cast<double>(w.step), w.time, m.pressure, enclosedVolume(m), m.strainEnergy,
            membraneKineticEnergy(m), push.x(), push.y(), push.z(), magnitudes};
}

/// "<prefix><name>.csv", with characters unsafe in a file name as '_'.
std::string historyFileName(const std::string& prefix, const std::string& name)
{
    std::string safe = name;
    for (char& c : safe)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    return prefix + safe + kHistorySuffix;
}

/// Whether @a fileName is "<prefix><something>.csv".
bool isHistoryFileName(const std::string& prefix, const std::string& fileName)
{
    const size_t affixes = prefix.size() + kHistorySuffix.size();
    return fileName.size() > affixes && fileName.rfind(prefix, 0) == 0 &&
           fileName.compare(fileName.size() - kHistorySuffix.size(), kHistorySuffix.size(),
                            kHistorySuffix) == 0;
}

} // namespace

void recordHistoryRow(const Simulation& sim, RunRecord& record)
{
    const World& w = sim.world();
    const Energies e = sim.energies();
    record.energyRows.push_back({static_cast<double>(w.step), w.time, e.kinetic, e.elastic,
                                 e.potential, e.boundaryWork, e.dissipated,
                                 static_cast<double>(sim.contactNodes()), e.friction,
                                 e.dashpot, e.globalDamping});
    record.boundaryRows.resize(w.boundaries.size());
    for (size_t b = 0; b < w.boundaries.size(); ++b) {
        const Boundary& bd = w.boundaries[b];
        std::vector<double> row = {static_cast<double>(w.step), w.time,
                                   bd.displacement.x(),         bd.displacement.y(),
                                   bd.displacement.z(),         bd.force.x(),
                                   bd.force.y(),                bd.force.z()};
        if (bd.servo.active()) {
            const double area = servoArea(w, bd);
            const Vec3 point = bd.referencePoint();
            row.insert(row.end(), {point.x(), point.y(), point.z(), area,
                                   normalStress(bd, area), bd.servo.targetStress,
                                   bd.velocity.dot(bd.plane.normal)});
        }
        record.boundaryRows[b].push_back(std::move(row));
    }
    record.membraneRows.resize(w.membranes.size());
    for (size_t k = 0; k < w.membranes.size(); ++k)
        record.membraneRows[k].push_back(membraneRow(w, w.membranes[k]));
    if (w.periodic.active()) {
        const PeriodicCell& c = w.periodic;
        record.cellRows.push_back({static_cast<double>(w.step), w.time, c.size.x(), c.size.y(),
                                   c.size.z(), c.strainRate.x(), c.strainRate.y(),
                                   c.strainRate.z(), c.stress.x(), c.stress.y(), c.stress.z()});
    }
    if (record.micromechanics) record.micromechanicsRows.push_back(micromechanicsRow(sim));
}

std::vector<double> micromechanicsRow(const Simulation& sim)
{
    // Split by space, rank 0 sums the whole simulation in one process's order (so the row has
    // its bytes) and every rank takes its row.
    const GhostDecomposition* split = sim.ghosts();
    World gathered;
    if (split) gathered = sim.wholeWorld();
    const std::vector<ContactRecord> records = sim.wholeContactRecords();
    const World& w = split ? gathered : sim.world();
    std::vector<double> row;
    if (!split || split->rank() == 0) {
        const Micromechanics m = micromechanicsOf(w, records);
        row = {static_cast<double>(w.step), w.time};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) row.push_back(m.stressMoment(i, j));
        for (const auto& [fabric, anisotropy] :
             {std::make_pair(&m.fabric, m.fabricAnisotropy),
              std::make_pair(&m.branchFabric, m.branchAnisotropy),
              std::make_pair(&m.forceFabric, m.forceAnisotropy)}) {
            const Mat3& f = *fabric;
            row.insert(row.end(), {f(0, 0), f(1, 1), f(2, 2), f(0, 1), f(0, 2), f(1, 2), anisotropy});
        }
        row.insert(row.end(), {m.meanNormalForce, static_cast<double>(m.grainContacts),
                               static_cast<double>(m.boundaryContacts),
                               static_cast<double>(m.freeGrains), static_cast<double>(m.rattlers),
                               m.mechanicalCoordination});
    }
    return sim.numbersFromRankZero(row);
}

std::string boundaryHistoryFileName(const std::string& name)
{
    return historyFileName(kBoundaryHistoryPrefix, name);
}

std::string membraneHistoryFileName(const std::string& name)
{
    return historyFileName(kMembraneHistoryPrefix, name);
}

bool isRunTextOutput(const std::string& path)
{
    std::ifstream in(path);
    std::string first;
    if (!std::getline(in, first)) return false;
    return first == kEnergyHeader || first == kGrainsHeader || first == kBoundaryHeader ||
           first == kServoBoundaryHeader || first == kMicromechanicsHeader ||
           first == kMembraneHeader || first == kCellHeader;
}

bool isBoundaryHistoryFileName(const std::string& fileName)
{
    return isHistoryFileName(kBoundaryHistoryPrefix, fileName);
}

bool isMembraneHistoryFileName(const std::string& fileName)
{
    return isHistoryFileName(kMembraneHistoryPrefix, fileName);
}

void writeHistoryFiles(const std::string& directory, const World& world,
                       const RunRecord& record)
{
    const std::filesystem::path dir(directory);
    writeTextFileAtomically(
        (dir / kEnergyFileName).string(),
        rowsToCsv(kEnergyHeader, record.energyRows));
    for (size_t b = 0; b < world.boundaries.size() && b < record.boundaryRows.size(); ++b)
        writeTextFileAtomically(
            (dir / boundaryHistoryFileName(world.boundaries[b].name)).string(),
            rowsToCsv(world.boundaries[b].servo.active() ? kServoBoundaryHeader : kBoundaryHeader,
                      record.boundaryRows[b]));
    for (size_t k = 0; k < world.membranes.size() && k < record.membraneRows.size(); ++k)
        writeTextFileAtomically((dir / membraneHistoryFileName(world.membranes[k].name)).string(),
                                rowsToCsv(kMembraneHeader, record.membraneRows[k]));
    if (world.periodic.active())
        writeTextFileAtomically((dir / kCellFileName).string(),
                                rowsToCsv(kCellHeader, record.cellRows));
    if (record.micromechanics)
        writeTextFileAtomically((dir / kMicromechanicsFileName).string(),
                                rowsToCsv(kMicromechanicsHeader, record.micromechanicsRows));
}

void writeGrainsFile(const std::string& path, const World& world,
                     const std::vector<Vec3>& initialPositions)
{
    std::string text = kGrainsHeader + "\n";
    for (size_t i = 0; i < world.grains.size(); ++i) {
        const Grain& g = world.grains[i];
        const RigidPose& p = g.body.pose;
        const Vec3 omega = g.angularVelocity();
        std::string line = csvField(g.name) + ",";  // the name column even when it is empty
        for (double v : {p.position.x(), p.position.y(), p.position.z(), p.orientation.w(),
                         p.orientation.x(), p.orientation.y(), p.orientation.z(),
                         g.body.velocity.x(), g.body.velocity.y(), g.body.velocity.z(),
                         omega.x(), omega.y(), omega.z(),
                         (g.unwrappedPosition() - initialPositions[i]).norm()})
            appendNumber(line, v);
        text += line + "\n";
    }
    writeTextFileAtomically(path, text);
}

} // namespace lsdem
