"""The package's surface: the type stub lists exactly what the module
exports (functions, classes, their public methods), and every call has a
docstring; pip settings that cannot work are refused in one line."""

import ast
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import habuffer as hb

STUB = os.path.join(os.path.dirname(hb.__file__), "__init__.pyi")


def stub_names():
    tree = ast.parse(open(STUB).read())
    top, methods = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            top.add(node.name)
        if isinstance(node, ast.ClassDef):
            methods[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        if isinstance(node, ast.AnnAssign):
            top.add(node.target.id)
    return top, methods


def test_the_stub_lists_every_export_and_nothing_else():
    top, methods = stub_names()
    exported = set(hb.__all__) | {"__version__"}
    assert exported <= top | {"FRAGMENT_DTYPE"}, exported - top
    for cls in ("Buffer", "SpatialHash"):
        real = {n for n in dir(getattr(hb, cls)) if not n.startswith("__") or n == "__len__"}
        real.discard("__init__")
        assert real == methods[cls] - {"__init__"}, (cls, real ^ (methods[cls] - {"__init__"}))


def test_every_call_has_a_docstring():
    for name in hb.__all__:
        obj = getattr(hb, name)
        if callable(obj) and name not in ("DataError", "GlError", "SceneError"):
            assert (obj.__doc__ or "").strip(), name


def test_the_figures_run_on_the_gpu_path(gl_available):
    t = hb.figure_fig10(4, size=(32, 32), repeats=1)
    assert t.title == "fig10" and t.rows > 0 and (t["failures"] == 0).all()
    f = hb.figure_fig2("hairball", opacities=[0.5], size=(32, 32), repeats=1)
    assert f.rows > 0


U64 = "18446744073709551615"


def integer_calls():
    """Every binding's unsigned integer parameter, given a value pybind11's own
    conversion would refuse with a dump of signatures (or pass on silently),
    and the error that names it and its range instead. Each is refused before
    any work (no scene, no GL context)."""
    xy, depth = np.zeros((2, 2), np.uint32), np.full(2, 0.5, np.float32)
    buf = hb.Buffer(screen=(4, 4))
    frags = np.zeros(2, dtype=hb.FRAGMENT_DTYPE)
    return [
        (lambda: hb.SpatialHash((8, 8), threads=-1), "threads: -1 is outside 0..1024"),
        (lambda: hb.SpatialHash((8, 8), miss_filter_bits=4), "miss_filter_bits: 4 is not 0, 8 or 16"),
        (lambda: hb.SpatialHash((8, 8), miss_filter_bits=32), "miss_filter_bits: 32 is outside 0..16"),
        (lambda: hb.SpatialHash((8, 8), capacity=2**64), "capacity: 18446744073709551616 is outside 0.." + U64),
        (lambda: hb.Buffer(screen=(4, 4), seed=-1), "seed: -1 is outside 0.." + U64),
        (lambda: hb.build(xy, depth, screen=(4, 4), threads=-1), "threads: -1 is outside 0..1024"),
        (lambda: hb.build(xy, depth, screen=(4, 4), max_attempts=2**32), "max_attempts: 4294967296 is outside 1..1000"),
        (lambda: hb.build(xy, depth, screen=(4, 4), seed=2**64), "seed: 18446744073709551616 is outside 0.." + U64),
        (lambda: buf.insert(xy, depth, threads=5000), "threads: 5000 is outside 0..1024"),
        (lambda: buf.insert_fragments(frags, threads=2**40), "threads: 1099511627776 is outside 0..1024"),
        (lambda: buf.composite_image(threads=-3), "threads: -3 is outside 0..1024"),
        (lambda: hb.offsets((8, 8), -1), "count: -1 is outside 1..1048576"),
        (lambda: hb.offsets((8, 8), 4, seed=-2), "seed: -2 is outside 0.." + U64),
        (lambda: hb.age_experiment(trials=-1), "trials: -1 is outside 1..100000"),
        (lambda: hb.age_experiment(block=2**33), "block: 8589934592 is outside 1..65536"),
        (lambda: hb.age_experiment(age_bits=-1), "age_bits: -1 is outside 4..12"),
        (lambda: hb.key_experiment(count=-1), "count: -1 is outside 1.." + U64),
        (lambda: hb.key_experiment(misses=-1), "misses: -1 is outside 0..10000000"),
        (lambda: hb.key_experiment(seed=-1), "seed: -1 is outside 0.." + U64),
        (lambda: hb.sweep("planes", repeats=-1), "repeats: -1 is outside 1..1000"),
        (lambda: hb.sweep("planes", path="cpu", threads=-1), "threads: -1 is outside 0..1024"),
        (lambda: hb.bench(["planes"], seed=-1), "seed: -1 is outside 0.." + U64),
        (lambda: hb.frontier(["planes"], threads=2**32), "threads: 4294967296 is outside 0..1024"),
        (lambda: hb.plan("planes", trials=-1), "trials: -1 is outside 1..1000"),
        (lambda: hb.plan("planes", age_bits=2**32), "age_bits: 4294967296 is outside 4..12"),
        (lambda: hb.figure_fig2("hairball", repeats=2**32), "repeats: 4294967296 is outside 1..1000"),
        (lambda: hb.figure_fig8(frames=-1), "frames: -1 is outside 2..100000"),
        (lambda: hb.figure_fig10(-1), "planes: -1 is outside 1..4096"),
        (lambda: hb.memory_table((8, 8), fragments=[100, -1]), "fragments[1]: -1 is outside 0.." + U64),
        (lambda: hb.voxelize("torus", grid=-1), "grid: -1 is outside 1..4096"),
        (lambda: hb.voxelize("torus", threads=-1), "threads: -1 is outside 0..1024"),
    ]


def test_every_integer_argument_out_of_range_is_refused_naming_it_and_its_range():
    for call, message in integer_calls():
        with pytest.raises(ValueError, match="^" + re.escape(message) + "$"):
            call()


def test_an_integer_argument_of_another_type_is_refused_naming_it():
    with pytest.raises(TypeError, match=r"^repeats: expected an integer, got 1\.0$"):
        hb.sweep("planes", repeats=1.0)
    with pytest.raises(TypeError, match="^fragments\\[0\\]: expected an integer, got '9'$"):
        hb.memory_table((8, 8), fragments=["9"])


def test_a_target_psnr_that_is_not_a_finite_number_of_decibels_above_0_is_refused():
    for target in (-1.0, 0.0, float("inf"), float("nan")):
        with pytest.raises(ValueError, match="^target_psnr: .* is not a finite PSNR above 0 dB$"):
            hb.plan("planes", target_psnr=target)


@pytest.mark.parametrize("env, named", [
    ({"HABUFFER_CMAKE_ARGS": '"-DHABUFFER_WITH_TBB=OFF'}, "HABUFFER_CMAKE_ARGS"),
    ({"HABUFFER_CMAKE_ARGS": "WITH_TBB=OFF"}, "HABUFFER_CMAKE_ARGS"),
    ({"HABUFFER_CMAKE_BUILD_DIR": "FILE"}, "is a file"),
])
def test_pip_settings_that_cannot_work_are_one_line_without_a_traceback(env, named, workdir):
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    a_file = os.path.join(workdir, "a-file")
    open(a_file, "w").close()
    env = {k: (a_file if v == "FILE" else v) for k, v in env.items()}
    r = subprocess.run([sys.executable, "setup.py", "-q", "build_ext"], cwd=root, capture_output=True, text=True,
                       env=dict(os.environ, **env), timeout=300)
    assert r.returncode != 0
    assert "Traceback" not in r.stderr, r.stderr
    assert named in r.stderr, r.stderr
