"""Statistics and harness tables from Python equal the CLI's for the same
seeds; tables are dicts of numpy arrays."""

import json
import os

import numpy as np
import pytest

import habuffer as hb


def cli_rows(cli, workdir, name, *args):
    out = os.path.join(workdir, name + ".json")
    cli("stats", *args, "--out", out, "--quiet")
    with open(out) as f:
        return json.load(f)["rows"]


def assert_table_equals_rows(table, rows):
    assert table.rows == len(rows)
    for key in rows[0]:
        got = list(table[key])
        want = [r[key] for r in rows]
        assert got == want, key


def test_the_age_experiment_equals_habuffer_stats_for_the_same_seeds(cli, workdir):
    rows = cli_rows(cli, workdir, "stats", "--screen", "48x32", "--table", "56x40", "--loads", "0.5,0.9,1.2",
                    "--trials", 4, "--seed", 17, "--stream", "coherent", "--probing", "all", "--policy", "all",
                    "--offsets", "all", "--age-bits", 6, "--block", 4)
    t = hb.age_experiment(screen=(48, 32), table=(56, 40), loads=[0.5, 0.9, 1.2], trials=4, seed=17,
                          stream="coherent", probing=["all"], policy=["all"], offsets=["all"], age_bits=6, block=4)
    assert t["mean_age"].dtype == np.float64 and t["max_age"].dtype == np.uint64
    assert_table_equals_rows(t, rows)


def test_hot_and_stacked_streams_match_the_cli_too(cli, workdir):
    for stream, extra in (("hot", []), ("stacked", ["--spread", "0.25"])):
        rows = cli_rows(cli, workdir, "stats_" + stream, "--screen", "32x32", "--loads", "0.8", "--trials", 2,
                        "--stream", stream, *extra, "--age-bits", 5)
        t = hb.age_experiment(screen=(32, 32), loads=[0.8], trials=2, stream=stream,
                              spread=0.25 if extra else 1.0, age_bits=5)
        assert_table_equals_rows(t, rows)


def test_the_key_experiment_equals_habuffer_stats_keys(cli, workdir):
    rows = cli_rows(cli, workdir, "keys", "--keys", "random", "--domain", "64x64x8", "--count", 3000,
                    "--loads", "0.6,0.95", "--trials", 2, "--misses", 500, "--seed", 5, "--policy", "robinhood,fcfs")
    t = hb.key_experiment(keys="random", domain=(64, 64, 8), count=3000, loads=[0.6, 0.95], trials=2, misses=500,
                          seed=5, policy=["robinhood", "fcfs"])
    assert_table_equals_rows(t, rows)


def test_statistics_arguments_are_checked():
    with pytest.raises(ValueError, match="unknown value .sideways. \(coherent, independent or all\)"):
        hb.age_experiment(probing=["sideways"])
    with pytest.raises(ValueError):
        hb.age_experiment(trials=0)
    with pytest.raises(ValueError, match="stream"):
        hb.age_experiment(stream="spiral")


def write_stream(path, n=6000, screen=(48, 32), seed=2):
    rng = np.random.default_rng(seed)
    with open(path, "w") as f:
        f.write("x,y,depth,rgba\n")
        for _ in range(n):
            f.write("%d,%d,%r,%d\n" % (rng.integers(0, screen[0]), rng.integers(0, screen[1]),
                                       float(np.float32(rng.random())), rng.integers(0, 2**32)))
    return path


def test_a_sweep_over_a_stream_is_the_clis_table(cli, workdir):
    stream = write_stream(os.path.join(workdir, "sweep_stream.csv"))
    out = os.path.join(workdir, "sweep.json")
    cli("sweep", "--fragments", stream, "--size", "48x32", "--loads", "0.5,0.9", "--repeats", 2, "--threads", 1,
        "--out", out, "--quiet")
    with open(out) as f:
        want = json.load(f)
    t = hb.sweep(stream, size=(48, 32), loads=[0.5, 0.9], repeats=2, path="cpu", threads=1)
    assert t.title == want.get("title", "sweep")
    rows = want["rows"]
    assert t.rows == len(rows)
    timed = {k for k in rows[0] if "ms" in k or "per_s" in k}
    for key in rows[0]:
        if key in timed:
            continue
        got = [None if isinstance(v, float) and np.isnan(v) else v for v in
               (t[key].tolist() if t[key].dtype != object else [x.tolist() if isinstance(x, np.ndarray) else x
                                                                 for x in t[key]])]
        assert got == [r[key] for r in rows], key


def test_bench_plan_and_the_memory_table_return_tables_of_arrays(workdir):
    stream = write_stream(os.path.join(workdir, "bench_stream.csv"), n=3000)
    t = hb.bench([stream], techniques=["ha", "lists", "kbuffer:k=4"], sizes=[(48, 32)], repeats=1, path="cpu",
                 threads=1, floors=False)
    assert list(t["technique"]) == ["ha", "lists", "kbuffer:k=4"]
    assert t["fragments"].dtype == np.int64 and (t["fragments"] == 3000).all()
    assert t["psnr"][0] > 100 and t["failures"][0] == 0  # ha is exact (float32 against the double reference)
    p = hb.plan(stream, size=(48, 32), trials=1, loads=[0.5, 0.8])
    assert p.notes["recommendation"] and p.rows > 0
    m = hb.memory_table((64, 64), fragments=[10000], loads=[0.5])
    assert m.rows > 0 and "technique" in m
    with pytest.raises(ValueError):
        hb.bench([stream], techniques=["nope"], sizes=[(48, 32)], path="cpu")


def test_a_scene_runs_on_the_gpu_path_through_the_modules_context(gl_available):
    t = hb.sweep("planes:count=4", size=(32, 32), loads=[0.8], repeats=1, path="gl")
    assert t.rows == 1 and t["fragments"][0] > 0


def test_voxelize_gives_the_clis_grid_as_a_dense_array(cli, workdir, gl_available):
    stats_path = os.path.join(workdir, "vox.json")
    cli("voxelize", "--mesh", "torus", "--grid", 32, "--out", os.path.join(workdir, "vox.grid"), "--stats",
        stats_path, "--quiet")
    with open(stats_path) as f:
        want = json.load(f)
    solid, stats = hb.voxelize("torus", grid=32, reference=True)
    assert solid.shape == (32, 32, 32) and solid.dtype == np.bool_
    assert int(solid.sum()) == stats["voxels"] == want["voxels"] > 0
    assert stats["reference"]["mismatches"] == 0
    assert not solid[:, 16, 16].any()  # the torus' hole is empty along z at the centre column
    cpu, _ = hb.voxelize("torus", grid=32, path="cpu")
    np.testing.assert_array_equal(cpu, solid)
    with pytest.raises(ValueError, match="axis"):
        hb.voxelize("torus", axis="w")


def test_harness_arguments_are_refused_as_the_cli_refuses_them():
    with pytest.raises(ValueError, match="repeats"):
        hb.figure_fig2("hairball", size=(16, 16), repeats=0)
    with pytest.raises(ValueError):
        hb.figure_fig2("hairball", size=(16, 16), tau=0.0)
    with pytest.raises(ValueError, match="threads"):
        hb.sweep("hairball", path="gl", threads=2)
    with pytest.raises(ValueError, match=r"not a load in \(0, 4\]"):
        hb.age_experiment(loads=[5.0])
    with pytest.raises(ValueError, match="gives no fragment"):
        hb.age_experiment(screen=(4, 4), loads=[0.01])
    with pytest.raises(TypeError, match="domain"):
        hb.key_experiment(domain="64x64")
