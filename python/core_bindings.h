/// @file
/// @brief The parts of the Python module `imunoise._core` (python/core_*.cpp), each adding its
/// functions to the module, and the checks of Python arguments they share. Internal to python/.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <span>
#include <string>

namespace imunoise::python {

namespace py = pybind11;

/// A 1-D float64 array, C-contiguous: numpy's float64 arrays pass without a copy (forcecast
/// copies only other dtypes or strides).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// The values of ARRAY (1-D, every value finite) as a span; InputError naming WHAT otherwise.
std::span<const double> finite_values(const DoubleArray& array, const std::string& what);

/// A numpy array that views VALUES without a copy, kept alive by OWNER.
py::array_t<double> array_view(const std::vector<double>& values, py::handle owner);

void add_deviation_functions(py::module_& m);  ///< deviation, psd (core_deviation.cpp)
void add_recording_functions(
    py::module_& m);  ///< Recording, read_recording, recording_from_arrays, simulate
void add_model_functions(py::module_& m);  ///< fit, model text, export (core_model.cpp)

}  // namespace imunoise::python
