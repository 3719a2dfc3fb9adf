/// @file VtkSeries.cpp
/// @brief ParaView output: VTK XML unstructured grids (`.vtu`) with their arrays in one raw
///        appended binary block, and the `.pvd` collection listing them with their times.
#include "lsdem/run/VtkSeries.h"

#include "lsdem/core/AtomicFile.h"
#include "lsdem/core/Error.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace lsdem {

namespace {

constexpr std::uint8_t kVtkVertex = 1;
constexpr std::uint8_t kVtkTriangle = 5;

/// Append @a value least significant byte first: the files declare byte_order="LittleEndian"
/// whatever the machine writing them is.
void appendLittleEndian(std::string& bytes, std::uint64_t value, size_t size)
{
    for (size_t i = 0; i < size; ++i) bytes.push_back(static_cast<char>((value >> (8 * i)) & 0xffu));
}

// One overload per element type written, so the stored width always matches the tag's type.
void appendValue(std::string& bytes, double v)
{
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);  // the IEEE-754 bits, so values round-trip exactly
    appendLittleEndian(bytes, bits, 8);
}
void appendValue(std::string& bytes, std::int32_t v)
{
    appendLittleEndian(bytes, static_cast<std::uint32_t>(v), 4);
}
void appendValue(std::string& bytes, std::int64_t v)
{
    appendLittleEndian(bytes, static_cast<std::uint64_t>(v), 8);
}
void appendValue(std::string& bytes, std::uint8_t v) { bytes.push_back(static_cast<char>(v)); }

/// The name VTK gives each element type in a DataArray's `type` attribute.
template <typename T> const char* vtkTypeName();
template <> const char* vtkTypeName<double>() { return "Float64"; }
template <> const char* vtkTypeName<std::int32_t>() { return "Int32"; }
template <> const char* vtkTypeName<std::int64_t>() { return "Int64"; }
template <> const char* vtkTypeName<std::uint8_t>() { return "UInt8"; }

