"""Containers from Python: lists equal habuffer build-lists byte for byte,
zero-copy views, dtype and shape checks, errors, threads."""

import json
import os
import sys
import threading

import numpy as np
import pytest

import habuffer as hb
from conftest import SPEC_MODEL

sys.path.insert(0, SPEC_MODEL)
import crosscheck  # noqa: E402  (the model's seeded cross-check cases)

CASES = range(1, 25)


def lists_csv(lists, screen):
    """The lists as habuffer build-lists writes them (x,y,rank,code,rgba)."""
    w, _ = screen
    out = ["x,y,rank,code,rgba\n"]
    offsets = lists.offsets
    for p in range(len(offsets) - 1):
        x, y = p % w, p // w
        for rank, i in enumerate(range(offsets[p], offsets[p + 1])):
            out.append("%d,%d,%d,%d,%d\n" % (x, y, rank, lists.codes[i], lists.rgba[i]))
    return "".join(out).encode()


def case_files(case, workdir):
    d = os.path.join(workdir, "case%d" % case["seed"])
    os.makedirs(d, exist_ok=True)
    crosscheck.write_case(case, d)
    return d


@pytest.mark.parametrize("seed", CASES)
def test_lists_equal_build_lists_byte_for_byte_on_the_crosscheck_streams(seed, cli, workdir):
    case = crosscheck.make_case(seed)
    d = case_files(case, workdir)
    screen = (case["Vx"], case["Vy"])
    cli("build-lists", "--in", os.path.join(d, "frags.csv"), "--out", os.path.join(d, "cli.csv"),
        "--screen", "%dx%d" % screen, "--table", "%dx%d" % (case["Hx"], case["Hy"]), "--layout", case["layout"],
        "--age-bits", case["A"], "--offsets", os.path.join(d, "offsets.csv"), "--block", case["B"],
        "--threads", 1, "--stats", os.path.join(d, "cli.json"))
    xy, depth, rgba = hb.read_fragments(os.path.join(d, "frags.csv"), screen)
    buf = hb.build(xy, depth, rgba, screen=screen, table=(case["Hx"], case["Hy"]), layout=case["layout"],
                   age_bits=case["A"], block=case["B"], offset_list=np.array(case["offsets"], dtype=np.uint32))
    with open(os.path.join(d, "cli.csv"), "rb") as f:
        want = f.read()
    assert lists_csv(buf.lists(), screen) == want
    buf.write_lists(os.path.join(d, "py.csv"))
    with open(os.path.join(d, "py.csv"), "rb") as f:
        assert f.read() == want
    with open(os.path.join(d, "cli.json")) as f:
        stats = json.load(f)
    for key in ("fragments", "stored", "duplicates", "invalid", "failed_age", "failed_iter"):
        assert buf.counters[key] == stats[key], key
    assert list(buf.age_histogram()[:stats["max_age"] + 1]) == stats["age_histogram"]


def valid_arrays(case):
    """A cross-check case's fragments of valid depth, as (xy, depth, rgba) arrays."""
    frags = [f for f in case["frags"] if f[2] == f[2] and 0.0 <= f[2] <= 1.0]
    xy = np.array([(f[0], f[1]) for f in frags], dtype=np.uint32)
    depth = np.array([f[2] for f in frags], dtype=np.float32)
    rgba = np.array([f[3] for f in frags], dtype=np.uint32)
    return xy, depth, rgba


@pytest.mark.parametrize("technique,options", [("lists", {"pool": "auto"}), ("arrays", {"layers": 2}),
                                               ("sorted-lists", {"pool": "auto"}), ("paged-lists", {})])
