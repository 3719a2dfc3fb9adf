// lsdem::Error as the Python exception lsdem.Error, with its parts as attributes.
#include "Bindings.h"

#include "lsdem/core/Error.h"

namespace lsdem::python {

void bindErrors(py::module_& m)
{
    // A RuntimeError subclass, so `except RuntimeError` still catches it. Kept alive by the
    // module's attribute; the translator only borrows it.
    static py::exception<Error> errorType(m, "Error", PyExc_RuntimeError);
    errorType.doc() =
        "lsdem's error for bad input or a failed run. str(e) is the whole message (where, "
        "problem and fix, as the command-line tools print it); e.where names the file and "
        "place (or ''), e.problem says what is wrong, e.fix what to do about it (or '').";
    py::register_exception_translator([](std::exception_ptr thrown) {
        try {
            if (thrown) std::rethrow_exception(thrown);
        } catch (const Error& e) {
            // Call the type itself (py::exception::operator() would only set the error).
            py::object instance = py::reinterpret_borrow<py::object>(errorType.ptr())(e.what());
            instance.attr("where") = e.where();
            instance.attr("problem") = e.problem();
            instance.attr("fix") = e.fix();
            PyErr_SetObject(errorType.ptr(), instance.ptr());
        }
    });
}

} // namespace lsdem::python
