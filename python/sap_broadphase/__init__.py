"""sap_broadphase: exact parallel Sweep and Prune broad phase for axis-aligned boxes.

Boxes are numpy arrays of shape (n, 6) (or empty), rows ``min_x min_y min_z max_x max_y max_z``,
closed intervals (touching boxes overlap, -0.0 == 0.0, infinities allowed), of float64 (read in
place when C-contiguous, else copied once), float32 or integers (copied once into float64,
exactly; integers beyond 2^53 in magnitude are refused); ids, groups and masks are integers in
[0, 2^32). Other dtypes and shapes raise ValueError naming what was expected (docs/PYTHON.md).

- ``find_pairs(boxes, ids=None, threads=0)``: every overlapping pair, uint32 (k, 2), a < b, sorted.
- ``Broadphase(**config)``: frame after frame: ``update(boxes, ids=None, groups=None,
  masks=None)``, ``query(boxes, groups=None, masks=None)`` (rows (query row, world id)),
  ``set_static_boxes(boxes, ids=None, groups=None, masks=None)``, ``stats``, ``config``.
- ``InvalidBoxes`` (a ValueError): a box with a NaN bound, min > max or a repeated id.
- ``TooManyPairs`` (a ValueError): a frame with more pairs than ``max_pairs``, refused.

In a ROS workspace this package also holds the generated ``sap_broadphase.msg`` and
``sap_broadphase.srv``.
"""
from sap_broadphase._sap_broadphase import Broadphase, InvalidBoxes, TooManyPairs, find_pairs

__all__ = ["Broadphase", "InvalidBoxes", "TooManyPairs", "find_pairs"]