def test_every_exact_technique_gives_the_ha_buffers_lists_when_nothing_drops(technique, options):
    case = crosscheck.make_case(7)
    screen = (case["Vx"], case["Vy"])
    xy, depth, rgba = valid_arrays(case)
    ha = hb.build(xy, depth, rgba, screen=screen, lossless=True, max_attempts=40)
    other = hb.build(xy, depth, rgba, technique=technique, screen=screen, lossless=True, max_attempts=40, **options)
    assert ha.counters["failures"] == 0 and other.counters["failures"] == 0
    a, b = ha.lists(), other.lists()
    for name in ("offsets", "codes", "rgba"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    np.testing.assert_array_equal(ha.composite_image(), other.composite_image())


def small_stream(n=4000, screen=(32, 24), seed=3):
    rng = np.random.default_rng(seed)
    xy = np.stack([rng.integers(0, screen[0], n), rng.integers(0, screen[1], n)], axis=1).astype(np.uint32)
    depth = rng.random(n, dtype=np.float32)
    rgba = rng.integers(0, 2**32, n, dtype=np.uint32)
    return xy, depth, rgba


def test_the_table_view_is_the_containers_storage_read_only_and_keeps_the_buffer_alive():
    buf = hb.HaBuffer((32, 24), table=(40, 30))
    view = buf.table()
    assert view.shape == (30, 40) and view.dtype == np.uint64
    assert view.ctypes.data == buf._table_address()  # the container's own words, not a copy
    assert buf.table().ctypes.data == view.ctypes.data
    assert not view.flags.writeable
    with pytest.raises(ValueError):
        view[0, 0] = 1
    assert not view.any()
    xy, depth, rgba = small_stream(500)
    buf.insert(xy, depth, rgba)
    assert np.count_nonzero(view) == buf.count_stored()  # the earlier view sees the insert
    ages = buf.max_age()
    assert ages.ctypes.data == buf._max_age_address() and ages.max() >= 1
    del buf
    assert np.count_nonzero(view) > 0  # the view holds the buffer
    l32 = hb.HaBuffer((8, 8), layout=32)
    assert l32.table().dtype == np.uint32


def test_wrong_dtypes_are_refused_with_the_expected_one_named():
    buf = hb.HaBuffer((32, 24))
    xy, depth, rgba = small_stream(100)
    with pytest.raises(TypeError, match="depth: expected a float32 array"):
        buf.insert(xy, depth.astype(np.float64), rgba)
    with pytest.raises(TypeError, match="xy: expected a uint32 array.*got int64"):
        buf.insert(xy.astype(np.int64), depth, rgba)
    with pytest.raises(ValueError, match=r"xy: expected shape \(N, 2\), got \(100, 3\)"):
        buf.insert(np.zeros((100, 3), np.uint32), depth, rgba)
    with pytest.raises(ValueError, match="one row per fragment"):
        buf.insert(xy, depth[:50], rgba)
    with pytest.raises(TypeError, match="FRAGMENT_DTYPE"):
        buf.insert_fragments(np.zeros(4, np.uint32))
    assert buf.counters["fragments"] == 0  # nothing refused was inserted


def test_non_contiguous_arrays_insert_as_their_contiguous_copies():
    xy, depth, rgba = small_stream(2000)
    wide = np.zeros((2000, 4), np.uint32)
    wide[:, 1] = xy[:, 0]
    wide[:, 3] = xy[:, 1]
    strided_xy = wide[:, 1::2]
    assert not strided_xy.flags.c_contiguous
    a, b = hb.HaBuffer((32, 24)), hb.HaBuffer((32, 24))
    a.insert(xy, depth, rgba)
    b.insert(strided_xy, np.repeat(depth, 2)[::2], rgba)
    np.testing.assert_array_equal(a.table(), b.table())
    frags = np.zeros(4000, hb.FRAGMENT_DTYPE)[::2]
    with pytest.raises(ValueError, match="C-contiguous"):
        a.insert_fragments(frags)


def test_structured_fragments_insert_in_place_as_the_three_arrays_do():
    xy, depth, rgba = small_stream(3000)
    frags = np.zeros(len(depth), hb.FRAGMENT_DTYPE)
    frags["x"], frags["y"], frags["depth"], frags["rgba"] = xy[:, 0], xy[:, 1], depth, rgba
    a, b = hb.HaBuffer((32, 24)), hb.HaBuffer((32, 24))
    assert a.insert(xy, depth, rgba) == b.insert_fragments(frags)
    np.testing.assert_array_equal(a.table(), b.table())


def test_errors_carry_the_librarys_messages():
    with pytest.raises(IndexError, match="outside"):
        hb.HaBuffer((4, 4)).insert(np.array([[4, 0]], np.uint32), np.array([0.5], np.float32))
    with pytest.raises(ValueError, match="unknown 'nope'"):
        hb.Buffer("nope", screen=(4, 4))
    with pytest.raises(ValueError, match="layers does not apply to technique ha"):
        hb.Buffer("ha", screen=(4, 4), layers=3)
    with pytest.raises(ValueError, match="option layers: "):
        hb.Buffer("arrays", screen=(4, 4), layers=0)
    with pytest.raises(TypeError, match="unknown option 'colour'"):
        hb.Buffer("ha", screen=(4, 4), colour=1)
    with pytest.raises(ValueError, match="pool"):
        hb.Buffer("lists", screen=(4, 4))
    with pytest.raises(ValueError, match="occupancy"):
        hb.Buffer("kbuffer", screen=(4, 4), occupancy_words=2)
    with pytest.raises(ValueError, match="screen"):
        hb.HaBuffer("4y4")
    with pytest.raises(TypeError, match="no hash table"):
        hb.Buffer("arrays", screen=(4, 4)).table()
    with pytest.raises(hb.DataError):
        hb.read_fragments("/nonexistent/frags.csv", (4, 4))


def test_counters_account_for_every_fragment_and_clear_empties():
    xy, depth, rgba = small_stream(5000)
    depth[:10] = np.nan
    buf = hb.HaBuffer((32, 24), table=(36, 27))
    c = buf.insert(xy, depth, rgba, threads=2)
    assert c["fragments"] == 5000 and c["invalid"] == 10
    assert c["stored"] == buf.count_stored() == np.count_nonzero(buf.table())
    assert sum(v for k, v in c.items() if k not in ("fragments", "stored", "failures")) + c["stored"] == 5000
    assert buf.counters == c
    assert buf.clear() == c["stored"] and buf.count_stored() == 0 and buf.counters["fragments"] == 0


def test_calls_from_several_python_threads_overlap_and_add_up_to_one_call():
    xy, depth, rgba = small_stream(40000, screen=(64, 64))
    whole = hb.HaBuffer((64, 64), table=(256, 256))  # load 0.6: no failure, so any schedule gives one table
    whole.insert(xy, depth, rgba)
    shared = hb.HaBuffer((64, 64), table=(256, 256))
    parts = np.array_split(np.arange(len(depth)), 4)
    threads = [threading.Thread(target=shared.insert, args=(xy[p], depth[p], rgba[p]), kwargs={"mode": "atomic"})
               for p in parts]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert whole.counters["failures"] == 0
    assert shared.counters == whole.counters
    np.testing.assert_array_equal(shared.table(), whole.table())


def test_config_round_trips_the_option_table():
    buf = hb.Buffer("kbuffer", screen=(16, 8), layers=6, occupancy=True, occupancy_words=2)
    cfg = buf.config
    assert cfg["technique"] == "kbuffer" and cfg["screen"] == (16, 8)
    assert cfg["layers"] == 6 and cfg["occupancy"] is True and cfg["occupancy_words"] == 2
    names = [t["name"] for t in hb.techniques()]
    assert "ha" in names and "paged-lists" in names
    offs = hb.offsets((40, 30), 15, "farthest", 2)
    assert offs.shape == (15, 2) and offs.dtype == np.uint32 and (offs[:, 0] < 40).all()


def test_the_gpu_path_builds_the_cpu_paths_lists(gl_available):
    case = crosscheck.make_case(11)
    screen = (case["Vx"], case["Vy"])
    xy, depth, rgba = valid_arrays(case)
    cpu = hb.build(xy, depth, rgba, screen=screen, lossless=True)
    gpu = hb.build(xy, depth, rgba, screen=screen, lossless=True, path="gl")
    assert gpu.build_report["path"] == "gl" and gpu.build_report["gl_renderer"]
    for name in ("offsets", "codes", "rgba"):
        np.testing.assert_array_equal(getattr(cpu.lists(), name), getattr(gpu.lists(), name))


def test_the_vulkan_path_builds_the_cpu_paths_lists_for_every_technique_it_runs(vk_available):
    case = crosscheck.make_case(12)
    screen = (case["Vx"], case["Vy"])
    xy, depth, rgba = valid_arrays(case)
    for technique, options in (("ha", {}), ("lists", {}), ("sorted-lists", {}), ("arrays", {"layers": 3}),
                               ("kbuffer", {"layers": 4}), ("paged-lists", {})):
        # arrays grow K losslessly: a full pixel keeps its first arrivals, in the device's order
        lossless = technique != "kbuffer"
        cpu = hb.build(xy, depth, rgba, screen=screen, technique=technique, lossless=lossless, **options)
        vk = hb.build(xy, depth, rgba, screen=screen, technique=technique, lossless=lossless, path="vk", **options)
        assert vk.build_report["path"] == "vk" and vk.build_report["vk_device"], technique
        assert vk.build_report["vk_atomic_mode"] in ("native64", "native32", "emulated64"), technique
        assert vk.counters == cpu.counters, technique
        for name in ("offsets", "codes", "rgba"):
            np.testing.assert_array_equal(getattr(cpu.lists(), name), getattr(vk.lists(), name), err_msg=technique)
    with pytest.raises(ValueError, match="threads, mode and order are the CPU path's"):
        hb.build(xy, depth, rgba, screen=screen, path="vk", threads=2)
    with pytest.raises(hb.DataError, match="does not run wboit yet"):
        hb.build(xy, depth, rgba, screen=screen, path="vk", technique="wboit")


def deep_pixel_stream(screen=(8, 8), others=200, seed=5):
    """300 distinct depths at pixel (3, 5), more than AMAX = 255 at the default 8 age bits, and `others`
    fragments in rows 0..2."""
    rng = np.random.default_rng(seed)
    deep = np.tile(np.array([[3, 5]], np.uint32), (300, 1))
    rest = np.stack([rng.integers(0, screen[0], others), rng.integers(0, 3, others)], axis=1).astype(np.uint32)
    depth = np.concatenate([(np.arange(300, dtype=np.float32) + 0.5) / 300, rng.random(others, dtype=np.float32)])
    return np.concatenate([deep, rest]), depth, np.full(len(depth), 0x336699FF, np.uint32)


def test_a_lossless_build_stopped_where_growing_cannot_help_raises_naming_the_pixel_age_bits_and_max_attempts():
    xy, depth, rgba = deep_pixel_stream()
    with pytest.raises(hb.DataError, match=r"after 1 attempt: pixel \(3, 5\) has 300 distinct fragments, more than "
                                           r"AMAX = 2\^8 - 1 = 255, .*use age_bits=9 .*\(max_attempts=16\)"):
        hb.build(xy, depth, rgba, screen=(8, 8), lossless=True)
    lossy = hb.build(xy, depth, rgba, screen=(8, 8))  # no lossless request: the loss is the result's, no error
    assert lossy.counters["failures"] > 0 and len(lossy.build_report["attempts"]) == 1


def test_a_lossless_build_still_lossy_after_max_attempts_raises_naming_the_pixel_amax_and_max_attempts():
    # 4000 depths at one pixel fit AMAX 4095 (age bits 12): the table could grow, but one attempt cannot hold
    # them (a second, sized for the first one's count, does).
    xy = np.tile(np.array([[1, 2]], np.uint32), (4000, 1))
    depth = (np.arange(4000, dtype=np.float32) + 0.5) / 4000
    with pytest.raises(hb.DataError, match=r"after 1 attempt \(last table \d+x\d+; AMAX = 2\^12 - 1 = 4095\): "
                                           r"pixel \(1, 2\) lost the most, \d+ of its 4000 distinct records: "
                                           r"raise max_attempts above 1$"):
        hb.build(xy, depth, screen=(4, 4), age_bits=12, lossless=True, max_attempts=1)
    assert len(hb.build(xy, depth, screen=(4, 4), age_bits=12, lossless=True, max_attempts=2)
               .build_report["attempts"]) == 2


def test_both_paths_stop_a_lossless_build_alike_on_a_pixel_deeper_than_amax(gl_available):
    xy, depth, rgba = deep_pixel_stream()
    for path in ("cpu", "gl"):
        with pytest.raises(hb.DataError) as e:
            hb.build(xy, depth, rgba, screen=(8, 8), lossless=True, path=path)
        message = str(e.value)
        assert "after 1 attempt: pixel (3, 5) has 300 distinct fragments" in message, (path, message)
        assert "use age_bits=9" in message and "(max_attempts=16)" in message, (path, message)
    for path in ("cpu", "gl"):  # without lossless mode: one attempt each, no error
        assert len(hb.build(xy, depth, rgba, screen=(8, 8), path=path).build_report["attempts"]) == 1


def test_gpu_calls_from_two_python_threads_share_the_modules_context(gl_available):
    xy, depth, rgba = small_stream(500)
    results = []

    def build_on_gl():
        results.append(hb.build(xy, depth, rgba, screen=(32, 24), path="gl").counters["stored"])

    for _ in range(2):  # one after the other, each on a thread of its own
        t = threading.Thread(target=build_on_gl)
        t.start()
        t.join()
    build_on_gl()  # and on this thread
    assert len(results) == 3 and len(set(results)) == 1 and results[0] > 0


class ArrayLike:
    """Something numpy reads as an array (as pandas and tensors are)."""

    def __init__(self, a):
        self.a = a

    def __array__(self, dtype=None):
        return self.a if dtype is None else self.a.astype(dtype)


def test_array_likes_obey_the_dtype_rule_and_lists_are_checked_to_fit():
    buf = hb.HaBuffer((32, 24))
    xy, depth, rgba = small_stream(10)
    with pytest.raises(TypeError, match="xy: expected a uint32 array.*got int64"):
        buf.insert(ArrayLike(xy.astype(np.int64) + 2**32), depth, rgba)  # would wrap to the same pixels
    with pytest.raises(TypeError, match="depth: expected a float32 array.*got float64"):
        buf.insert(xy, ArrayLike(depth.astype(np.float64)), rgba)
    with pytest.raises(ValueError, match=r"xy: values must lie in \[0, 4294967295\]"):
        buf.insert([[0, -1]], [0.5])
    with pytest.raises(TypeError, match="xy: expected integers"):
        buf.insert([[0.5, 1.7]], [0.5])
    c = buf.insert([[1, 2], [3, 4]], [0.5, 0.25], [7, 9])  # Python lists of numbers are converted
    assert c["stored"] == 2 and buf.counters["fragments"] == 2
    assert buf.insert(ArrayLike(xy), ArrayLike(depth), ArrayLike(rgba))["fragments"] == 10
    frags = np.zeros(8, hb.FRAGMENT_DTYPE)
    unaligned = np.frombuffer(b"\0" * (hb.FRAGMENT_DTYPE.itemsize * 4 + 4), hb.FRAGMENT_DTYPE, count=4, offset=4)
    assert buf.insert_fragments(frags)["fragments"] == 8
    if not unaligned.flags.aligned:
        with pytest.raises(ValueError, match="aligned"):
            buf.insert_fragments(unaligned)


def test_options_take_numpy_scalars_and_refuse_what_the_cli_refuses():
    k = hb.Buffer("kbuffer", screen=(8, 8), layers=np.int64(6))
    assert k.config["layers"] == 6
    assert hb.Buffer("ha", screen=(8, 8), saturation=False).config["saturation"] is False  # off needs nothing
    with pytest.raises(ValueError, match="saturation"):
        hb.Buffer("ha", screen=(8, 8), saturation=True)
    with pytest.raises(TypeError, match="early_cull: expected a number"):
        hb.Buffer("ha", screen=(8, 8), early_cull=True)
    assert hb.Buffer("ha", screen=(8, 8), early_cull=np.float32(0.5)).config["early_cull"] == 0.5
    with pytest.raises(TypeError, match="depth_range"):
        hb.Buffer("kbuffer", screen=(8, 8), depth_range=0.5)
    with pytest.raises(ValueError, match="positive sides"):
        hb.HaBuffer((0, 4))


def test_reading_calls_wait_for_inserts_from_other_python_threads():
    xy, depth, rgba = small_stream(200000, screen=(64, 64))
    buf = hb.Buffer("lists", screen=(64, 64), pool=250000)
    parts = np.array_split(np.arange(len(depth)), 8)
    seen = []

    def read():
        for _ in range(20):
            lists = buf.lists()
            seen.append(int(lists.offsets[-1]))

    threads = [threading.Thread(target=buf.insert, args=(xy[p], depth[p], rgba[p])) for p in parts]
    threads.append(threading.Thread(target=read))
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert seen == sorted(seen)  # every read saw whole inserts, never a list half written
    assert buf.lists().offsets[-1] == buf.counters["stored"]


def test_gpu_calls_overlapping_from_two_threads_do_not_deadlock(gl_available):
    done = []

    def sweep():
        done.append(hb.sweep("planes:count=8", size=(32, 32), loads=[0.8], repeats=1, path="gl").rows)

    def info():
        for _ in range(20):
            done.append(hb.gl_info()["renderer"])

    threads = [threading.Thread(target=sweep), threading.Thread(target=info), threading.Thread(target=sweep)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)
    assert not any(t.is_alive() for t in threads), "a GL call deadlocked"
    assert len(done) == 22


def test_multisampled_buffers_keep_each_fragments_coverage_mask_and_refuse_bad_sample_counts():
    """samples=4 (issue 37): FRAGMENT_DTYPE's coverage field is each fragment's mask; two halves of a
    pixel at one depth and colour make the whole pixel, a quarter blends into a quarter of it."""
    frags = np.zeros(3, hb.FRAGMENT_DTYPE)
    frags["x"], frags["y"] = [1, 1, 2], [1, 1, 1]
    frags["depth"], frags["rgba"] = [0.5, 0.5, 0.5], 0xFF0000FF  # opaque red
    frags["coverage"] = [0b0011, 0b1100, 0b0001]
    for technique, extra in [("ha", {}), ("lists", {"pool": 16}), ("arrays", {"layers": 4})]:
        buf = hb.Buffer(technique, screen=(4, 4), samples=4, **extra)
        c = buf.insert_fragments(frags)
        assert c["stored"] == 3 and c["duplicates"] == 0, technique
        image = buf.composite_image((1.0, 1.0, 1.0))
        assert np.array_equal(image[1, 1], [1.0, 0.0, 0.0, 1.0]), technique
        assert np.array_equal(image[1, 2], [1.0, 0.75, 0.75, 0.25]), technique
    with pytest.raises(ValueError, match="option samples: 3 is not a power of two in 1..8"):
        hb.Buffer("ha", screen=(4, 4), samples=3)
    with pytest.raises(ValueError, match="wboit stores none"):
        hb.Buffer("wboit", screen=(4, 4), samples=4)


def test_a_jump_of_depth_complexity_is_lossless_in_one_regather_sized_by_the_failed_attempts_count(gl_available):
    # 40 full-screen layers into a table of the screen (load 40): the failed
    # attempt counted every fragment it received, and the regather's table
    # holds them at the middle of the 80/30 band, on both paths.
    w, h, layers = 16, 16, 40
    ys, xs = np.mgrid[0:h, 0:w]
    xy = np.concatenate([np.stack([xs.ravel(), ys.ravel()], axis=1)] * layers).astype(np.uint32)
    order = (7 * np.repeat(np.arange(layers), w * h) + np.tile(xs.ravel() + ys.ravel(), layers)) % layers
    depth = ((order + 0.5) / layers).astype(np.float32)
    rgba = np.full(len(depth), 0x80808080, dtype=np.uint32)
    for path in ("cpu", "gl") if gl_available else ("cpu",):
        b = hb.build(xy, depth, rgba, screen=(w, h), table=(w, h), lossless=True, path=path)
        attempts = b.build_report["attempts"]
        assert len(attempts) == 2, (path, attempts)
        assert attempts[0]["counters"]["failures"] > 0 and attempts[0]["sized_for"] == 0
        assert attempts[1]["sized_for"] == w * h * layers, path
        assert attempts[1]["counters"]["failures"] == 0
        tx, ty = attempts[1]["table"]
        assert 0.5 <= w * h * layers / (tx * ty) <= 0.55, (path, attempts[1]["table"])


def test_a_stream_with_coverage_masks_builds_as_build_lists_builds_it_and_is_never_read_without_them(cli, workdir):
    d = os.path.join(workdir, "coverage")
    os.makedirs(d, exist_ok=True)
    screen = (16, 12)
    xy, depth, rgba = small_stream(1500, screen, seed=11)
    masks = np.random.default_rng(5).integers(0, 64, len(depth), dtype=np.uint32)  # 0: the whole pixel; 16: none of 4
    frags = os.path.join(d, "frags.csv")
    with open(frags, "w") as f:
        f.write("x,y,depth,rgba,coverage\n")
        for (x, y), t, c, m in zip(xy, depth, rgba, masks):
            f.write("%d,%d,%r,0x%08x,0x%02x\n" % (x, y, float(t), c, m))
    cli("build-lists", "--in", frags, "--out", os.path.join(d, "cli.csv"), "--screen", "16x12", "--samples", 4,
        "--table", "24x18", "--threads", 1)
    with pytest.raises(ValueError, match="coverage=True"):
        hb.read_fragments(frags, screen)
    xy2, depth2, rgba2, coverage = hb.read_fragments(frags, screen, coverage=True)
    assert (coverage == masks).all()
    buf = hb.build(xy2, depth2, rgba2, coverage=coverage, screen=screen, table=(24, 18), samples=4)
    buf.write_lists(os.path.join(d, "py.csv"))
    with open(os.path.join(d, "cli.csv"), "rb") as a, open(os.path.join(d, "py.csv"), "rb") as b:
        assert a.read() == b.read()
    whole = hb.build(xy2, depth2, rgba2, screen=screen, table=(24, 18), samples=4)
    assert whole.counters["invalid"] == 0 and buf.counters["invalid"] > 0  # masks naming none of the 4 samples
