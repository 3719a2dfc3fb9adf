// The entry point of the compiled module lsdem._lsdem; the package lsdem re-exports it.
#include "Bindings.h"

#include "lsdem/core/Error.h"

#include <cstring>

namespace lsdem::python {

namespace {

py::array makeView(const void* first, std::vector<py::ssize_t> shape,
                   std::vector<py::ssize_t> strides, py::handle owner)
{
    // numpy refuses a null pointer even for zero elements; any valid address will do then.
    static const double kEmpty = 0.0;
    py::array view(py::dtype::of<double>(), std::move(shape), std::move(strides),
                   first ? first : &kEmpty, owner);
    // The data belongs to lsdem (shared assets, the running world): look, do not touch.
    view.attr("setflags")(py::arg("write") = false);
    return view;
}

} // namespace

py::array vectorView(const Vec3* first, size_t count, size_t strideBytes, py::handle owner)
{
    const auto n = static_cast<py::ssize_t>(count);
    return makeView(count ? first->data() : nullptr, {n, 3},
                    {static_cast<py::ssize_t>(strideBytes), sizeof(double)}, owner);
}

py::array scalarView(const double* first, size_t count, size_t strideBytes, py::handle owner)
{
    return makeView(count ? first : nullptr, {static_cast<py::ssize_t>(count)},
                    {static_cast<py::ssize_t>(strideBytes)}, owner);
}

py::array_t<double> vectorCopy(const std::vector<Vec3>& vectors)
{
    py::array_t<double> out({static_cast<py::ssize_t>(vectors.size()), py::ssize_t{3}});
    auto view = out.mutable_unchecked<2>();
    for (size_t i = 0; i < vectors.size(); ++i)
        for (int k = 0; k < 3; ++k) view(static_cast<py::ssize_t>(i), k) = vectors[i][k];
    return out;
}

py::array_t<double> toArray(const Vec3& v)
{
    py::array_t<double> out(3);
    std::memcpy(out.mutable_data(), v.data(), 3 * sizeof(double));
    return out;
}

py::array_t<double> toArray(const Mat3& m)
{
    py::array_t<double> out({3, 3});
    auto view = out.mutable_unchecked<2>();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) view(i, j) = m(i, j);
    return out;
}

Vec3 toVec3(const py::handle& value, const std::string& what)
{
    try {
        const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
        if (a && a.ndim() == 1 && a.shape(0) == 3) {
            const Vec3 v(a.at(0), a.at(1), a.at(2));
            if (!v.allFinite())
                throw Error("", what + " must be finite, got " +
                                    std::string(py::str(py::repr(value))));
            return v;
        }
    } catch (const py::error_already_set&) {
    }
    throw Error("", what + " must be three numbers [x, y, z], not " +
                        std::string(py::str(py::repr(value))),
                "pass a list, tuple or numpy array of three numbers");
}

} // namespace lsdem::python

PYBIND11_MODULE(_lsdem, m)
{
    using namespace lsdem::python;
    m.doc() = "lsdem: level-set discrete element method (LS-DEM). Grain assets (bake, load, "
              "sample), scenes (TOML) and simulations, with numpy arrays. Units are yours: "
              "lsdem never converts.";
    bindErrors(m);
    bindAssets(m);
    bindSampling(m);
    bindScenes(m);
    bindSimulation(m);
    bindMicromechanics(m);
    bindRuns(m);
}
