// Conversions between numpy arrays and the library's types: checked inputs
// (dtype and shape named in the error), owning outputs without a copy
// (a moved std::vector kept alive by a capsule), read-only views of a
// container's storage that keep the container alive.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "habuffer/extent.h"
#include "habuffer/fragment.h"

namespace habuffer::python {

namespace py = pybind11;

/// `obj` as an array of T with `ndim` dimensions (and `cols` columns when
/// ndim is 2 and cols > 0): a numpy array of another dtype raises TypeError
/// naming `name`, the dtype wanted and the one given; a wrong shape raises
/// ValueError with both shapes; a list or other sequence is converted.
/// Any strides are accepted (readers use unchecked access).
template <class T>
py::array_t<T, py::array::forcecast> checked_array(py::handle obj, const char* name, int ndim, py::ssize_t cols = 0);

/// "(3, 2)" for an array's shape.
std::string shape_text(const py::array& a);

/// `v` as a 1-D numpy array owning the vector's storage (no copy).
template <class T>
py::array_t<T> owned_array(std::vector<T>&& v) {
  auto* heap = new std::vector<T>(std::move(v));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({static_cast<py::ssize_t>(heap->size())}, {static_cast<py::ssize_t>(sizeof(T))}, heap->data(),
                        owner);
}

/// A read-only numpy view of `data` (rows x cols of T, row-major) whose base
/// is `owner`, so the storage outlives every view of it.
template <class T>
py::array_t<T> readonly_view(const T* data, py::ssize_t rows, py::ssize_t cols, py::handle owner) {
  py::array_t<T> a({rows, cols}, {static_cast<py::ssize_t>(sizeof(T)) * cols, static_cast<py::ssize_t>(sizeof(T))},
                   data, owner);
  a.attr("flags").attr("writeable") = false;
  return a;
}

/// The fragments of xy (N x 2 uint32), depth (N float32) and rgba (N uint32,
/// or None: 0), copied on `threads` threads (0: the default count for N).
/// Sizes that differ raise ValueError naming them.
/// With `coverage` (None: 0, the whole pixel), each fragment's sample mask.
std::vector<Fragment> fragments_from(py::handle xy, py::handle depth, py::handle rgba, std::uint32_t threads = 1,
                                     py::handle coverage = py::none());

/// numpy's dtype of Fragment: [('x', '<u4'), ('y', '<u4'), ('depth', '<f4'), ('rgba', '<u4')].
py::dtype fragment_dtype();

/// (W, H), [W, H] or "WxH" as an Extent; ValueError naming `name` otherwise.
Extent extent_arg(py::handle obj, const char* name);

/// An integer parameter as Python passed it: the signature shows `int`, and
/// any object reaches the function, which reads it with uint_arg, so a value
/// out of range or of another type raises an error naming the parameter and
/// its range (pybind11's own unsigned conversion refuses such a call with a
/// dump of the signatures, naming neither).
struct IntArg {
  py::object value;
};

/// `arg` as an integer in [lo, hi]: Python's and numpy's integers
/// (operator.index), not bools. TypeError "NAME: expected an integer, got
/// X" for another type; ValueError "NAME: V is outside LO..HI" otherwise.
std::uint64_t uint_arg(py::handle arg, const std::string& name, std::uint64_t lo, std::uint64_t hi);
inline std::uint64_t uint_arg(const IntArg& arg, const std::string& name, std::uint64_t lo, std::uint64_t hi) {
  return uint_arg(arg.value, name, lo, hi);
}
/// As uint_arg, 32 bits.
inline std::uint32_t u32_arg(const IntArg& arg, const std::string& name, std::uint32_t lo = 0,
                             std::uint32_t hi = UINT32_MAX) {
  return static_cast<std::uint32_t>(uint_arg(arg.value, name, lo, hi));
}
/// A thread count in 0..kMaxThreads (every --threads of the CLI).
std::uint32_t threads_arg(const IntArg& arg, const std::string& name = "threads");
/// A seed in 0..2^64 - 1 (--seed).
inline std::uint64_t seed_arg(const IntArg& arg, const std::string& name = "seed") {
  return uint_arg(arg.value, name, 0, UINT64_MAX);
}

}  // namespace habuffer::python

namespace pybind11::detail {

// Any object loads as an IntArg (uint_arg checks it); the signature says int.
template <>
struct type_caster<habuffer::python::IntArg> {
  PYBIND11_TYPE_CASTER(habuffer::python::IntArg, const_name("int"));
  bool load(handle src, bool) {
    if (!src) return false;
    value.value = reinterpret_borrow<object>(src);
    return true;
  }
  static handle cast(const habuffer::python::IntArg& arg, return_value_policy, handle) {
    return arg.value.inc_ref();
  }
};

}  // namespace pybind11::detail
