#!/usr/bin/env python3
"""sap_broadphase from Python: the pairs of a box cloud, then a world frame after frame with
scenery, asked what overlaps a robot's next footprint.

Run with the package pip installed (README, "From Python"), after `source scripts/env.sh` (ROS
workspace), or with PYTHONPATH set to the ROS-free build's python directory (BUILD/python, or
PREFIX/lib/python3/dist-packages once installed).
"""
import numpy as np

import sap_broadphase


def boxes_around(centres, half_sizes):
    """(n, 6) rows min_x min_y min_z max_x max_y max_z from centres and half sizes."""
    return np.hstack([centres - half_sizes, centres + half_sizes])


def main():
    rng = np.random.default_rng(1)

    # One-shot: every overlapping pair of 100 000 boxes (row numbers as ids).
    cloud = boxes_around(rng.uniform(0, 100, (100_000, 3)), rng.uniform(0.05, 0.5, (100_000, 3)))
    pairs = sap_broadphase.find_pairs(cloud)
    print(f"{len(cloud)} boxes: {len(pairs)} pairs, first {pairs[:3].tolist()}")

    # A world over frames: shelves as scenery (declared once), moving parcels each frame.
    engine = sap_broadphase.Broadphase(threads=0)
    shelves = boxes_around(rng.uniform(0, 50, (2_000, 3)) * [1, 1, 0], [1.0, 0.2, 2.0])
    engine.set_static_boxes(shelves, ids=np.arange(2_000) + 1_000_000)
    parcels = boxes_around(rng.uniform(0, 50, (20_000, 3)), 0.15)
    # Parcels (group 1) meet shelves and each other; the robot's footprint (group 2) asks with
    # mask 1, so it sees parcels and shelves, and parcels see it (their mask is all groups).
    for frame in range(3):
        parcels += rng.normal(0, 0.05, (1, 6)).repeat(len(parcels), axis=0)
        pairs = engine.update(parcels)
        footprint = boxes_around(np.array([[10.0 + frame, 10.0, 0.0]]), [0.6, 0.4, 1.0])
        hits = engine.query(footprint, groups=[2], masks=[1])
        print(f"frame {frame}: {len(pairs)} pairs ({engine.stats['path']}, "
              f"{engine.stats['ms_total']:.2f} ms); footprint hits {len(hits)}: "
              f"{hits[:, 1].tolist()[:8]}")

    try:
        sap_broadphase.find_pairs([[0, 0, 0, 1, -1, 1]])
    except ValueError as refusal:  # sap_broadphase.InvalidBoxes
        print(f"refused: {refusal}")


if __name__ == "__main__":
    main()