/// Make @a text safe inside a double-quoted XML attribute (a base name may hold '&' or '"').
std::string xmlEscape(const std::string& text)
{
    std::string out;
    for (char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

/// One `.vtu` being assembled: the DataArray tags of each section and the appended block they
/// point into. Each array there is its UInt64 byte count followed by its values; a tag's offset
/// is where that count starts, counted from just after the block's leading '_'.
class UnstructuredGridFile
{
public:
    enum Section { PointData, CellData, Points, Cells, SectionCount };

    template <typename T>
    void addArray(Section section, const std::string& name, int components,
                  const std::vector<T>& values)
    {
        mTags[section] += "        <DataArray type=\"" + std::string(vtkTypeName<T>()) +
                          "\" Name=\"" + name + "\" NumberOfComponents=\"" +
                          std::to_string(components) + "\" format=\"appended\" offset=\"" +
                          std::to_string(mData.size()) + "\"/>\n";
        appendLittleEndian(mData, static_cast<std::uint64_t>(values.size() * sizeof(T)), 8);
        for (const T& v : values) appendValue(mData, v);
    }

    /// Extra attributes of a section's opening tag, e.g. `Vectors="force"`: ParaView's glyphs
    /// and colouring start from these active arrays.
    void setSectionAttributes(Section section, const std::string& attributes)
    {
        mAttributes[section] = attributes;
    }

    std::string contents(size_t pointCount, size_t cellCount) const
    {
        static const char* const names[SectionCount] = {"PointData", "CellData", "Points", "Cells"};
        std::string xml = "<?xml version=\"1.0\"?>\n"
                          "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                          "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                          "  <UnstructuredGrid>\n"
                          "    <Piece NumberOfPoints=\"" + std::to_string(pointCount) +
                          "\" NumberOfCells=\"" + std::to_string(cellCount) + "\">\n";
        for (int s = 0; s < SectionCount; ++s) {
            const std::string attributes = mAttributes[s].empty() ? "" : " " + mAttributes[s];
            xml += "      <" + std::string(names[s]) + attributes + ">\n" + mTags[s] +
                   "      </" + names[s] + ">\n";
        }
        xml += "    </Piece>\n"
               "  </UnstructuredGrid>\n"
               "  <AppendedData encoding=\"raw\">\n"
               "   _";
        xml += mData;
        xml += "\n  </AppendedData>\n</VTKFile>\n";
        return xml;
    }

private:
    std::string mTags[SectionCount];
    std::string mAttributes[SectionCount];
    std::string mData;
};

/// Flatten 3-vectors into x0 y0 z0 x1 ... as VTK stores 3-component arrays.
void appendXyz(std::vector<double>& out, const Vec3& v)
{
    out.push_back(v.x());
    out.push_back(v.y());
    out.push_back(v.z());
}

/// Whether every one of @a grains (at least one) carries its measures.
bool allMeasured(const std::vector<VtkGrain>& grains)
{
    return !grains.empty() && std::all_of(grains.begin(), grains.end(), [](const VtkGrain& g) {
        return g.measures != nullptr;
    });
}

/// A grid's points and cells (its connectivity, offsets and cell types), after its data.
void addGeometry(UnstructuredGridFile& file, const std::vector<double>& points,
                 const std::vector<std::int64_t>& connectivity,
                 const std::vector<std::int64_t>& offsets, const std::vector<std::uint8_t>& types)
{
    file.addArray(UnstructuredGridFile::Points, "Points", 3, points);
    file.addArray(UnstructuredGridFile::Cells, "connectivity", 1, connectivity);
    file.addArray(UnstructuredGridFile::Cells, "offsets", 1, offsets);
    file.addArray(UnstructuredGridFile::Cells, "types", 1, types);
}

/// Every grain's surface triangles in world coordinates, each vertex carrying its rigid-body
/// velocity (and, @a measured, its grain's measures) and each triangle the id of its grain.
std::string grainsFile(const std::vector<VtkGrain>& grains, bool measured)
{
    std::vector<double> displacements, rotations, d2mins, stresses;
    std::vector<double> points, velocities;
    std::vector<std::int64_t> connectivity, offsets;
    std::vector<std::int32_t> grainIds;
    for (const VtkGrain& grain : grains) {
        if (!grain.surface) continue;  // nothing to draw
        const std::int64_t first = static_cast<std::int64_t>(points.size() / 3);
        for (const Vec3& local : grain.surface->vertices) {
            const Vec3 x = grain.pose.toWorld(local);
            appendXyz(points, x);
            appendXyz(velocities,
                      grain.velocity + grain.angularVelocity.cross(x - grain.pose.position));
            if (!measured) continue;
            const VtkGrainMeasures& m = *grain.measures;
            appendXyz(displacements, m.displacement);
            rotations.push_back(m.rotation);
            d2mins.push_back(m.d2min);
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) stresses.push_back(m.stress(i, j));
        }
        for (const auto& triangle : grain.surface->triangles) {
            for (int corner : triangle) connectivity.push_back(first + corner);
            offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
            grainIds.push_back(grain.id);
        }
    }
    const std::vector<std::uint8_t> types(offsets.size(), kVtkTriangle);

    UnstructuredGridFile file;
    file.setSectionAttributes(UnstructuredGridFile::PointData, "Vectors=\"velocity\"");
    file.setSectionAttributes(UnstructuredGridFile::CellData, "Scalars=\"grain\"");
    file.addArray(UnstructuredGridFile::PointData, "velocity", 3, velocities);
    if (measured) {
        file.addArray(UnstructuredGridFile::PointData, "displacement", 3, displacements);
        file.addArray(UnstructuredGridFile::PointData, "rotation", 1, rotations);
        file.addArray(UnstructuredGridFile::PointData, "d2min", 1, d2mins);
        file.addArray(UnstructuredGridFile::PointData, "stress", 9, stresses);
    }
    file.addArray(UnstructuredGridFile::CellData, "grain", 1, grainIds);
    addGeometry(file, points, connectivity, offsets, types);
    return file.contents(points.size() / 3, offsets.size());
}

/// The contact forces as points (one vertex cell each, so every filter sees them) with their
/// force vector and the grain it acts on. No forces still makes a valid, empty grid.
std::string contactsFile(const std::vector<VtkForcePoint>& forces)
{
    std::vector<double> points, forceVectors;
    std::vector<std::int32_t> grainIds;
    std::vector<std::int64_t> connectivity, offsets;
    for (const VtkForcePoint& f : forces) {
        appendXyz(points, f.point);
        appendXyz(forceVectors, f.force);
        grainIds.push_back(f.grain);
        connectivity.push_back(static_cast<std::int64_t>(connectivity.size()));
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    }
    const std::vector<std::uint8_t> types(forces.size(), kVtkVertex);

    UnstructuredGridFile file;
    file.setSectionAttributes(UnstructuredGridFile::PointData,
                              "Vectors=\"force\" Scalars=\"grain\"");
    file.addArray(UnstructuredGridFile::PointData, "force", 3, forceVectors);
    file.addArray(UnstructuredGridFile::PointData, "grain", 1, grainIds);
    addGeometry(file, points, connectivity, offsets, types);
    return file.contents(forces.size(), forces.size());
}

/// Every membrane's triangles in one grid (their vertices numbered on from the previous
/// membrane's), each vertex with its velocity, the grains' push on it and whether it is held,
/// each triangle with its membrane's index.
std::string membranesFile(const std::vector<Membrane>& membranes)
{
    std::vector<double> points, velocities, grainForces;
    std::vector<std::int32_t> held, membraneIds;
    std::vector<std::int64_t> connectivity, offsets;
    for (size_t k = 0; k < membranes.size(); ++k) {
        const Membrane& m = membranes[k];
        const std::int64_t first = static_cast<std::int64_t>(points.size() / 3);
        for (size_t v = 0; v < m.positions.size(); ++v) {
            appendXyz(points, m.positions[v]);
            appendXyz(velocities, v < m.velocities.size() ? m.velocities[v] : Vec3::Zero());
            // Outside a Simulation nothing has filled the grains' push: none, then.
            appendXyz(grainForces, v < m.grainForces.size() ? m.grainForces[v] : Vec3::Zero());
            held.push_back(v < m.heldBy.size() && m.heldBy[v] >= 0 ? 1 : 0);
        }
        for (const MembraneTriangle& t : m.triangles) {
            for (int corner : t.vertices) connectivity.push_back(first + corner);
            offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
            membraneIds.push_back(static_cast<std::int32_t>(k));
        }
    }
    const std::vector<std::uint8_t> types(offsets.size(), kVtkTriangle);

    UnstructuredGridFile file;
    file.setSectionAttributes(UnstructuredGridFile::PointData, "Vectors=\"velocity\"");
    file.setSectionAttributes(UnstructuredGridFile::CellData, "Scalars=\"membrane\"");
    file.addArray(UnstructuredGridFile::PointData, "velocity", 3, velocities);
    file.addArray(UnstructuredGridFile::PointData, "grain_force", 3, grainForces);
    file.addArray(UnstructuredGridFile::PointData, "held", 1, held);
    file.addArray(UnstructuredGridFile::CellData, "membrane", 1, membraneIds);
    addGeometry(file, points, connectivity, offsets, types);
    return file.contents(points.size() / 3, offsets.size());
}

std::string frameFileName(const std::string& baseName, const char* kind, size_t frame,
                          bool parallel = false)
{
    return baseName + "_" + kind + "_" + std::to_string(frame) + (parallel ? ".pvtu" : ".vtu");
}

std::string pieceFileName(const std::string& baseName, const char* kind, size_t frame, int piece)
{
    return baseName + "_" + kind + "_" + std::to_string(frame) + "_" + std::to_string(piece) +
           ".vtu";
}

/// A parallel frame's `.pvtu` of one kind: the arrays its pieces hold (as grainsFile and
/// contactsFile write them) and the pieces' files, relative to it.
std::string parallelFile(const std::string& baseName, const char* kind, size_t frame, int pieces,
                         bool measured)
{
    const bool grains = std::string(kind) == "grains";
    std::string xml = "<?xml version=\"1.0\"?>\n"
                      "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
                      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                      "  <PUnstructuredGrid GhostLevel=\"0\">\n";
    if (grains) {
        xml += "    <PPointData Vectors=\"velocity\">\n"
               "      <PDataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\"/>\n";
        if (measured)
            for (const auto& [name, components] : {std::pair{"displacement", 3}, {"rotation", 1},
                                                   {"d2min", 1}, {"stress", 9}})
                xml += "      <PDataArray type=\"Float64\" Name=\"" + std::string(name) +
                       "\" NumberOfComponents=\"" + std::to_string(components) + "\"/>\n";
        xml += "    </PPointData>\n"
               "    <PCellData Scalars=\"grain\">\n"
               "      <PDataArray type=\"Int32\" Name=\"grain\" NumberOfComponents=\"1\"/>\n"
               "    </PCellData>\n";
    } else {
        xml += "    <PPointData Vectors=\"force\" Scalars=\"grain\">\n"
               "      <PDataArray type=\"Float64\" Name=\"force\" NumberOfComponents=\"3\"/>\n"
               "      <PDataArray type=\"Int32\" Name=\"grain\" NumberOfComponents=\"1\"/>\n"
               "    </PPointData>\n"
               "    <PCellData>\n"
               "    </PCellData>\n";
    }
    xml += "    <PPoints>\n"
           "      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
           "    </PPoints>\n";
    for (int p = 0; p < pieces; ++p)
        xml += "    <Piece Source=\"" + xmlEscape(pieceFileName(baseName, kind, frame, p)) +
               "\"/>\n";
    xml += "  </PUnstructuredGrid>\n</VTKFile>\n";
    return xml;
}

/// The collection: per frame, its time and its files (part 0 grains, part 1 contacts and, for
/// a frame with membranes, part 2 membranes), named relative to the .pvd so the output folder
/// can be moved.
std::string collectionFile(const std::string& baseName, const std::vector<double>& times,
                           const std::vector<char>& parallel, const std::vector<char>& membranes)
{
    std::string xml = "<?xml version=\"1.0\"?>\n"
                      "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\" "
                      "header_type=\"UInt64\">\n"
                      "  <Collection>\n";
    for (size_t k = 0; k < times.size(); ++k) {
        char timestep[40];
        std::snprintf(timestep, sizeof timestep, "%.17g", times[k]);  // round-trips the double
        const char* const kinds[] = {"grains", "contacts", "membranes"};
        for (int part = 0; part < (membranes[k] ? 3 : 2); ++part)
            xml += "    <DataSet timestep=\"" + std::string(timestep) + "\" part=\"" +
                   std::to_string(part) + "\" file=\"" +
                   xmlEscape(frameFileName(baseName, kinds[part], k, parallel[k] && part < 2)) +
                   "\"/>\n";
    }
    xml += "  </Collection>\n</VTKFile>\n";
    return xml;
}

} // namespace

