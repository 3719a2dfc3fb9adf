// Simulation.contact_pairs and Simulation.micromechanics() in Python: each contact as a whole
// (both bodies, resultant, centre, normal, nodes) and what granular mechanics derives from them
// (Micromechanics.h), so a user can compute fabrics and stresses without the point forces.
#include "PySimulation.h"

#include "lsdem/simulation/Micromechanics.h"
#include "lsdem/simulation/NonAffineMotion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace lsdem::python {

namespace {

py::array_t<double> rowsOf(const std::vector<ContactRecord>& records, Vec3 ContactRecord::*field)
{
    const auto n = static_cast<py::ssize_t>(records.size());
    py::array_t<double> rows({n, py::ssize_t{3}});
    auto r = rows.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) r(i, k) = (records[size_t(i)].*field)[k];
    return rows;
}

py::array_t<int> columnOf(const std::vector<ContactRecord>& records, int ContactRecord::*field)
{
    py::array_t<int> column(static_cast<py::ssize_t>(records.size()));
    for (size_t i = 0; i < records.size(); ++i) column.mutable_at(py::ssize_t(i)) = records[i].*field;
    return column;
}

py::array_t<double> matrixOf(const Mat3& m)
{
    py::array_t<double> a({py::ssize_t{3}, py::ssize_t{3}});
    auto r = a.mutable_unchecked<2>();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r(i, j) = m(i, j);
    return a;
}

/// The rows of an (N, 3) array of finite numbers, named @a what in errors.
std::vector<Vec3> pointsOf(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                           const std::string& what)
{
    if (a.ndim() != 2 || a.shape(1) != 3)
        throw Error("", what + " must have shape (N, 3)", "pass an array of N points");
    std::vector<Vec3> points;
    auto r = a.unchecked<2>();
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
        const Vec3 p(r(i, 0), r(i, 1), r(i, 2));
        if (!p.allFinite())
            throw Error("", what + " row " + std::to_string(i) + " is not finite", "give numbers");
        points.push_back(p);
    }
    return points;
}

} // namespace

