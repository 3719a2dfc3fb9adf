// Asset.sample: φ and ∇φ at many points, threaded with TBB, the GIL released.
#include "Bindings.h"

#include "lsdem/core/Error.h"
#include "lsdem/ls/LevelSetSampler.h"

#include <pybind11/stl.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <optional>

namespace lsdem::python {

namespace {

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

py::tuple sample(const AssetHandle& a, const Points& points, std::optional<int> threads)
{
    if (points.ndim() < 1 || points.shape(points.ndim() - 1) != 3) {
        std::string shape;
        for (py::ssize_t k = 0; k < points.ndim(); ++k)
            shape += (k ? ", " : "") + std::to_string(points.shape(k));
        throw Error("", "points must be an array of shape (..., 3), got shape (" + shape +
                            (points.ndim() == 1 ? ",)" : ")"),
                    "pass an (N, 3) array of positions in the asset frame");
    }
    checkThreads(threads);
    // φ has the points' shape without the last axis; ∇φ the points' shape.
    std::vector<py::ssize_t> shape(points.shape(), points.shape() + points.ndim());
    py::array_t<double> gradient(shape);
    shape.pop_back();
    py::array_t<double> phi(shape);
    const size_t n = static_cast<size_t>(phi.size());
    const double* in = points.data();
    double* outPhi = phi.mutable_data();
    double* outGradient = gradient.mutable_data();
    const LevelSetGrid& levelSet = *a.asset->levelSet;
    {
        py::gil_scoped_release release;
        auto work = [&] {
            tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096),
                              [&](const tbb::blocked_range<size_t>& r) {
                                  // One sampler per task: its accessor is not thread-safe.
                                  LevelSetSampler sampler(levelSet);
                                  for (size_t i = r.begin(); i < r.end(); ++i) {
                                      const Vec3 p(in[3 * i], in[3 * i + 1], in[3 * i + 2]);
                                      const LevelSetSample s = sampler.sample(p);
                                      outPhi[i] = s.phi;
                                      for (int k = 0; k < 3; ++k)
                                          outGradient[3 * i + k] = s.gradient[k];
                                  }
                              });
        };
        if (threads) tbb::task_arena(*threads).execute(work);
        else work();
    }
    return py::make_tuple(phi, gradient);
}

} // namespace

void bindSampling(py::module_& m)
{
    auto asset = py::reinterpret_borrow<py::class_<AssetHandle>>(m.attr("Asset"));
    asset.def("sample", &sample, py::arg("points"), py::kw_only(),
              py::arg("threads") = py::none(),
              "Sample the level set at points (array of shape (..., 3), asset frame, length).\n"
              "Returns (phi, grad): phi of shape (...) is the signed distance (negative "
              "inside), grad of shape (..., 3) the gradient of the trilinear interpolant "
              "(about unit length near the surface; zero outside the narrow band, where phi "
              "is the band width). Runs on TBB threads (all cores, or `threads`) with the GIL "
              "released; the same interpolant the contact laws use.");
}

} // namespace lsdem::python
