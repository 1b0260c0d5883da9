"""The bounded memory every kept value of a plan lives in (``scanplan.io.kept.Kept``): at
most its size, the least recently used dropped first, a failed make keeping nothing, None a
value like any other, and safe to share between threads."""

from __future__ import annotations

import threading

import pytest

from scanplan.io.kept import MISSING, Kept


def test_the_least_recently_used_is_dropped_first():
    kept: Kept[str, int] = Kept(3)
    for i, key in enumerate("abc"):
        kept.put(key, i)
    assert kept.get("a") == 0  # now the most recently used
    kept.put("d", 3)
    assert list(kept) == ["c", "a", "d"] and "b" not in kept and len(kept) == 3
    assert kept.get("b") is MISSING and kept.get("b", None) is None
    kept.put("c", 9)  # put again: a new value, used most recently
    kept.put("e", 4)
    assert list(kept) == ["d", "c", "e"] and kept.get("c") == 9  # "a" dropped
    kept.clear()
    assert len(kept) == 0 and list(kept) == []


def test_a_value_is_made_once_and_a_failure_keeps_nothing():
    kept: Kept[str, object] = Kept(2)
    calls: list[str] = []

    def make(value):
        return lambda: calls.append("made") or value

    assert kept.made("x", make(None)) is None and kept.made("x", make(1)) is None
    assert calls == ["made"]  # None is a value kept, not a miss

    def fail():
        raise ValueError("refused")

    with pytest.raises(ValueError, match="refused"):
        kept.made("y", fail)
    assert "y" not in kept and kept.made("y", make(2)) == 2


def test_its_size_must_be_at_least_one():
    with pytest.raises(ValueError, match="at least 1"):
        Kept(0)


def test_threads_share_it_within_its_size():
    kept: Kept[int, int] = Kept(8)
    errors: list[BaseException] = []

    def work(offset: int) -> None:
        try:
            for i in range(2000):
                key = (i + offset) % 20
                assert kept.made(key, lambda k=key: k * k) == key * key
                list(kept)
        except BaseException as exc:  # reported below
            errors.append(exc)

    threads = [threading.Thread(target=work, args=(n,)) for n in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors and len(kept) <= 8


def test_a_copy_or_a_pickle_is_an_empty_memory_of_the_same_size():
    import copy
    import pickle

    kept = Kept(3)
    kept.put("a", 1)
    for twin in (copy.copy(kept), copy.deepcopy(kept), pickle.loads(pickle.dumps(kept))):
        assert isinstance(twin, Kept) and twin.size == 3 and len(twin) == 0
        assert twin.made("a", lambda: 2) == 2  # made again; the original keeps its own
    assert kept.get("a") == 1


def test_arrays_key_tells_arrays_by_dtype_shape_and_bytes():
    import numpy as np

    from scanplan.io.kept import arrays_key

    a = np.arange(6.0)
    assert arrays_key(a) == arrays_key(a.copy()) == arrays_key(a[::-1][::-1])
    assert arrays_key(a) != arrays_key(a.reshape(2, 3))
    assert arrays_key(a) != arrays_key(a.astype(np.float32))
    assert arrays_key(a, a) != arrays_key(a)
    b = a.copy()
    b[3] = np.nextafter(b[3], 10.0)  # one bit
    assert arrays_key(a) != arrays_key(b)