VtkSeries::VtkSeries(std::string directory, std::string baseName)
    : mDirectory(std::move(directory)), mBaseName(std::move(baseName))
{
}

void VtkSeries::writeFrame(int frame, double time, const std::vector<VtkGrain>& grains,
                           const std::vector<VtkForcePoint>& forces,
                           const std::vector<Membrane>& membranes)
{
    // The .pvd names frames by their index, so a frame past the end would leave a hole in it.
    if (frame < 0 || frame > framesWritten())
        throw std::invalid_argument("VtkSeries::writeFrame: frame " + std::to_string(frame) +
                                    " is not in 0.." + std::to_string(framesWritten()));
    const std::filesystem::path dir(mDirectory);
    const size_t k = static_cast<size_t>(frame);
    writeTextFileAtomically((dir / frameFileName(mBaseName, "grains", k)).string(),
                            grainsFile(grains, allMeasured(grains)));
    writeTextFileAtomically((dir / frameFileName(mBaseName, "contacts", k)).string(), contactsFile(forces));
    writeMembranes(k, membranes);
    list(frame, time, false, !membranes.empty(), true);
}

void VtkSeries::writeParallelFrame(int frame, double time, int piece, int pieces,
                                   const std::vector<VtkGrain>& grains,
                                   const std::vector<VtkForcePoint>& forces, bool measured,
                                   const std::vector<Membrane>& membranes)
{
    if (measured && !grains.empty() && !allMeasured(grains))
        throw std::invalid_argument("VtkSeries::writeParallelFrame: a grain without measures");
    if (frame < 0 || frame > framesWritten() || piece < 0 || piece >= pieces)
        throw std::invalid_argument("VtkSeries::writeParallelFrame: frame " +
                                    std::to_string(frame) + " is not in 0.." +
                                    std::to_string(framesWritten()) + ", or piece " +
                                    std::to_string(piece) + " not in 0.." +
                                    std::to_string(pieces - 1));
    const std::filesystem::path dir(mDirectory);
    const size_t k = static_cast<size_t>(frame);
    writeTextFileAtomically((dir / pieceFileName(mBaseName, "grains", k, piece)).string(),
                            grainsFile(grains, measured));
    writeTextFileAtomically((dir / pieceFileName(mBaseName, "contacts", k, piece)).string(),
                            contactsFile(forces));
    if (piece == 0) {
        for (const char* kind : {"grains", "contacts"})
            writeTextFileAtomically((dir / frameFileName(mBaseName, kind, k, true)).string(),
                                    parallelFile(mBaseName, kind, k, pieces, measured));
        writeMembranes(k, membranes);  // (every rank holds them whole: the first writes them)
    }
    list(frame, time, true, !membranes.empty(), piece == 0);
}

