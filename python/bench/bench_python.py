#!/usr/bin/env python3
"""The Python module beside what Python users have, in one run on the same boxes.

- python_find_pairs: find_pairs() against the same work in C++ alone (the engine made and run
  on the same array: _one_shot_ms), and against rtree (libspatialindex's R-tree, Debian's
  python3-rtree) finding the pairs by querying each box in an index bulk-loaded from all of them
  (its build included: both answer "which boxes overlap" from scratch), for 10^3 .. 10^6 boxes.
- python_query: batches of 1, 100 and 10 000 query boxes against worlds of 10^3 .. 10^6 boxes:
  Broadphase.query() as the first query after update() and with the frame's index built (then
  asked back to back, as rtree's batches are), against rtree's intersection() per query box on
  an index built beforehand.

Boxes: cubes with edges uniform in [0.5, 1.5], uniform in a cube sized for density 0.05 (the
sum of the box volumes over the world's). Every answer is compared with ours. Prints the
tables and writes OUT/python_find_pairs.csv and OUT/python_query.csv.

Usage: bench_python.py [--out DIR] [--quick] [--threads N]
"""
import argparse
import csv
import pathlib
import statistics
import sys
import time

import numpy as np
from rtree import index as rtree_index

import sap_broadphase
from sap_broadphase._sap_broadphase import _one_shot_ms

DENSITY = 0.05
MEAN_CUBED_EDGE = (1.5 ** 4 - 0.5 ** 4) / 4.0  # E[e^3] for e uniform in [0.5, 1.5]
RTREE_MOST_BOXES = 10 ** 5  # the largest size rtree finds pairs for (the target's; a short run)


def uniform_boxes(count, seed, world_boxes=None):
    """count boxes in the cube that holds world_boxes (default: count) at the density."""
    rng = np.random.default_rng(seed)
    side = ((world_boxes or count) * MEAN_CUBED_EDGE / DENSITY) ** (1.0 / 3.0)
    low = rng.uniform(0.0, side, size=(count, 3))
    edge = rng.uniform(0.5, 1.5, size=(count, 1))
    return np.ascontiguousarray(np.hstack([low, low + edge]))


def median_ms(work, runs):
    times = []
    result = None
    for _ in range(runs):
        start = time.perf_counter()
        result = work()
        times.append(1000.0 * (time.perf_counter() - start))
    return statistics.median(times), result


def rtree_of(boxes):
    properties = rtree_index.Property()
    properties.dimension = 3
    return rtree_index.Index(((i, tuple(box), None) for i, box in enumerate(boxes.tolist())),
                             properties=properties)


def rtree_pairs(boxes):
    tree = rtree_of(boxes)
    pairs = [(i, j) for i, box in enumerate(boxes.tolist()) for j in tree.intersection(box)
             if i < j]
    return np.array(sorted(pairs), dtype=np.uint32).reshape(-1, 2)


def rtree_query(tree, queries):
    hits = [(q, w) for q, box in enumerate(queries.tolist()) for w in tree.intersection(box)]
    return np.array(sorted(hits), dtype=np.uint32).reshape(-1, 2)


def ratio(numerator, denominator):
    return f"{numerator / denominator:.3g}" if numerator > 0 and denominator > 0 else "-"


def publish(out_dir, stem, title, rows):
    print(f"\n== {title} ==")
    columns = list(rows[0])
    widths = [max(len(c), *(len(str(row[c])) for row in rows)) for c in columns]
    print("  ".join(c.rjust(w) for c, w in zip(columns, widths)))
    for row in rows:
        print("  ".join(str(row[c]).rjust(w) for c, w in zip(columns, widths)))
    out_dir.mkdir(parents=True, exist_ok=True)
    with open(out_dir / f"{stem}.csv", "w", newline="", encoding="utf-8") as stream:
        writer = csv.DictWriter(stream, fieldnames=columns)
        writer.writeheader()
        writer.writerows(rows)
    print(f"wrote {out_dir / (stem + '.csv')}")