// Long by nature: one .def per function, each with its keyword arguments and docstring.
void bindMicromechanics(py::module_& m)
{
    m.def(
        "nonaffine_displacement",
        [](const py::array_t<double, py::array::c_style | py::array::forcecast>& reference,
           const py::array_t<double, py::array::c_style | py::array::forcecast>& current,
           const py::array_t<double, py::array::c_style | py::array::forcecast>& radii,
           double reach, const std::optional<std::array<double, 3>>& referenceSize,
           const std::optional<std::array<double, 3>>& currentSize,
           const std::optional<std::array<double, 3>>& cellOrigin) {
            const std::vector<Vec3> was = pointsOf(reference, "reference");
            const std::vector<Vec3> now = pointsOf(current, "current");
            if (now.size() != was.size())
                throw Error("", "current has " + std::to_string(now.size()) + " rows, reference " +
                                    std::to_string(was.size()),
                            "give the same grains in both");
            if (radii.ndim() != 1 || size_t(radii.shape(0)) != was.size())
                throw Error("", "radii must have shape (N,), one per grain", "e.g. bounding radii");
            std::vector<double> r(radii.data(), radii.data() + radii.shape(0));
            for (const double v : r)
                if (!(v > 0.0 && std::isfinite(v)))
                    throw Error("", "radii must be finite and > 0", "e.g. the grains' bounding radii");
            if (!(reach > 0.0 && std::isfinite(reach)))
                throw Error("", "reach must be finite and > 0", "e.g. 1.1");
            if (!referenceSize && (currentSize || cellOrigin))
                throw Error("", "current_size and cell_origin describe a periodic cell: give "
                                "its reference_size too", "add reference_size=, or drop them");
            if (!referenceSize) {
                const std::vector<double> d2 =
                    nonAffineDisplacement(was, now, neighboursWithin(was, r, reach));
                return py::array_t<double>(static_cast<py::ssize_t>(d2.size()), d2.data());
            }
            // A periodic cell: neighbours across its faces too.
            PeriodicCell cell;
            if (cellOrigin) cell.origin = Vec3((*cellOrigin)[0], (*cellOrigin)[1], (*cellOrigin)[2]);
            cell.size = Vec3((*referenceSize)[0], (*referenceSize)[1], (*referenceSize)[2]);
            const Vec3 sizeNow = currentSize ? Vec3((*currentSize)[0], (*currentSize)[1], (*currentSize)[2])
                                             : cell.size;
            for (const Vec3& s : {cell.size, sizeNow})
                if (!s.allFinite() || s.minCoeff() < 0.0)
                    throw Error("", "a cell size must be three finite numbers >= 0",
                                "give the periods, 0 along an axis that is not periodic");
            if ((cell.size.array() > 0.0).matrix() != (sizeNow.array() > 0.0).matrix())
                throw Error("", "reference_size and current_size are periodic along different axes",
                            "give both cells' sizes along the same periodic axes");
            // Neighbours are looked for one period away: no grain may be near two images of
            // another (as the simulation's own cell, 4.5 radii wide at least).
            const double largest = *std::max_element(r.begin(), r.end());
            for (int a = 0; a < 3; ++a)
                if (cell.size[a] > 0.0 && !(cell.size[a] > 4.0 * reach * largest))
                    throw Error("", std::string("the cell's period along ") + "xyz"[a] + " is " +
                                        "less than 4·reach times the largest radius",
                                "give the periods of a cell as wide as the simulation's");
            const std::vector<double> d2 = nonAffineDisplacement(
                was, cell.size, now, sizeNow, neighboursWithin(was, r, reach, cell));
            return py::array_t<double>(static_cast<py::ssize_t>(d2.size()), d2.data());
        },
        py::arg("reference"), py::arg("current"), py::arg("radii"), py::arg("reach") = 1.1,
        py::arg("reference_size") = py::none(), py::arg("current_size") = py::none(),
        py::arg("cell_origin") = py::none(),
        "D²min of Falk & Langer for each grain (docs/micromechanics.md): its neighbours in the "
        "reference (centres within reach·(r_i + r_j), radii (N,)), the best local affine "
        "deformation of their offsets taken out, what is left of their motion relative to it, "
        "length². reference and current (N, 3) positions, e.g. sim.grains.positions at two "
        "times. In a periodic cell give its periods then and now (reference_size, current_size, "
        "0 along an axis that is not periodic; and cell_origin, default 0) and both positions "
        "unwrapped (sim.grains.unwrapped_positions: a grain that has crossed a face is a whole "
        "period away in positions): a grain at a face then has its neighbours across it.");

    auto simulation = py::reinterpret_borrow<py::class_<PySimulation>>(m.attr("Simulation"));
    simulation.def_property_readonly(
        "contact_pairs",
        [](const PySimulation& s) {
            s.checkNotSteppingElsewhere();
            const std::vector<ContactRecord> records = s.sim().contactRecords();
            py::dict d;
            d["first"] = columnOf(records, &ContactRecord::first);
            d["second"] = columnOf(records, &ContactRecord::second);
            d["boundary"] = columnOf(records, &ContactRecord::boundary);
            d["membrane"] = columnOf(records, &ContactRecord::membrane);
            d["forces"] = rowsOf(records, &ContactRecord::force);
            d["centres"] = rowsOf(records, &ContactRecord::centre);
            d["normals"] = rowsOf(records, &ContactRecord::normal);
            d["nodes"] = columnOf(records, &ContactRecord::nodes);
            d["shifts"] = rowsOf(records, &ContactRecord::shift);
            return py::module_::import("types").attr("SimpleNamespace")(**d);
        },
        "Every contact of the last evaluation as a whole (copies; K contacts, grain pairs "
        "first): .first (K,) grain index; .second (K,) the other grain's index or -1, and then "
        ".boundary (K,) the boundary's index (else -1), or .membrane (K,) the membrane's (else "
        "-1); .forces (K, 3) the resultant on the "
        "first grain (the other body gets the opposite); .centres (K, 3) where it acts (the "
        "stiffness-weighted centre of its point forces); .normals (K, 3) unit, pushing the first "
        "grain out; .nodes (K,) its penetrating nodes; .shifts (K, 3) in a periodic cell the "
        "periods added to the second grain's position (it touches that image; zero otherwise).");
    simulation.def(
        "micromechanics",
        [](const PySimulation& s) {
            s.checkNotSteppingElsewhere();
            const std::vector<ContactRecord> records = s.sim().contactRecords();
            const Micromechanics mm = micromechanicsOf(s.world(), records);
            const std::vector<Mat3> perGrain = grainStresses(s.world(), records);
            const auto n = static_cast<py::ssize_t>(perGrain.size());
            py::array_t<double> grains({n, py::ssize_t{3}, py::ssize_t{3}});
            auto g = grains.mutable_unchecked<3>();
            for (py::ssize_t p = 0; p < n; ++p)
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) g(p, i, j) = perGrain[size_t(p)](i, j);
            py::dict d;
            d["stress_moment"] = matrixOf(mm.stressMoment);
            d["grain_stresses"] = grains;
            d["fabric"] = matrixOf(mm.fabric);
            d["fabric_anisotropy"] = mm.fabricAnisotropy;
            d["branch_fabric"] = matrixOf(mm.branchFabric);
            d["branch_anisotropy"] = mm.branchAnisotropy;
            d["force_fabric"] = matrixOf(mm.forceFabric);
            d["force_anisotropy"] = mm.forceAnisotropy;
            d["mean_normal_force"] = mm.meanNormalForce;
            d["grain_contacts"] = mm.grainContacts;
            d["boundary_contacts"] = mm.boundaryContacts;
            d["free_grains"] = mm.freeGrains;
            d["rattlers"] = mm.rattlers;
            d["mechanical_coordination"] = mm.mechanicalCoordination;
            return d;
        },
        "The sample's micromechanics at the last evaluation (docs/micromechanics.md), free "
        "grains being the sample: stress_moment (3, 3) Σ (x_c − x_p) ⊗ f_c, the Love–Weber "
        "stress times the sample's volume (divide by your sample's volume); grain_stresses "
        "(N, 3, 3) each free grain's mean stress; fabric (3, 3) of the grain contacts' normals "
        "and fabric_anisotropy sqrt(3/2 a:a), a = 15/2 (fabric − I/3); branch_fabric and "
        "branch_anisotropy the same of the unit branch vectors between the grains' centroids; "
        "force_fabric Σ f_n n⊗n / Σ f_n (the normals weighted by their normal force) and "
        "force_anisotropy; mean_normal_force; grain_contacts, "
        "boundary_contacts, free_grains, rattlers (free grains with fewer than two grain "
        "contacts) and Thornton's mechanical_coordination (2C − N1)/(N − N0 − N1).");
}

} // namespace lsdem::python
