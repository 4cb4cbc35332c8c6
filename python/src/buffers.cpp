// Every technique's CPU container as habuffer.Buffer: insert from numpy
// arrays with the GIL released (calls may overlap from Python threads, as
// the library allows), the lists as CSR arrays, the composite, counters as
// a dict, and for the HA-buffer its table and max-age table as zero-copy
// read-only views. habuffer.build() is build_technique (lossless mode
// included) on the CPU path or, where a context can be made, the GPU path;
// a lossless build that ends lossy raises DataError (require_lossless).
#include <pybind11/stl.h>

#include <chrono>
#include <cstring>
#include <mutex>
#include <shared_mutex>

#include "arrays.h"
#include "bindings.h"
#include "config.h"
#include "gl_context.h"
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/build_report.h"
#include "habuffer/interchange.h"
#include "habuffer/lossless_build.h"
#include "habuffer/render/stream_build.h"
#include "habuffer/technique_descriptor.h"
#ifdef HABUFFER_WITH_VK
#include "habuffer/data_error.h"
#include "habuffer/vk/vulkan_build.h"
#include "habuffer/vk/vulkan_context.h"
#include "habuffer/vk/vulkan_error.h"
#endif

namespace habuffer::python {
namespace {

py::dict counters_dict(const Counters& c) {
  py::dict d;
  d["fragments"] = c.fragments;
  d["stored"] = c.stored();
  for (const CounterField& f : kCounterFields) d[std::string(f.name).c_str()] = c.*f.member;
  d["failures"] = c.failures();
  return d;
}

InsertOptions insert_options(std::uint32_t threads, const std::string& mode, const std::string& order) {
  InsertOptions o;
  o.threads = threads;
  const std::optional<InsertMode> parsed_mode = parse_insert_mode(mode);
  if (!parsed_mode) throw py::value_error("mode: '" + mode + "' is not auto, serial, atomic or owner");
  o.mode = *parsed_mode;
  if (o.mode == InsertMode::Serial && threads != 1)
    throw py::value_error("mode 'serial' runs on one thread: give threads=1");
  const std::optional<InsertOrder> parsed = parse_insert_order(order);
  if (!parsed) throw py::value_error("order: '" + order + "' is not auto, arrival or pixel");
  o.order = *parsed;
  return o;
}

// One container, owned; the counters of every insert since the last clear.
class Buffer {
 public:
  explicit Buffer(std::unique_ptr<FragmentBuffer> b) : buffer_(std::move(b)) {}

  FragmentBuffer& get() const { return *buffer_; }
  const HaBuffer& hash_table(const char* what) const {
    const HaBuffer* ha = as_hash_table(*buffer_);
    if (!ha)
      throw py::type_error(std::string(what) + ": technique " + to_string(buffer_->technique()) +
                           " has no hash table (only ha)");
    return *ha;
  }

  // `f(container)` with the GIL released and no insert or clear running:
  // the library lets reading calls overlap each other, not a call that
  // changes the container (fragment_buffer.h). Returns what f returns (no
  // Python object: the GIL is not held).
  template <class F>
  auto read(F f) const {
    py::gil_scoped_release release;
    const std::unique_lock lock(access_);
    return f(static_cast<const FragmentBuffer&>(*buffer_));
  }

  py::dict insert(std::span<const Fragment> fragments, const InsertOptions& options) {
    Counters c;
    {
      py::gil_scoped_release release;
      const std::shared_lock changing(access_);  // inserts overlap as the library allows (its InsertGate)
      const auto t0 = std::chrono::steady_clock::now();
      c = buffer_->insert(fragments, options);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      const std::lock_guard lock(mutex_);
      totals_ += c;
      last_insert_ms_ = ms;
    }
    return counters_dict(c);
  }
  double last_insert_ms() {
    const std::lock_guard lock(mutex_);
    return last_insert_ms_;
  }
  py::dict totals() {
    const std::lock_guard lock(mutex_);
    return counters_dict(totals_);
  }
  std::uint64_t clear() {
    std::uint64_t held = 0;
    {
      py::gil_scoped_release release;
      const std::shared_lock changing(access_);
      held = buffer_->clear();
    }
    const std::lock_guard lock(mutex_);
    totals_ = {};
    return held;
  }
  void set_totals(const Counters& c) { totals_ = c; }
  py::dict build_report;  // habuffer.build()'s attempts; empty for a Buffer made empty

