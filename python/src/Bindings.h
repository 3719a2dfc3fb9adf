/// @file Bindings.h
/// @brief What the binding files of the Python module share: one bind function per concept
///        (errors, assets, sampling, scenes, simulation, whole runs), the Python-side asset handle, and
///        the conversions between lsdem's Eigen vectors and numpy arrays.
#pragma once

#include "lsdem/core/ThreadLimit.h"
#include "lsdem/ls/GrainAsset.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <tbb/task_arena.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lsdem {
struct Scene;
}

namespace lsdem::python {

namespace py = pybind11;

void bindErrors(py::module_& m);
void bindAssets(py::module_& m);
void bindSampling(py::module_& m);  ///< adds Asset.sample (after bindAssets)
void bindScenes(py::module_& m);
void bindSimulation(py::module_& m);
void bindMicromechanics(py::module_& m);  ///< adds Simulation.contact_pairs (after bindSimulation)
void bindRuns(py::module_& m);      ///< run_scene (lsdem-run) and the study submodule

/// A grain asset as Python sees it: shared and read-only (many grains, one asset), with the
/// file it was loaded from or saved to, so a scene holding it can be written as TOML.
struct AssetHandle
{
    std::shared_ptr<const GrainAsset> asset;
    std::string path;  ///< "" while it lives only in memory
};

/// Remember that @a asset was loaded from or saved to @a path (made absolute here): a scene
/// given the asset before it was saved still finds its file when written (to_toml,
/// checkpoints). Call with the GIL held.
void rememberAssetFile(const std::shared_ptr<const GrainAsset>& asset, const std::string& path);
/// The file @a asset was last loaded from or saved to in Python ("" if none).
std::string rememberedAssetFile(const GrainAsset* asset);
/// @a scene with each asset it holds only in memory given the file that asset has since been
/// saved to in Python (for writing the scene). @throw lsdem::Error if one was never saved.
Scene withSavedAssetFiles(const Scene& scene);

/// A read-only (count, 3) float64 view of @a count vectors starting at @a first, each
/// @a strideBytes apart; @a owner is kept alive as long as the view (numpy's base).
py::array vectorView(const Vec3* first, size_t count, size_t strideBytes, py::handle owner);
/// A read-only (count,) float64 view of @a count doubles starting at @a first.
py::array scalarView(const double* first, size_t count, size_t strideBytes, py::handle owner);
/// A fresh (n, 3) float64 array holding @a vectors.
py::array_t<double> vectorCopy(const std::vector<Vec3>& vectors);
/// A fresh (3,) float64 array; a fresh (3, 3) one.
py::array_t<double> toArray(const Vec3& v);
py::array_t<double> toArray(const Mat3& m);
/// @throw lsdem::Error unless @a threads is none or from 1 to kMaxThreads.
void checkThreads(std::optional<int> threads);
/// A TBB arena of @a threads threads (all cores if none). @throw lsdem::Error as checkThreads.
std::unique_ptr<tbb::task_arena> makeArena(std::optional<int> threads);
/// A vector from any Python sequence of three numbers. @throw lsdem::Error naming @a what.
Vec3 toVec3(const py::handle& value, const std::string& what);

} // namespace lsdem::python