def find_pairs_rows(sizes, threads, runs):
    rows = []
    for count in sizes:
        boxes = uniform_boxes(count, seed=count)
        # Alternating, so that a busy spell of the machine falls on both alike.
        python_times, cpp_times = [], []
        for _ in range(runs):
            ms, pairs = median_ms(lambda: sap_broadphase.find_pairs(boxes, threads=threads), 1)
            python_times.append(ms)
            cpp_times.append(_one_shot_ms(boxes, threads))
        python_ms, cpp_ms = statistics.median(python_times), statistics.median(cpp_times)
        rtree_ms, rtree_check = 0.0, "-"
        if count <= RTREE_MOST_BOXES:
            rtree_ms, theirs = median_ms(lambda: rtree_pairs(boxes), 1)
            rtree_check = "same" if np.array_equal(theirs, pairs) else (
                f"differ ({len(theirs)} against {len(pairs)})")
        rows.append({"boxes": count, "pairs": len(pairs), "find_pairs_ms": f"{python_ms:.4g}",
                     "cpp_one_shot_ms": f"{cpp_ms:.4g}",
                     "python_over_cpp": ratio(python_ms, cpp_ms),
                     "rtree_pairs_ms": f"{rtree_ms:.4g}" if rtree_ms else "-",
                     "rtree_over_ours": ratio(rtree_ms, python_ms), "rtree_pairs": rtree_check})
    return rows


def query_rows(sizes, batches, threads, runs):
    rows = []
    for count in sizes:
        world = uniform_boxes(count, seed=count)
        other = uniform_boxes(max(batches), seed=count + 1, world_boxes=count)  # same volume
        engine = sap_broadphase.Broadphase(threads=threads)
        update_ms, _ = median_ms(lambda: engine.update(world), 1)
        tree = rtree_of(world)
        index_builder = other[:max(batches)]
        for batch_size in batches:
            batch = other[:batch_size]
            first = []
            for _ in range(runs):
                engine.update(world)  # the same frame: its pairs reused, the index forgotten
                ms, hits = median_ms(lambda: engine.query(batch), 1)
                first.append(ms)
            engine.query(index_builder)
            indexed = [median_ms(lambda: engine.query(batch), 1)[0] for _ in range(runs)]
            rtree_ms, theirs = median_ms(lambda: rtree_query(tree, batch), max(1, runs // 2))
            rows.append({
                "world_boxes": count, "queries": batch_size, "hits": len(hits),
                "update_ms": f"{update_ms:.4g}",
                "ours_first_ms": f"{statistics.median(first):.4g}",
                "ours_indexed_ms": f"{statistics.median(indexed):.4g}",
                "rtree_ms": f"{rtree_ms:.4g}",
                "rtree_over_first": ratio(rtree_ms, statistics.median(first)),
                "rtree_over_indexed": ratio(rtree_ms, statistics.median(indexed)),
                "rtree_hits": "same" if np.array_equal(theirs, hits) else (
                    f"differ ({len(theirs)} against {len(hits)})")})
    return rows


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="bench_out", help="where the CSV files go")
    parser.add_argument("--quick", action="store_true", help="small sizes, a smoke test")
    parser.add_argument("--threads", type=int, default=0, help="engine threads (0 = all cores)")
    options = parser.parse_args(argv)
    sizes = [10 ** 3, 10 ** 4] if options.quick else [10 ** 3, 10 ** 4, 10 ** 5, 10 ** 6]
    batches = [1, 100, 1000] if options.quick else [1, 100, 10000]
    runs = 2 if options.quick else 9
    out_dir = pathlib.Path(options.out)
    publish(out_dir, "python_find_pairs",
            f"find_pairs against C++ alone (alternating) and rtree (ms, median of {runs}; "
            "rtree once)",
            find_pairs_rows(sizes, options.threads, runs))
    publish(out_dir, "python_query",
            f"Broadphase.query against rtree (ms per batch, median of {runs})",
            query_rows(sizes, batches, options.threads, runs))


if __name__ == "__main__":
    main(sys.argv[1:])