void VtkSeries::writeMembranes(size_t frame, const std::vector<Membrane>& membranes) const
{
    if (membranes.empty()) return;
    writeTextFileAtomically(
        (std::filesystem::path(mDirectory) / frameFileName(mBaseName, "membranes", frame)).string(),
        membranesFile(membranes));
}

void VtkSeries::list(int frame, double time, bool parallel, bool membranes, bool writeCollection)
{
    // The list changes only once the .pvd naming it is written, so a failure leaves the
    // series as it was and the frame can be written again.
    std::vector<double> times(mTimes.begin(), mTimes.begin() + frame);
    std::vector<char> kinds(mParallel.begin(), mParallel.begin() + frame);
    std::vector<char> withMembranes(mMembranes.begin(), mMembranes.begin() + frame);
    times.push_back(time);
    kinds.push_back(parallel);
    withMembranes.push_back(membranes);
    const std::filesystem::path dir(mDirectory);
    if (writeCollection)
        writeTextFileAtomically((dir / (mBaseName + ".pvd")).string(),
                                collectionFile(mBaseName, times, kinds, withMembranes));
    mTimes = std::move(times);
    mParallel = std::move(kinds);
    mMembranes = std::move(withMembranes);
}

void VtkSeries::restoreFrameTimes(std::vector<double> times)
{
    mTimes = std::move(times);
    mParallel.assign(mTimes.size(), 0);
    mMembranes.assign(mTimes.size(), 0);
    const std::filesystem::path dir(mDirectory);
    for (size_t k = 0; k < mTimes.size(); ++k) {
        mParallel[k] = std::filesystem::exists(dir / frameFileName(mBaseName, "grains", k, true));
        // (A parallel frame's membranes are a whole .vtu too.)
        mMembranes[k] = std::filesystem::exists(dir / frameFileName(mBaseName, "membranes", k));
    }
}

} // namespace lsdem
