#include "arrays.h"

#include <pybind11/stl.h>

#include <limits>
#include <optional>
#include <type_traits>
#include <stdexcept>

#include "habuffer/fragment_buffer.h"
#include "habuffer/parallel.h"

namespace habuffer::python {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) {
    if (i) s += ", ";
    s += std::to_string(a.shape(i));
  }
  return s + (a.ndim() == 1 ? ",)" : ")");
}

namespace {

// A list or tuple of Python numbers as an array of T: integers for an
// integer T, checked to fit; integers or reals for a real T. Other shapes
// and types are left to the caller's checks.
template <class T>
py::array from_sequence(py::handle obj, const char* name) {
  const py::array raw = py::module_::import("numpy").attr("asarray")(obj);
  if (raw.size() == 0) return py::array_t<T>(std::vector<py::ssize_t>(raw.shape(), raw.shape() + raw.ndim()));
  const char kind = raw.dtype().kind();
  if constexpr (std::is_integral_v<T>) {
    if (kind != 'i' && kind != 'u')
      throw py::type_error(std::string(name) + ": expected integers, got " + py::str(raw.dtype()).cast<std::string>());
    const auto lo = raw.attr("min")().cast<long double>(), hi = raw.attr("max")().cast<long double>();
    if (lo < 0 || hi > static_cast<long double>(std::numeric_limits<T>::max()))
      throw py::value_error(std::string(name) + ": values must lie in [0, " +
                            std::to_string(std::numeric_limits<T>::max()) + "]");
  } else if (kind != 'i' && kind != 'u' && kind != 'f') {
    throw py::type_error(std::string(name) + ": expected numbers, got " + py::str(raw.dtype()).cast<std::string>());
  }
  return raw.attr("astype")(py::dtype::of<T>());
}

}  // namespace

template <class T>
py::array_t<T, py::array::forcecast> checked_array(py::handle obj, const char* name, int ndim, py::ssize_t cols) {
  const std::string wanted = py::str(py::dtype::of<T>()).cast<std::string>();
  const std::string shape_wanted = ndim == 1 ? "(N,)" : "(N, " + (cols > 0 ? std::to_string(cols) : "M") + ")";
  // numpy arrays and whatever numpy reads as one (pandas, buffers, __array__)
  // must have the dtype: nothing is wrapped, truncated or rounded silently.
  // Python lists and tuples are converted, their values checked to fit.
  py::array a;
  if (py::isinstance<py::array>(obj))
    a = py::reinterpret_borrow<py::array>(obj);
  else if (py::isinstance<py::list>(obj) || py::isinstance<py::tuple>(obj))
    a = from_sequence<T>(obj, name);
  else
    a = py::module_::import("numpy").attr("asarray")(obj);
  if (!a.dtype().equal(py::dtype::of<T>()))
    throw py::type_error(std::string(name) + ": expected a " + wanted + " array of shape " + shape_wanted + ", got " +
                         py::str(a.dtype()).cast<std::string>() + " (convert with .astype(numpy." + wanted +
                         ") if the values fit)");
  if (a.ndim() != ndim || (ndim == 2 && cols > 0 && a.shape(1) != cols))
    throw py::value_error(std::string(name) + ": expected shape " + shape_wanted + ", got " + shape_text(a));
  return py::array_t<T, py::array::forcecast>::ensure(a);  // the same dtype: no copy, no conversion
}

template py::array_t<std::uint32_t, py::array::forcecast> checked_array<std::uint32_t>(py::handle, const char*, int,
                                                                                      py::ssize_t);
template py::array_t<float, py::array::forcecast> checked_array<float>(py::handle, const char*, int, py::ssize_t);
template py::array_t<double, py::array::forcecast> checked_array<double>(py::handle, const char*, int, py::ssize_t);

