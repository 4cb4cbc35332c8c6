#!/usr/bin/env bash
# Install-and-consume test: installs the build tree into a temporary prefix,
# then, as a host project would:
#  - configures examples/ out of tree with find_package(habuffer CONFIG) and a
#    C++17 default (the package's targets must raise it to C++20), builds it
#    and runs every example headless (each checks its own pixels);
#  - checks the package refuses a newer version and an unknown component;
#  - adds the source tree to a C++17 host project by add_subdirectory, with
#    shared libraries and without oneTBB: only the libraries are made, the
#    host's build type is kept, both examples build and run;
#  - builds the CPU example of COMPONENTS core with pkg-config disabled
#    (core needs neither pkg-config nor libepoxy);
#  - checks that add_subdirectory sets habuffer_GLSL_DIR and leaves the
#    host's targets that do not link habuffer at C++17;
#  - builds the CPU example again through pkg-config alone (its Cflags
#    carry -std=c++20), and the Vulkan host through habuffer-vk.pc where
#    the package has the Vulkan path;
#  - checks the license (MIT) is installed and named by both packages;
#  - compiles every installed header on its own;
#  - checks that the installed headers define no macro outside HABUFFER_*;
#  - checks the installed GLSL files;
#  - imports the installed Python package (where built) and builds a list.
# Usage: consume.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) work=$3
rm -rf "$work"
mkdir -p "$work"
prefix=$work/prefix
fail() { echo "consume: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" >"$work/install.log"
echo "installed into $prefix:"
(cd "$prefix" && find . -type f | sed -E 's#/[^/]+\.(h|glsl)$#/*.\1#' | sort | uniq -c)

echo "== CMake package"
cmake -S "$source/examples" -B "$work/examples" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_STANDARD=17 -DCMAKE_CXX_EXTENSIONS=ON >"$work/configure.log" ||
  { cat "$work/configure.log"; fail "configuring the examples failed"; }
cmake --build "$work/examples" >"$work/build.log" 2>&1 || { cat "$work/build.log"; fail "building the examples failed"; }
"$work/examples/cpu_only" || fail "cpu_only failed"
"$work/examples/host_app" || fail "host_app failed"
"$work/examples/host_shadows" || fail "host_shadows failed"
"$work/examples/host_spot_shadows" || fail "host_spot_shadows failed"
"$work/examples/host_msaa" || fail "host_msaa failed"
# The Vulkan host, where the installation has the Vulkan path (its own
# instance and device; the validation layer, where installed, reports nothing).
has_vk=0
[ -f "$prefix/include/habuffer/vk.h" ] && has_vk=1
if [ "$has_vk" = 1 ]; then
  [ -x "$work/examples/host_vulkan" ] || fail "the package has the Vulkan path but find_package(COMPONENTS vk) built no host_vulkan"
  "$work/examples/host_vulkan" || fail "host_vulkan failed"
fi

echo "== a version the package must refuse"
mkdir -p "$work/too_new"
cat >"$work/too_new/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.22)
project(too_new LANGUAGES CXX)
find_package(habuffer 99.0 CONFIG REQUIRED COMPONENTS core)
CMAKE
if cmake -S "$work/too_new" -B "$work/too_new/build" -DCMAKE_PREFIX_PATH="$prefix" >"$work/too_new.log" 2>&1; then
  fail "find_package(habuffer 99.0) succeeded"
fi
cat >"$work/too_new/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.22)
project(no_component LANGUAGES CXX)
find_package(habuffer CONFIG REQUIRED COMPONENTS vulkan)
CMAKE
if cmake -S "$work/too_new" -B "$work/too_new/build2" -DCMAKE_PREFIX_PATH="$prefix" >"$work/no_component.log" 2>&1; then
  fail "find_package(habuffer COMPONENTS vulkan) succeeded"
fi
grep -q "no component 'vulkan'" "$work/no_component.log" || fail "the missing component is not named"

echo "== COMPONENTS core without pkg-config or libepoxy"
mkdir -p "$work/core_only"
cat >"$work/core_only/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.22)
project(core_only LANGUAGES CXX)
find_package(habuffer 0.1 CONFIG REQUIRED COMPONENTS core)
if(NOT habuffer_LICENSE STREQUAL "MIT" OR NOT EXISTS "\${habuffer_LICENSE_FILE}")
  message(FATAL_ERROR "the package names license '\${habuffer_LICENSE}', file '\${habuffer_LICENSE_FILE}'")
endif()
add_executable(cpu_only "$source/examples/cpu_only/main.cpp")
target_link_libraries(cpu_only PRIVATE habuffer::core)
CMAKE
cmake -S "$work/core_only" -B "$work/core_only/build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_DISABLE_FIND_PACKAGE_PkgConfig=ON -DPKG_CONFIG_EXECUTABLE=/nonexistent >"$work/core_only.log" 2>&1 ||
  { cat "$work/core_only.log"; fail "COMPONENTS core needed pkg-config"; }
cmake --build "$work/core_only/build" >>"$work/core_only.log" 2>&1 || { tail -40 "$work/core_only.log"; fail "COMPONENTS core: build failed"; }
"$work/core_only/build/cpu_only" >/dev/null || fail "COMPONENTS core: cpu_only failed"

if [ "$has_vk" = 1 ]; then
  echo "== COMPONENTS core vk (the GL path's dependencies come with vk)"
  mkdir -p "$work/vk_only"
  cat >"$work/vk_only/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.22)
project(vk_only LANGUAGES CXX)
find_package(habuffer 0.1 CONFIG REQUIRED COMPONENTS core vk)
add_executable(host_vulkan "$source/examples/host_vulkan/main.cpp")
target_link_libraries(host_vulkan PRIVATE habuffer::vk)
CMAKE
  cmake -S "$work/vk_only" -B "$work/vk_only/build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" >"$work/vk_only.log" 2>&1 ||
    { cat "$work/vk_only.log"; fail "COMPONENTS core vk: configuring failed"; }
fi

echo "== add_subdirectory into a C++17 host project (shared libraries, std::thread instead of oneTBB)"
mkdir -p "$work/subdir"
cat >"$work/subdir/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.22)
project(host LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 17)
set(BUILD_SHARED_LIBS ON)
set(HABUFFER_WITH_TBB OFF CACHE BOOL "")
set(HABUFFER_WITH_VULKAN OFF CACHE STRING "")  # the installed package builds the Vulkan host above
add_subdirectory("$source" habuffer)
if(NOT habuffer_GLSL_DIR)
  message(FATAL_ERROR "add_subdirectory does not set habuffer_GLSL_DIR")
endif()
file(WRITE "\${CMAKE_BINARY_DIR}/glsl_dir.txt" "\${habuffer_GLSL_DIR}")
# A target that does not link habuffer keeps the host's C++17.
file(WRITE "\${CMAKE_BINARY_DIR}/cxx17.cpp" "static_assert(__cplusplus == 201703L, \\"C++17\\");\\nint main() { return 0; }\\n")
add_executable(cxx17_probe "\${CMAKE_BINARY_DIR}/cxx17.cpp")
foreach(t habuffer habuffer_tests habuffer_gl_tests habuffer_bench habuffer_scene habuffer_render habuffer_harness)
  if(TARGET \${t})
    message(FATAL_ERROR "add_subdirectory made \${t}")
  endif()
endforeach()
if(CMAKE_BUILD_TYPE)
  message(FATAL_ERROR "the host's build type became \${CMAKE_BUILD_TYPE}")
endif()
add_executable(cpu_only "$source/examples/cpu_only/main.cpp")
target_link_libraries(cpu_only PRIVATE habuffer::core)
add_executable(host_app "$source/examples/host_app/main.cpp")
target_link_libraries(host_app PRIVATE habuffer::gl)
CMAKE
cmake -S "$work/subdir" -B "$work/subdir/build" -G Ninja >"$work/subdir.log" 2>&1 ||
  { cat "$work/subdir.log"; fail "add_subdirectory: configuring failed"; }
cmake --build "$work/subdir/build" >>"$work/subdir.log" 2>&1 || { tail -40 "$work/subdir.log"; fail "add_subdirectory: build failed"; }
"$work/subdir/build/cpu_only" >/dev/null || fail "add_subdirectory: cpu_only failed"
# grep reads ldd's whole output (no -q): under pipefail, grep -q leaving early
# could kill ldd with SIGPIPE and fail the pipeline on a match (seen once in CI load).
ldd "$work/subdir/build/cpu_only" >"$work/ldd.txt"
grep libhabuffer_core.so "$work/ldd.txt" >/dev/null || fail "add_subdirectory: libhabuffer_core is not shared"
! grep libtbb "$work/ldd.txt" >/dev/null || fail "add_subdirectory: oneTBB linked with HABUFFER_WITH_TBB=OFF"
"$work/subdir/build/host_app" >/dev/null || fail "add_subdirectory: host_app failed"
[ -f "$(cat "$work/subdir/build/glsl_dir.txt")/native32/ha.frag.glsl" ] || fail "add_subdirectory: habuffer_GLSL_DIR has no GLSL files"

echo "== pkg-config"
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig:$prefix/lib/x86_64-linux-gnu/pkgconfig
pkg-config --exists habuffer-core habuffer-gl || fail "pkg-config does not find habuffer-core and habuffer-gl"
# shellcheck disable=SC2046
c++ -O1 "$source/examples/cpu_only/main.cpp" -o "$work/cpu_only_pc" $(pkg-config --cflags --libs habuffer-core)
"$work/cpu_only_pc" >/dev/null || fail "cpu_only built through pkg-config failed"
[ -d "$(pkg-config --variable=glsldir habuffer-gl)" ] || fail "habuffer-gl's glsldir does not exist"
case "$(pkg-config --variable=glsldir habuffer-gl)" in *//*) fail "habuffer-gl's glsldir holds //";; esac
if [ "$has_vk" = 1 ]; then
  # shellcheck disable=SC2046
  c++ -O1 "$source/examples/host_vulkan/main.cpp" -o "$work/host_vulkan_pc" $(pkg-config --cflags --libs habuffer-vk) ||
    fail "host_vulkan does not build through pkg-config (habuffer-vk)"
  "$work/host_vulkan_pc" >/dev/null || fail "host_vulkan built through pkg-config failed"
fi

echo "== license"
grep -q "^MIT License" "$prefix/share/doc/habuffer/LICENSE" || fail "the license is not installed in share/doc/habuffer"
pcs="habuffer-core habuffer-gl"
[ "$has_vk" = 1 ] && pcs="$pcs habuffer-vk"
for pc in $pcs; do
  [ "$(pkg-config --variable=license $pc)" = MIT ] || fail "$pc does not name the MIT license"
done

echo "== every installed header compiles on its own"
find "$prefix/include/habuffer" -name '*.h' ! -path '*/shared/*' | sort >"$work/headers.txt"
[ -s "$work/headers.txt" ] || fail "no headers installed"
xargs -P 2 -I{} sh -c 'echo "#include \"{}\"" | c++ -std=c++20 -fsyntax-only -I"$1" -x c++ - || { echo "not self-contained: {}"; exit 255; }' \
  _ "$prefix/include" <"$work/headers.txt" || fail "a header does not compile on its own"
echo "$(wc -l <"$work/headers.txt") headers"

echo "== no macros outside HABUFFER_*"
baseline='#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>
#include <glm/glm.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>'
macros() { c++ -std=c++20 -dM -E -I"$prefix/include" -x c++ - | awk '{print $2}' | sed 's/(.*//' | sort -u; }
echo "$baseline" | macros >"$work/macros_baseline.txt"
printf '%s\n#include <habuffer/habuffer.h>\n#include <habuffer/gl.h>\n#include <habuffer/hash_kernel.h>\n#include <habuffer/techniques/linked_lists/detail/lists_kernel.h>\n#include <habuffer/techniques/arrays/detail/arrays_kernel.h>\n#include <habuffer/techniques/kbuffer/detail/kbuffer_kernel.h>\n#include <habuffer/techniques/blended/detail/blended_kernel.h>\n' "$baseline" |
  macros >"$work/macros_ours.txt"
comm -13 "$work/macros_baseline.txt" "$work/macros_ours.txt" | grep -v '^HABUFFER_' | grep -v '^_' >"$work/leaked.txt" || true
[ ! -s "$work/leaked.txt" ] || { cat "$work/leaked.txt"; fail "macros outside HABUFFER_* leak from the headers"; }

echo "== GLSL files"
for mode in native32 native64 emulated64; do
  for t in ha lists arrays sorted-lists kbuffer; do
    for stage in frag comp; do
      f=$prefix/share/habuffer/glsl/$mode/$t.$stage.glsl
      [ -s "$f" ] || fail "missing $f"
      ! grep -q '^#version' "$f" || fail "$f has a #version line"
    done
  done
  [ -f "$prefix/share/habuffer/glsl/$mode/extensions.glsl" ] || fail "missing $mode/extensions.glsl"
done
# The spatial hash's lookup, one file for every mode.
grep -q "habuffer_spatial_find(uvec3 key, out uint stored)" "$prefix/share/habuffer/glsl/spatial_lookup.glsl" ||
  fail "missing spatial_lookup.glsl or its habuffer_spatial_find"
echo "== Python package (where the build made it)"
if [ -f "$build/python/habuffer/__init__.py" ]; then
  pkg=$prefix/lib/python3/dist-packages
  for f in __init__.py __init__.pyi py.typed; do [ -f "$pkg/habuffer/$f" ] || fail "missing $pkg/habuffer/$f"; done
  (cd "$work" && PYTHONPATH=$pkg /usr/bin/python3 -c '
import numpy as np, habuffer as hb
assert hb.__file__.startswith("'"$pkg"'"), hb.__file__
b = hb.build(np.array([[0, 0], [0, 0]], np.uint32), np.array([0.5, 0.25], np.float32), screen=(2, 2))
assert b.counters["stored"] == 2 and list(b.lists().offsets) == [0, 2, 2, 2, 2]
') || fail "the installed Python package does not import or build"
fi
echo "consume: all passed"
