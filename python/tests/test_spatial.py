"""The spatial hash from arrays: find, contains and erase against a dict."""

import re
import threading

import numpy as np
import pytest

import habuffer as hb


def random_keys(n, domain, seed=4):
    rng = np.random.default_rng(seed)
    keys = np.stack([rng.integers(0, d, n) for d in domain], axis=1).astype(np.uint32)
    return np.unique(keys, axis=0)


@pytest.mark.parametrize("filter_bits", [16, 8, 0])
@pytest.mark.parametrize("domain", [(300, 200), (40, 30, 20)])
def test_find_and_contains_agree_with_a_dict(domain, filter_bits):
    keys = random_keys(20000, domain)
    values = np.arange(len(keys), dtype=np.uint32) * 7
    h = hb.SpatialHash(domain, capacity=len(keys), miss_filter_bits=filter_bits)
    report = h.insert(keys, values)
    assert report["stored"] == len(keys) and report["lost"] == 0 and len(h) == len(keys)
    probe = random_keys(5000, domain, seed=9)
    truth = {tuple(k): v for k, v in zip(keys.tolist(), values.tolist())}
    got, found = h.find(probe)
    for k, v, f in zip(probe.tolist(), got.tolist(), found.tolist()):
        assert f == (tuple(k) in truth)
        assert v == truth.get(tuple(k), 0)
    np.testing.assert_array_equal(h.contains(probe), found)
    assert h.erase(keys[:100]) == 100 and not h.contains(keys[:100]).any()


def test_the_table_is_a_copy_that_a_rehash_leaves_valid():
    h = hb.SpatialHash((64, 64), capacity=10)
    h.insert(random_keys(100, (64, 64)))
    t = h.table()
    assert t.shape == (h.table_extent[1], h.table_extent[0])
    assert np.count_nonzero(t) == len(h) == h.stats()["keys"]
    before = t.copy()
    h.insert(random_keys(3000, (64, 64), seed=5))  # grows: new storage
    np.testing.assert_array_equal(t, before)
    assert h.table().size > t.size


def test_inserts_and_finds_from_several_python_threads_are_ordered():
    domain = (256, 256)
    keys = random_keys(40000, domain)
    h = hb.SpatialHash(domain, capacity=16)  # every insert below rehashes often
    parts = np.array_split(keys, 8)
    errors = []

    def insert(part):
        h.insert(part)

    def find():
        try:
            for _ in range(20):
                _, found = h.find(keys)
                assert found.sum() <= len(keys)
        except Exception as e:  # noqa: BLE001 - reported below
            errors.append(e)

    threads = [threading.Thread(target=insert, args=(p,)) for p in parts] + [threading.Thread(target=find)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors and len(h) == len(keys) and h.contains(keys).all()


def test_bad_keys_are_refused_naming_the_problem():
    h = hb.SpatialHash((16, 16))
    with pytest.raises(TypeError, match="keys: expected a uint32 array"):
        h.insert(np.zeros((3, 2), np.int32))
    with pytest.raises(ValueError, match=r"\(N, 2\) or \(N, 3\)"):
        h.insert(np.zeros((3, 4), np.uint32))
    with pytest.raises(ValueError, match="outside"):
        h.insert(np.array([[16, 0]], np.uint32))
    with pytest.raises(ValueError, match="values"):
        h.insert(np.zeros((3, 2), np.uint32), np.zeros(2, np.uint32))
    with pytest.raises(ValueError, match="rule"):
        hb.SpatialHash((4, 4), rule="median")


@pytest.mark.parametrize("kwargs, message", [
    ({"threads": 5000}, "threads: 5000 is outside 0..1024"),  # the CLI's --threads range
    ({"threads": -1}, "threads: -1 is outside 0..1024"),
    ({"seed": -1}, "seed: -1 is outside 0..18446744073709551615"),
    ({"seed": 2**64}, "seed: 18446744073709551616 is outside 0..18446744073709551615"),
    ({"age_bits": 2**32}, "age_bits: 4294967296 is outside 4..12"),
    ({"age_bits": 13}, "age_bits: 13 is outside 4..12"),
    ({"capacity": -5}, "capacity: -5 is outside 0..18446744073709551615"),
])
def test_integer_arguments_out_of_range_are_refused_naming_the_argument_and_its_range(kwargs, message):
    with pytest.raises(ValueError, match="^" + re.escape(message) + "$"):
        hb.SpatialHash((16, 16), **kwargs)


def test_integer_arguments_of_another_type_are_refused_naming_the_argument():
    with pytest.raises(TypeError, match=r"^threads: expected an integer, got 1\.5$"):
        hb.SpatialHash((16, 16), threads=1.5)
    with pytest.raises(TypeError, match="^seed: expected an integer, got True$"):
        hb.SpatialHash((16, 16), seed=True)
    h = hb.SpatialHash((16, 16), threads=np.uint16(1024), seed=np.uint64(2**64 - 1), age_bits=np.int8(12))
    assert len(h) == 0
    assert "threads: int = 0" in hb.SpatialHash.__init__.__doc__  # the signature still says int


def test_a_table_that_never_resizes_needs_a_capacity_at_once():
    with pytest.raises(ValueError, match="capacity: a table with adaptive=False"):
        hb.SpatialHash((64, 64), adaptive=False)
    keys = random_keys(100, (64, 64))
    h = hb.SpatialHash((64, 64), adaptive=False, capacity=len(keys))
    assert h.insert(keys)["stored"] == len(keys) and h.contains(keys).all()
