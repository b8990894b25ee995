// The Python module imunoise._core (docs/python.md): the errors of the C++ layers as Python
// exceptions carrying the same messages as the CLI prints, and the functions of core_*.cpp.
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "common/errors.h"
#include "python/core_bindings.h"

namespace imunoise::python {

std::span<const double> finite_values(const DoubleArray& array, const std::string& what) {
  if (array.ndim() != 1) {
    throw InputError(what + ": expected a 1-D array, got " + std::to_string(array.ndim()) +
                     " dimensions");
  }
  const std::span<const double> values(array.data(), static_cast<std::size_t>(array.shape(0)));
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw InputError(what + ": value " + std::to_string(i) + " is not finite");
    }
  }
  return values;
}

py::array_t<double> array_view(const std::vector<double>& values, py::handle owner) {
  return py::array_t<double>({static_cast<py::ssize_t>(values.size())}, {sizeof(double)},
                             values.data(), owner);
}

}  // namespace imunoise::python

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace imunoise;
  m.doc() = "imunoise's C++ core (see the imunoise package for the documented API)";
  // The CLI's three error classes (docs/architecture.md, Contracts): a value the user chose is
  // wrong (ValueError), the data cannot answer (RuntimeError), a bug (RuntimeError).
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<AnalysisError> analysis_error(m, "AnalysisError", PyExc_RuntimeError);
  static py::exception<ContractViolation> internal_error(m, "InternalError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(e.what());
    } catch (const AnalysisError& e) {
      analysis_error(e.what());
    } catch (const ContractViolation& e) {
      internal_error((std::string("internal error: ") + e.what()).c_str());
    }
  });
  python::add_deviation_functions(m);
  python::add_recording_functions(m);
  python::add_model_functions(m);
}
