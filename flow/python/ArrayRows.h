#pragma once
// Vectors as the (n, 3) numpy arrays the flow bindings return (pore_wrappers.cpp,
// twophase_wrappers.cpp).
#include "flow/pore/PoreNetwork.h"

#include <pybind11/numpy.h>

#include <vector>

namespace talus::flow::python
{
inline pybind11::array_t<double> rows(const std::vector<pore::Vec3>& v)
{
  pybind11::array_t<double> a({static_cast<pybind11::ssize_t>(v.size()), pybind11::ssize_t{3}});
  auto out = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (pybind11::ssize_t d = 0; d < 3; ++d)
      out(static_cast<pybind11::ssize_t>(i), d) = v[i][d];
  return a;
}
} // namespace talus::flow::python
