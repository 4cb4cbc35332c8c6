#include "arrays.h"

#include <pybind11/stl.h>

#include <optional>
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

template <class T>
py::array_t<T, py::array::forcecast> checked_array(py::handle obj, const char* name, int ndim, py::ssize_t cols) {
  const std::string wanted = py::str(py::dtype::of<T>()).cast<std::string>();
  const std::string shape_wanted = ndim == 1 ? "(N,)" : "(N, " + (cols > 0 ? std::to_string(cols) : "M") + ")";
  if (py::isinstance<py::array>(obj)) {
    const auto a = py::reinterpret_borrow<py::array>(obj);
    if (!a.dtype().equal(py::dtype::of<T>()))
      throw py::type_error(std::string(name) + ": expected a " + wanted + " array of shape " + shape_wanted +
                           ", got " + py::str(a.dtype()).cast<std::string>() +
                           " (convert with .astype(numpy." + wanted + ") if the values fit)");
  }
  auto a = py::array_t<T, py::array::forcecast>::ensure(obj);
  if (!a) throw py::type_error(std::string(name) + ": expected a " + wanted + " array of shape " + shape_wanted);
  if (a.ndim() != ndim || (ndim == 2 && cols > 0 && a.shape(1) != cols))
    throw py::value_error(std::string(name) + ": expected shape " + shape_wanted + ", got " + shape_text(a));
  return a;
}

template py::array_t<std::uint32_t, py::array::forcecast> checked_array<std::uint32_t>(py::handle, const char*, int,
                                                                                      py::ssize_t);
template py::array_t<float, py::array::forcecast> checked_array<float>(py::handle, const char*, int, py::ssize_t);
template py::array_t<double, py::array::forcecast> checked_array<double>(py::handle, const char*, int, py::ssize_t);

std::vector<Fragment> fragments_from(py::handle xy_obj, py::handle depth_obj, py::handle rgba_obj,
                                     std::uint32_t threads) {
  const auto xy = checked_array<std::uint32_t>(xy_obj, "xy", 2, 2);
  const auto depth = checked_array<float>(depth_obj, "depth", 1);
  const bool has_rgba = !rgba_obj.is_none();
  py::array_t<std::uint32_t, py::array::forcecast> rgba;
  if (has_rgba) rgba = checked_array<std::uint32_t>(rgba_obj, "rgba", 1);
  const py::ssize_t n = xy.shape(0);
  if (depth.shape(0) != n || (has_rgba && rgba.shape(0) != n))
    throw py::value_error("xy, depth and rgba must hold one row per fragment: got " + std::to_string(n) + ", " +
                          std::to_string(depth.shape(0)) +
                          (has_rgba ? " and " + std::to_string(rgba.shape(0)) : std::string(" and None")));
  std::vector<Fragment> out(static_cast<std::size_t>(n));
  const auto p = xy.unchecked<2>();
  const auto d = depth.unchecked<1>();
  std::optional<py::detail::unchecked_reference<std::uint32_t, 1>> c;
  if (has_rgba) c.emplace(rgba.unchecked<1>());
  // The copy reads the arrays only (their owners are held by the caller), in
  // as many chunks as the insert's threads, so it stays a small part of it.
  const std::uint32_t tasks = resolve_threads(threads, static_cast<std::uint64_t>(n));
  py::gil_scoped_release release;
  run_with_threads(tasks, [&] {
    fork_join(tasks, [&](std::uint32_t t) {
      const py::ssize_t begin = n * t / tasks, end = n * (t + 1) / tasks;
      for (py::ssize_t i = begin; i < end; ++i)
        out[static_cast<std::size_t>(i)] = Fragment{p(i, 0), p(i, 1), d(i), c ? (*c)(i) : 0u};
    });
  });
  return out;
}

py::dtype fragment_dtype() {
  static_assert(sizeof(Fragment) == 16 && offsetof(Fragment, depth) == 8 && offsetof(Fragment, rgba) == 12,
                "FRAGMENT_DTYPE mirrors Fragment's layout: change both together");
  py::list fields;
  for (const char* f : {"x", "y"}) fields.append(py::make_tuple(f, "<u4"));
  fields.append(py::make_tuple("depth", "<f4"));
  fields.append(py::make_tuple("rgba", "<u4"));
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
    if (seq.size() == 2 && seq[0] >= 0 && seq[1] >= 0 && seq[0] <= UINT32_MAX && seq[1] <= UINT32_MAX)
      return Extent{static_cast<std::uint32_t>(seq[0]), static_cast<std::uint32_t>(seq[1])};
  } catch (const py::cast_error&) {
  }
  throw py::value_error(std::string(name) + ": expected (W, H) or 'WxH', got " + py::repr(obj).cast<std::string>());
}

}  // namespace habuffer::python