 private:
  std::unique_ptr<FragmentBuffer> buffer_;
  // Shared by the calls that change the container (the library orders them
  // itself), exclusive for the calls that read it.
  mutable std::shared_mutex access_;
  std::mutex mutex_;
  Counters totals_;
  double last_insert_ms_ = 0.0;
};

// Every pixel's list, row-major, as CSR: offsets (area + 1), then each
// entry's code, data and age.
struct Csr {
  std::vector<std::uint64_t> offsets;
  std::vector<std::uint32_t> codes, data, ages;
};

Csr read_lists(const FragmentBuffer& b) {
  Csr csr;
  const Extent v = b.screen();
  csr.offsets.reserve(v.area() + 1);
  csr.offsets.push_back(0);
  std::vector<ListEntry> list;
  for (std::uint32_t y = 0; y < v.y; ++y)
    for (std::uint32_t x = 0; x < v.x; ++x) {
      b.list(x, y, list);
      for (const ListEntry& e : list) {
        csr.codes.push_back(e.code);
        csr.data.push_back(e.data);
        csr.ages.push_back(e.age);
      }
      csr.offsets.push_back(csr.codes.size());
    }
  return csr;
}

py::array_t<float> composite(const Buffer& self, py::handle background, const IntArg& threads_obj) {
  const std::uint32_t threads = threads_arg(threads_obj);
  const FragmentBuffer& b = self.get();
  const Extent v = b.screen();
  std::vector<glm::vec3> backgrounds;
  const auto bg = py::array_t<float, py::array::forcecast>::ensure(background);
  if (!bg) throw py::type_error("background: expected numbers of shape (3,) or (H, W, 3)");
  if (bg.ndim() == 1 && bg.shape(0) == 3) {
    backgrounds.assign(v.area(), glm::vec3(bg.at(0), bg.at(1), bg.at(2)));
  } else if (bg.ndim() == 3 && bg.shape(0) == v.y && bg.shape(1) == v.x && bg.shape(2) == 3) {
    const auto r = bg.unchecked<3>();
    backgrounds.reserve(v.area());
    for (py::ssize_t y = 0; y < bg.shape(0); ++y)
      for (py::ssize_t x = 0; x < bg.shape(1); ++x) backgrounds.emplace_back(r(y, x, 0), r(y, x, 1), r(y, x, 2));
  } else {
    throw py::value_error("background: expected (3,) or (" + std::to_string(v.y) + ", " + std::to_string(v.x) +
                          ", 3) float32, got " + shape_text(bg));
  }
  const std::vector<glm::vec4> image =
      self.read([&](const FragmentBuffer& c) { return c.composite_image(backgrounds, threads); });
  std::vector<float> flat(image.size() * 4);
  std::memcpy(flat.data(), image.data(), flat.size() * sizeof(float));
  return owned_array(std::move(flat)).reshape({static_cast<py::ssize_t>(v.y), static_cast<py::ssize_t>(v.x), py::ssize_t{4}});
}

py::array table_view(py::object self_obj) {
  const Buffer& self = self_obj.cast<const Buffer&>();
  const HaBuffer& ha = self.hash_table("table()");
  const HaBuffer::TableWords w = ha.table_words();
  const Extent t = ha.table();
  if (w.word_bytes == 8)
    return readonly_view(static_cast<const std::uint64_t*>(w.data), t.y, t.x, self_obj);
  return readonly_view(static_cast<const std::uint32_t*>(w.data), t.y, t.x, self_obj);
}

py::array max_age_view(py::object self_obj) {
  const Buffer& self = self_obj.cast<const Buffer&>();
  const MaxAgeTable& m = self.hash_table("max_age()").max_age();
  return readonly_view(m.ages().data(), m.cells().y, m.cells().x, self_obj);
}

py::dict attempt_dict(const BuildAttempt& a) {
  py::dict d;
  d["table"] = py::make_tuple(a.table.x, a.table.y);
  d["capacity"] = a.capacity;
  d["counters"] = counters_dict(a.counters);
  d["sized_for"] = a.sized_for;  // the count a regather was sized by (0 for a first attempt)
  d["ms"] = a.ms;
  return d;
}

std::unique_ptr<Buffer> build(py::handle xy, py::handle depth, py::handle rgba, py::handle coverage, const ConfigArgs& a,
                              const std::string& path, bool lossless, const IntArg& max_attempts_obj,
                              const IntArg& threads_obj, const std::string& mode, const std::string& order,
                              const py::kwargs& options) {
  const std::uint32_t max_attempts = u32_arg(max_attempts_obj, "max_attempts", 1, 1000);  // as --max-attempts
  const std::uint32_t threads = threads_arg(threads_obj);
  const TechniqueConfig config = technique_config_from(a, options);
  const OffsetSource offsets = offset_source_from(a);
  const InsertOptions insert = insert_options(threads, mode, order);
  const std::vector<Fragment> fragments = fragments_from(xy, depth, rgba, threads, coverage);
  const std::uint32_t attempts = lossless ? max_attempts : 1;
  TechniqueBuild built;
  py::dict report;
  const RenderPath which = path_arg(path);  // the one rule of every path= (ValueError naming the paths)
  if (which == RenderPath::Cpu) {
    py::gil_scoped_release release;
    built = build_technique(config, offsets, fragments, insert, ResizePolicy{}, attempts);
  } else if (which == RenderPath::Gl) {
    if (threads != 1 || mode != "auto" || order != "auto")
      throw py::value_error("threads, mode and order are the CPU path's: the GPU inserts (path='gl')");
    GlBuildInfo info;
    {
      py::gil_scoped_release release;  // before the context's lock: never wait for it holding the GIL
      const GlContextUse use;
      built = build_technique_on_gl(config, offsets, fragments, ResizePolicy{}, attempts, &info);
    }
    report["gl_renderer"] = info.renderer;
    report["gl_atomic_mode"] = info.atomic_mode;
    report["build_ms"] = info.build_ms;
#ifdef HABUFFER_WITH_VK
  } else {
    if (threads != 1 || mode != "auto" || order != "auto")
      throw py::value_error("threads, mode and order are the CPU path's: the GPU inserts (path='vk')");
    vk::VulkanBuildInfo info;
    try {
      py::gil_scoped_release release;
      const vk::VulkanContext context;  // headless: no GL context needed
      built = vk::build_technique_on_vulkan(context, config, offsets, fragments, ResizePolicy{}, attempts, &info);
    } catch (const vk::VulkanError& e) {
      throw DataError(std::string("path='vk': ") + e.what());
    }
    report["vk_device"] = info.device;
    report["vk_atomic_mode"] = info.atomic_mode;
    report["build_ms"] = info.build_ms;
#endif
  }
  if (lossless) {  // a lossless request that ended lossy: DataError, as the CLI's exit 1
    py::gil_scoped_release release;
    require_lossless(built, fragments, max_attempts, OptionSpelling::Keyword);
  }
  py::list tries;
  for (const BuildAttempt& t : built.attempts) tries.append(attempt_dict(t));
  report["attempts"] = tries;
  report["lossless"] = built.lossless();
  report["growth_limited"] = built.growth_limited;
  report["path"] = path;
  auto out = std::make_unique<Buffer>(std::move(built.buffer));
  out->set_totals(built.counters);
  out->build_report = report;
  return out;
}

std::unique_ptr<Buffer> make_buffer(const std::string& technique, py::object screen, py::object table,
                                    py::object layout, const std::string& offsets, const IntArg& seed,
                                    py::object offset_list, const py::kwargs& options) {
  const ConfigArgs a{technique, std::move(screen), std::move(table), std::move(layout), offsets, seed_arg(seed),
                     std::move(offset_list)};
  const TechniqueConfig c = technique_config_from(a, options);
  if (uses_pool(c.technique) && c.pool_capacity == 0)
    throw py::value_error("pool: an empty Buffer has no stream to size an automatic pool from: give "
                          "pool=N, or build from the stream with habuffer.build(..., pool='auto')");
  return std::make_unique<Buffer>(make_fragment_buffer(c, offset_source_from(a)));
}

py::dict insert_arrays(Buffer& self, py::handle xy, py::handle depth, py::handle rgba, py::handle coverage,
                       const IntArg& threads_obj, const std::string& mode, const std::string& order) {
  const std::uint32_t threads = threads_arg(threads_obj);
  const InsertOptions options = insert_options(threads, mode, order);
  const std::vector<Fragment> f = fragments_from(xy, depth, rgba, threads, coverage);
  return self.insert(f, options);
}

py::dict insert_in_place(Buffer& self, const py::array& frags, const IntArg& threads_obj, const std::string& mode,
                         const std::string& order) {
  const std::uint32_t threads = threads_arg(threads_obj);
  if (!frags.dtype().equal(fragment_dtype()))
    throw py::type_error("fragments: expected habuffer.FRAGMENT_DTYPE, got " + py::str(frags.dtype()).cast<std::string>());
  if (frags.ndim() != 1 || !(frags.flags() & py::array::c_style) || !frags.attr("flags").attr("aligned").cast<bool>())
    throw py::value_error("fragments: expected an aligned, C-contiguous 1-D array (numpy.ascontiguousarray), got "
                          "shape " + shape_text(frags));
  const std::span<const Fragment> f(static_cast<const Fragment*>(frags.data()), static_cast<std::size_t>(frags.shape(0)));
  return self.insert(f, insert_options(threads, mode, order));
}

py::object lists_csr(const Buffer& self) {
  if (!descriptor(self.get().technique()).stores_lists)
    throw py::type_error("lists(): technique " + to_string(self.get().technique()) +
                         " stores no lists (it blends every fragment into the image)");
  Csr csr = self.read([](const FragmentBuffer& b) { return read_lists(b); });
  const py::object Lists = py::module_::import("habuffer._habuffer").attr("Lists");
  return Lists(owned_array(std::move(csr.offsets)), owned_array(std::move(csr.codes)), owned_array(std::move(csr.data)),
               owned_array(std::move(csr.ages)));
}

constexpr const char* kInsertDoc =
    "Inserts fragments: xy (N, 2) uint32 pixels, depth (N,) float32 in [0, 1], rgba (N,) uint32 "
    "(R<<24|G<<16|B<<8|A; None: 0), coverage (N,) uint32 sample masks (bit s: sample s; None or 0: the whole "
    "pixel; read where samples is above 1). Any strides. The GIL is released: calls from several Python threads overlap "
    "as the library allows. threads: the call's own threads (0: the default count); mode: auto, serial, atomic or "
    "owner; order: auto, arrival or pixel. Returns the call's counters (dict).";

}  // namespace

void bind_buffers(py::module_& m) {
  m.attr("Lists") = py::module_::import("collections")
                        .attr("namedtuple")("Lists", py::make_tuple("offsets", "codes", "rgba", "ages"));
  py::class_<Buffer>(m, "Buffer",
                     "A technique's CPU container (habuffer.techniques() lists them). Options are the technique "
                     "option table's, named as the CLI's flags with underscores (layers=8, occupancy=True, "
                     "early_cull=0.99, pool='auto', age_bits=5, ...).")
      .def(py::init(&make_buffer),
           py::arg("technique") = "ha", py::kw_only(), py::arg("screen"), py::arg("table") = py::none(),
           py::arg("layout") = 64, py::arg("offsets") = "random", py::arg("seed") = 1,
           py::arg("offset_list") = py::none())
      .def("insert", &insert_arrays,
          py::arg("xy"), py::arg("depth"), py::arg("rgba") = py::none(), py::kw_only(),
          py::arg("coverage") = py::none(), py::arg("threads") = 1, py::arg("mode") = "auto",
          py::arg("order") = "auto", kInsertDoc)
      .def("insert_fragments", &insert_in_place,
          py::arg("fragments"), py::kw_only(), py::arg("threads") = 1, py::arg("mode") = "auto",
          py::arg("order") = "auto",
          "insert() from one aligned, C-contiguous array of habuffer.FRAGMENT_DTYPE, read in place (no copy): no "
          "thread may write to it during the call.")
      .def("lists", &lists_csr,
          "Every pixel's list, nearest first, pixels row-major (y, then x) as CSR: Lists(offsets (W*H + 1,) uint64, "
          "codes, rgba, ages (uint32; ages 0 for techniques other than ha)). Pixel (x, y)'s entries are "
          "[offsets[y*W + x], offsets[y*W + x + 1]). With samples=S above 1 each code is the record's code "
          "field: the depth code shifted left by S, the coverage mask in its low S bits (codes >> S, codes & "
          "(2**S - 1); the lists CSV writes them as two columns).")
      .def("composite_image", &composite, py::arg("background") = py::make_tuple(1.0f, 1.0f, 1.0f),
           py::arg("threads") = 0,
           "Front-to-back compositing over `background` ((3,) or (H, W, 3) float32): (H, W, 4) float32, row y = 0 first.")
      .def("write_lists",
           [](const Buffer& self, const std::string& path) {
             self.read([&](const FragmentBuffer& b) {
               write_lists(path, b);
               return 0;
             });
           },
           py::arg("path"), "The lists CSV habuffer build-lists writes (x,y,rank,code,rgba), whole or not at all.")
      .def("clear", &Buffer::clear, "Empties the container and its counters; returns the records it held.")
      .def("count_stored",
           [](const Buffer& self) { return self.read([](const FragmentBuffer& b) { return b.count_stored(); }); })
      .def_property_readonly("counters", &Buffer::totals,
                             "Counters of every insert since the last clear (habuffer.build(): the final attempt's).")
      .def_property_readonly("technique", [](const Buffer& self) { return to_string(self.get().technique()); })
      .def_property_readonly("screen", [](const Buffer& self) {
        return py::make_tuple(self.get().screen().x, self.get().screen().y);
      })
      .def_property_readonly("capacity", [](const Buffer& self) { return self.get().capacity(); })
      .def_property_readonly("memory_bytes", [](const Buffer& self) { return self.get().memory_bytes(); })
      .def_property_readonly("config", [](const Buffer& self) { return config_dict(self.get().technique_config()); })
      .def_readonly("build_report", &Buffer::build_report)
      .def_property_readonly("last_insert_ms", &Buffer::last_insert_ms,
                             "Milliseconds the library's insert took in the last insert call, measured inside the "
                             "binding (the binding's overhead is a call's wall time less this).")
      .def("table", &table_view,
           "The HA-buffer's table T as a read-only (Hy, Hx) view of the container's storage (uint64 for layout 64, "
           "uint32 for 32): no copy; it keeps the buffer alive and sees later inserts.")
      .def("max_age", &max_age_view,
           "The max-age table M as a read-only (ceil(Vy/B), ceil(Vx/B)) uint32 view of the container's storage.")
      .def(
          "_table_address",
          [](const Buffer& self) {
            return reinterpret_cast<std::uintptr_t>(self.hash_table("_table_address()").table_words().data);
          },
          "The address of T's first slot in the container (the zero-copy check of table()).")
      .def(
          "_max_age_address",
          [](const Buffer& self) {
            return reinterpret_cast<std::uintptr_t>(self.hash_table("_max_age_address()").max_age().ages().data());
          },
          "The address of M's first cell in the container (the zero-copy check of max_age()).")
      .def("age_histogram",
           [](const Buffer& self) {
             const HaBuffer& ha = self.hash_table("age_histogram()");
             return owned_array(self.read([&](const FragmentBuffer&) { return ha.age_histogram(); }));
           },
           "Stored records per age, index a = 0..AMAX (ha only).");

  m.def(
      "build",
      [](py::handle xy, py::handle depth, py::handle rgba, py::handle coverage, const std::string& technique,
         py::object screen, py::object table, py::object layout, const std::string& offsets, const IntArg& seed,
         py::object offset_list, const std::string& path, bool lossless, const IntArg& max_attempts,
         const IntArg& threads, const std::string& mode, const std::string& order, const py::kwargs& options) {
        const ConfigArgs a{technique, std::move(screen), std::move(table), std::move(layout), offsets, seed_arg(seed),
                           std::move(offset_list)};
        return build(xy, depth, rgba, coverage, a, path, lossless, max_attempts, threads, mode, order, options);
      },
      py::arg("xy"), py::arg("depth"), py::arg("rgba") = py::none(), py::kw_only(), py::arg("coverage") = py::none(),
      py::arg("technique") = "ha",
      py::arg("screen"), py::arg("table") = py::none(), py::arg("layout") = 64, py::arg("offsets") = "random",
      py::arg("seed") = 1, py::arg("offset_list") = py::none(), py::arg("path") = "cpu", py::arg("lossless") = false,
      py::arg("max_attempts") = 16, py::arg("threads") = 1, py::arg("mode") = "auto", py::arg("order") = "auto",
      "A stream built into a new Buffer as habuffer build-lists builds it: on the CPU path or the GPU path "
      "(path='gl', a headless EGL context; GlError where none can be made; path='vk', a headless Vulkan device "
      "where the module has the Vulkan path; DataError where none can be used), lossless mode growing the container "
      "until nothing drops (at most max_attempts; both paths by one rule, which never grows for a pixel deeper "
      "than AMAX, since no table holds it). A lossless build that still drops raises DataError naming the pixel, "
      "AMAX, the attempts and max_attempts (or age_bits where growing cannot help). An automatic pool "
      "(pool='auto' or none) is sized from the stream. The result's build_report holds every attempt.");
}

}  // namespace habuffer::python
