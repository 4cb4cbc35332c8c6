"""Builds the Python module habuffer for pip through the project's CMake.

pyproject.toml names setuptools as the backend; this file gives it the one
thing setuptools cannot do alone: the extension _habuffer is built by CMake
(target habuffer_python, which compiles the libraries it links), and the
package CMake assembles in <build>/python/habuffer (the extension, __init__.py,
__init__.pyi, py.typed) is copied whole into the wheel. The same files, from
the same rules, as `cmake --install` puts in dist-packages.

Environment:
  HABUFFER_CMAKE_BUILD_DIR  the CMake build directory (default: a folder under
                            setuptools' build-pip/; reused between installs)
  HABUFFER_CMAKE_ARGS       extra arguments to CMake's configure step
  CMAKE_BUILD_PARALLEL_LEVEL  build jobs (CMake's own variable)
"""

import os
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = os.path.dirname(os.path.abspath(__file__))
PACKAGE_FILES = ("__init__.py", "__init__.pyi", "py.typed")


def project_version():
    """The version of CMakeLists.txt's project(): one source for both."""
    path = os.path.join(SOURCE_DIR, "CMakeLists.txt")
    with open(path) as f:
        m = re.search(r"project\(\s*habuffer\s+VERSION\s+([0-9][0-9.]*)", f.read())
    if not m:
        sys.exit("setup.py: no 'project(habuffer VERSION x.y.z' in %s" % path)
    return m.group(1)


def require_tool(name, package):
    if shutil.which(name) is None:
        sys.exit("setup.py: '%s' not found on PATH: run scripts/setup.sh (Debian package %s)" % (name, package))


class CMakeExtension(Extension):
    """The extension CMake builds: no sources for setuptools to compile."""

    def __init__(self, name, target):
        super().__init__(name, sources=[])
        self.target = target


class CMakeBuild(build_ext):
    def run(self):
        for ext in self.extensions:
            self.build_cmake(ext)

    def cmake_build_dir(self):
        return os.path.abspath(os.environ.get("HABUFFER_CMAKE_BUILD_DIR") or os.path.join(self.build_temp, "cmake"))

    def build_cmake(self, ext):
        require_tool("cmake", "cmake")
        require_tool("ninja", "ninja-build")
        build_dir = self.cmake_build_dir()
        if os.path.exists(build_dir) and not os.path.isdir(build_dir):
            sys.exit("setup.py: the CMake build folder %s is a file, not a folder (HABUFFER_CMAKE_BUILD_DIR or "
                     "build-pip/): move it or name another" % build_dir)
        try:
            extra = shlex.split(os.environ.get("HABUFFER_CMAKE_ARGS", ""))
        except ValueError as e:
            sys.exit("setup.py: HABUFFER_CMAKE_ARGS %r cannot be split as a shell would: %s"
                     % (os.environ.get("HABUFFER_CMAKE_ARGS", "")[:200], e))
        bad = [a for a in extra if not a.startswith("-")]
        if bad:
            sys.exit("setup.py: HABUFFER_CMAKE_ARGS: %r is not a CMake option (they start with -, e.g. "
                     "-DHABUFFER_WITH_TBB=OFF)" % bad[0][:200])
        configure = [
            "cmake", "-S", SOURCE_DIR, "-B", build_dir, "-G", "Ninja",
            "-DCMAKE_BUILD_TYPE=Release",
            # The interpreter pip runs is the one the module is built for
            # (a virtual environment's python3 links to Debian's).
            "-DPython3_EXECUTABLE=" + sys.executable,
            "-DHABUFFER_WITH_PYTHON=ON",
            # The module links the CLI's libraries (harness, render, scene),
            # which HABUFFER_BUILD_APPS turns on; only its target is built.
            "-DHABUFFER_BUILD_APPS=ON",
            "-DHABUFFER_BUILD_TESTS=OFF",
            "-DHABUFFER_BUILD_BENCHMARKS=OFF",
            "-DHABUFFER_INSTALL=OFF",
        ] + extra
        self.announce("habuffer: " + " ".join(map(shlex.quote, configure)), level=2)
        # A failed step says which, once: CMake printed its reasons above.
        if subprocess.run(configure).returncode != 0:
            sys.exit("setup.py: CMake's configure step failed (its messages are above)%s"
                     % ("; HABUFFER_CMAKE_ARGS was %r" % " ".join(extra)[:200] if extra else ""))
        if subprocess.run(["cmake", "--build", build_dir, "--target", ext.target]).returncode != 0:
            sys.exit("setup.py: the CMake build of %s failed (its messages are above)" % ext.target)
        self.copy_package(build_dir, ext)

    def copy_package(self, build_dir, ext):
        built = os.path.join(build_dir, "python", "habuffer")
        module = os.path.basename(self.get_ext_filename(ext.name))
        expected = list(PACKAGE_FILES) + [module]
        missing = [f for f in expected if not os.path.isfile(os.path.join(built, f))]
        if missing:
            sys.exit("setup.py: the CMake build left no %s in %s (was it built for %s?)"
                     % (", ".join(missing), built, sys.executable))
        dest = os.path.dirname(self.get_ext_fullpath(ext.name))
        os.makedirs(dest, exist_ok=True)
        for f in expected:
            self.copy_file(os.path.join(built, f), os.path.join(dest, f))


# setuptools' own build folder, away from the CMake presets' build/ (egg_info
# needs it to exist before it runs).
if os.path.exists(os.path.join(SOURCE_DIR, "build-pip")) and not os.path.isdir(os.path.join(SOURCE_DIR, "build-pip")):
    sys.exit("setup.py: %s is a file, not setuptools' build folder: move it" % os.path.join(SOURCE_DIR, "build-pip"))
os.makedirs(os.path.join(SOURCE_DIR, "build-pip"), exist_ok=True)

setup(
    version=project_version(),
    ext_modules=[CMakeExtension("habuffer._habuffer", target="habuffer_python")],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-pip"}, "egg_info": {"egg_base": "build-pip"}},
    zip_safe=False,
)
