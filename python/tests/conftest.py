"""pytest setup for the habuffer module's tests: the CLI to compare with
(--habuffer) and a work directory (--workdir); ctest passes both and puts the
build tree's package on PYTHONPATH."""

import os
import shutil
import subprocess
import sys
import tempfile

import pytest

sys.dont_write_bytecode = True
SPEC_MODEL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "spec_model")


def pytest_addoption(parser):
    parser.addoption("--habuffer", default=None, help="the habuffer CLI to compare with")
    parser.addoption("--workdir", default=None, help="where the tests write their files")


@pytest.fixture(scope="session")
def cli(request):
    exe = request.config.getoption("--habuffer") or shutil.which("habuffer")
    if not exe:
        pytest.skip("no habuffer CLI given (--habuffer)")

    def run(*args, check=True):
        r = subprocess.run([exe, *map(str, args)], capture_output=True, text=True, timeout=600)
        if check and r.returncode != 0:
            raise AssertionError("habuffer %s failed (%d): %s" % (" ".join(map(str, args)), r.returncode, r.stderr))
        return r

    return run


@pytest.fixture(scope="session")
def workdir(request):
    d = request.config.getoption("--workdir")
    if d:
        shutil.rmtree(d, ignore_errors=True)
        os.makedirs(d)
        return d
    return tempfile.mkdtemp(prefix="habuffer-pytest-")


@pytest.fixture(scope="session")
def gl_available():
    import habuffer as hb
    try:
        return hb.gl_info()
    except hb.GlError as e:
        pytest.skip("no OpenGL context: %s" % e)


@pytest.fixture(scope="session")
def vk_available():
    """Skips where the module has no Vulkan path (ValueError naming it) or no usable device (DataError)."""
    import habuffer as hb
    import numpy as np
    try:
        hb.build(np.zeros((1, 2), np.uint32), np.full(1, 0.5, np.float32), screen=(1, 1), path="vk")
    except ValueError as e:
        pytest.skip("no Vulkan path: %s" % e)
    except hb.DataError as e:
        # Only a missing loader or device skips: a shader or validation error fails the tests that need it.
        if "no Vulkan" in str(e) or "no usable" in str(e) or "cannot run the library" in str(e):
            pytest.skip("no Vulkan device: %s" % e)
        raise
    return True
