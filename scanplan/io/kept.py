"""A bounded memory of values by key: what a plan keeps for the next one.

The page re-plans on every edit, and a plan asks the same things many times (a DEM's
header, a transformer, the resolving power at a height, a norm set read): each of these is
kept in a :class:`Kept`, at most ``size`` values, the one used least recently dropped
first. Only values that are a function of their key are kept, so what is dropped is made
again, the same.
"""

from __future__ import annotations

import hashlib
import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable, Iterator
from typing import Any, Generic, TypeVar

__all__ = ["MISSING", "Kept", "arrays_key"]

K = TypeVar("K", bound=Hashable)
V = TypeVar("V")

MISSING: object = object()
"""What :meth:`Kept.get` gives by default for a key not kept (None may be a value kept)."""


def arrays_key(*arrays: Any) -> bytes:
    """A key for values computed from numpy arrays: a digest of each array's dtype, shape
    and bytes (arrays equal in all three give the same key).

    >>> import numpy as np
    >>> arrays_key(np.arange(3.0)) == arrays_key(np.array([0.0, 1.0, 2.0]))
    True
    >>> arrays_key(np.arange(3.0)) == arrays_key(np.arange(3))
    False
    """
    import numpy as np

    digest = hashlib.blake2b(digest_size=20)
    for a in arrays:
        a = np.ascontiguousarray(a)
        digest.update(f"{a.dtype.str}{a.shape}".encode())
        digest.update(a.tobytes())
    return digest.digest()


class Kept(Generic[K, V]):
    """At most ``size`` values by key, the least recently used dropped first.

    Safe to share between threads (the page serves several requests at once): each look-up
    and each insertion holds the memory's lock; a value is made outside it, so two threads
    may make the same value, and the later one is kept.

    Parameters
    ----------
    size : int
        How many values are kept (≥ 1).

    Examples
    --------
    >>> kept = Kept(2)
    >>> kept.made("a", lambda: 1), kept.made("b", lambda: 2), kept.get("a")
    (1, 2, 1)
    >>> kept.put("c", 3)  # "b", used least recently, is dropped
    3
    >>> sorted(kept), kept.get("b", None)
    (['a', 'c'], None)
    """

    __slots__ = ("_items", "_lock", "size")

    def __init__(self, size: int) -> None:
        if size < 1:
            raise ValueError("Kept: size must be at least 1")
        self.size = size
        self._items: OrderedDict[K, V] = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key: K, default: object = MISSING) -> V | object:
        """The value kept for ``key`` (now the most recently used), else ``default``."""
        with self._lock:
            try:
                value = self._items[key]
            except KeyError:
                return default
            self._items.move_to_end(key)
            return value

    def put(self, key: K, value: V) -> V:
        """Keep ``value`` for ``key`` (dropping the least recently used beyond the size);
        returns ``value``."""
        with self._lock:
            self._items[key] = value
            self._items.move_to_end(key)
            while len(self._items) > self.size:
                self._items.popitem(last=False)
        return value

    def made(self, key: K, make: Callable[[], V]) -> V:
        """The value kept for ``key``, or ``make()`` kept for it (an exception from
        ``make`` keeps nothing)."""
        value = self.get(key)
        if value is MISSING:
            return self.put(key, make())
        return value  # type: ignore[return-value]

    def clear(self) -> None:
        """Forget every value."""
        with self._lock:
            self._items.clear()

    def __contains__(self, key: object) -> bool:
        return key in self._items

    def __len__(self) -> int:
        return len(self._items)

    def __iter__(self) -> Iterator[K]:
        with self._lock:
            return iter(list(self._items))

    def __reduce__(self) -> tuple[Any, ...]:
        """A copy or a pickle is an empty memory of the same size (what it keeps is made
        again, the same; its lock is never copied)."""
        return Kept, (self.size,)