std::vector<Fragment> fragments_from(py::handle xy_obj, py::handle depth_obj, py::handle rgba_obj,
                                     std::uint32_t threads, py::handle coverage_obj) {
  const auto xy = checked_array<std::uint32_t>(xy_obj, "xy", 2, 2);
  const auto depth = checked_array<float>(depth_obj, "depth", 1);
  const bool has_rgba = !rgba_obj.is_none();
  const bool has_coverage = !coverage_obj.is_none();
  py::array_t<std::uint32_t, py::array::forcecast> rgba, coverage;
  if (has_rgba) rgba = checked_array<std::uint32_t>(rgba_obj, "rgba", 1);
  if (has_coverage) coverage = checked_array<std::uint32_t>(coverage_obj, "coverage", 1);
  const py::ssize_t n = xy.shape(0);
  if (depth.shape(0) != n || (has_rgba && rgba.shape(0) != n) || (has_coverage && coverage.shape(0) != n))
    throw py::value_error("xy, depth, rgba and coverage must hold one row per fragment: got " + std::to_string(n) +
                          ", " + std::to_string(depth.shape(0)) + ", " +
                          (has_rgba ? std::to_string(rgba.shape(0)) : std::string("None")) + " and " +
                          (has_coverage ? std::to_string(coverage.shape(0)) : std::string("None")));
  std::vector<Fragment> out(static_cast<std::size_t>(n));
  const auto p = xy.unchecked<2>();
  const auto d = depth.unchecked<1>();
  std::optional<py::detail::unchecked_reference<std::uint32_t, 1>> c, m;
  if (has_rgba) c.emplace(rgba.unchecked<1>());
  if (has_coverage) m.emplace(coverage.unchecked<1>());
  // The copy reads the arrays only (their owners are held by the caller), in
  // as many chunks as the insert's threads, so it stays a small part of it.
  const std::uint32_t tasks = resolve_threads(threads, static_cast<std::uint64_t>(n));
  py::gil_scoped_release release;
  run_with_threads(tasks, [&] {
    fork_join(tasks, [&](std::uint32_t t) {
      const py::ssize_t begin = n * t / tasks, end = n * (t + 1) / tasks;
      for (py::ssize_t i = begin; i < end; ++i)
        out[static_cast<std::size_t>(i)] = Fragment{p(i, 0), p(i, 1), d(i), c ? (*c)(i) : 0u, m ? (*m)(i) : 0u};
    });
  });
  return out;
}

py::dtype fragment_dtype() {
  static_assert(sizeof(Fragment) == 20 && offsetof(Fragment, depth) == 8 && offsetof(Fragment, rgba) == 12 &&
                    offsetof(Fragment, coverage) == 16,
                "FRAGMENT_DTYPE mirrors Fragment's layout: change both together");
  py::list fields;
  for (const char* f : {"x", "y"}) fields.append(py::make_tuple(f, "<u4"));
  fields.append(py::make_tuple("depth", "<f4"));
  fields.append(py::make_tuple("rgba", "<u4"));
  fields.append(py::make_tuple("coverage", "<u4"));
  return py::dtype::from_args(fields);
}

Extent extent_arg(py::handle obj, const char* name) {
  if (py::isinstance<py::str>(obj)) {
    const std::string s = obj.cast<std::string>();
    if (const std::optional<Extent> e = parse_extent(s)) return *e;
    throw py::value_error(std::string(name) + ": '" + s + "' is not WxH (two positive integers)");
  }
  try {
    const auto seq = obj.cast<std::vector<std::int64_t>>();
    if (seq.size() == 2 && seq[0] >= 1 && seq[1] >= 1 && seq[0] <= UINT32_MAX && seq[1] <= UINT32_MAX)
      return Extent{static_cast<std::uint32_t>(seq[0]), static_cast<std::uint32_t>(seq[1])};
  } catch (const py::cast_error&) {
  }
  throw py::value_error(std::string(name) + ": expected (W, H) or 'WxH' of positive sides, got " +
                        py::repr(obj).cast<std::string>());
}

std::uint64_t uint_arg(py::handle arg, const std::string& name, std::uint64_t lo, std::uint64_t hi) {
  // Python's and numpy's integers (operator.index), not bools (True would read as 1)
  if (!arg || py::isinstance<py::bool_>(arg) || !PyIndex_Check(arg.ptr())) {
    std::string got = arg ? py::repr(arg).cast<std::string>() : std::string("nothing");
    if (got.size() > 60) got = got.substr(0, 57) + "...";
    throw py::type_error(name + ": expected an integer, got " + got);
  }
  const auto integer = py::reinterpret_steal<py::object>(PyNumber_Index(arg.ptr()));
  if (!integer) throw py::error_already_set();
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(integer.ptr(), &overflow);
  if (v == -1 && PyErr_Occurred()) throw py::error_already_set();
  bool fits = false;  // in 0..2^64 - 1
  std::uint64_t u = 0;
  if (overflow == 0 && v >= 0) {
    u = static_cast<std::uint64_t>(v);
    fits = true;
  } else if (overflow > 0) {
    u = PyLong_AsUnsignedLongLong(integer.ptr());
    if (PyErr_Occurred()) PyErr_Clear();
    else fits = true;
  }
  if (fits && u >= lo && u <= hi) return u;
  std::string text;
  try {
    text = py::str(integer).cast<std::string>();
  } catch (const py::error_already_set&) {  // past Python's digit limit for str()
    text = "an integer of " + py::str(integer.attr("bit_length")()).cast<std::string>() + " bits";
  }
  if (text.size() > 40) text = text.substr(0, 20) + "..." + text.substr(text.size() - 8);
  throw py::value_error(name + ": " + text + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
}

std::uint32_t threads_arg(const IntArg& arg, const std::string& name) {
  return static_cast<std::uint32_t>(uint_arg(arg.value, name, 0, kMaxThreads));
}

}  // namespace habuffer::python
