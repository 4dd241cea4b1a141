// SPDX-License-Identifier: MIT
// The parts of the module, each defined in its own file.
#pragma once

#include "convert.h"

namespace scpy {

/// Python's Model: an immutable, shareable model.
struct PyModel {
  sc::ModelPtr model;
};

/// Raises InvalidOperationError while `busy`: an object whose query runs without
/// the GIL on another thread must not be touched meanwhile.
void requireIdle(bool busy, const char* what);

/// Sets a flag for its lifetime (the GIL is held when it is set and cleared).
class BusyScope {
 public:
  BusyScope(bool& busy, const char* what) : busy_(busy) {
    requireIdle(busy, what);
    busy_ = true;
  }
  ~BusyScope() { busy_ = false; }
  BusyScope(const BusyScope&) = delete;
  BusyScope& operator=(const BusyScope&) = delete;

 private:
  bool& busy_;
};

void bindModel(py::module_& m);
void bindResults(py::module_& m);
void bindTracker(py::module_& m);
void bindScene(py::module_& m);

/// A Result object (tracker.cpp) for `r`, whose target has that model-frame centre.
py::object resultOf(const sc::DirectedResult& r, const sc::Vec3& local_center);
/// Contact points as a dict of arrays (see ContactArrays in _core.pyi).
py::dict contactArrays(const std::vector<sc::ContactPoint>& points);

}  // namespace scpy
