// What the module's files share: NumPy and JSON out, the scene handle, and the bindings each
// file adds to the module.
#pragma once

#include <pathlet/scene.hpp>

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <vector>

namespace py = pybind11;
using nlohmann::json;

namespace pathlet::python {

using SceneRef = std::shared_ptr<const Scene>;

// Python's json module turns our JSON text into dicts (no converter to maintain).
inline py::object from_json(const json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

// A vector handed to NumPy without a copy: the array owns it.
template <class T>
py::array to_numpy(std::vector<T>&& v, std::vector<py::ssize_t> shape) {
    auto* heap = new std::vector<T>(std::move(v));
    py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>(shape, heap->data(), owner);
}

// bench, quality (AO, transparency, against a reference) and their options (measure_bindings.cpp).
void bind_measures(py::module_& m);

}  // namespace pathlet::python
