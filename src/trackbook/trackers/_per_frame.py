"""A value computed once per frame and shared by the steps of one ``update``.

A tracker's halves (locate, learn, re-detect) often need the same conversion of the frame
(its grey levels, a whole-frame response); computing it once per frame saves the time. The
frame that value belongs to is named by the update count *and* the array object, never by one
of them alone: a caller may hand the same buffer every frame, refilled in place (as
``cv2.VideoCapture.read(image=buffer)`` does), so the object alone would return the last
frame's value; and an array's ``id`` is given to a new one once the old is freed, so the ``id``
alone would too.

The value must depend on nothing that changes within one ``update`` other than what is passed
as ``extra``: bacf's whole-frame response depends on its filter, which is safe only because
the filter learns on frames judged on target and the response is used on frames judged lost.
"""

from __future__ import annotations

from typing import Any, Callable


class PerFrame:
    """One cached value, recomputed when the frame, the update count or ``extra`` changes."""

    def __init__(self) -> None:
        self._frame = None
        self._key: tuple | None = None
        self._value: Any = None

    def get(self, frame, frame_index: int, compute: Callable[[], Any], *extra) -> Any:
        """The value for ``frame`` at update ``frame_index`` (and ``extra``, e.g. a scale):
        ``compute()`` on the first call for them, the stored value after."""
        key = (frame_index, *extra)
        if self._frame is not frame or self._key != key:
            self._value = compute()
            self._frame, self._key = frame, key
        return self._value
