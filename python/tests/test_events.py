"""Broadphase.events(): the contacts that began and ended at the last update(), equal to the set
differences of consecutive pair lists (and of find_pairs' answers) over multi-frame random runs,
on every path and thread count, with boxes that come and go, scenery, a refused frame and
reset()."""
import numpy as np
import pytest

import sap_broadphase
from box_oracle import assert_same, lattice_boxes, random_boxes

EMPTY_PAIRS = np.zeros((0, 2), np.uint32)


def difference(pairs, others):
    """The rows of pairs (sorted (k, 2) uint32) absent from others, still sorted."""
    if len(pairs) == 0 or len(others) == 0:
        return pairs.reshape(-1, 2)
    keys = pairs[:, 0].astype(np.uint64) << np.uint64(32) | pairs[:, 1]
    other_keys = others[:, 0].astype(np.uint64) << np.uint64(32) | others[:, 1]
    return pairs[~np.isin(keys, other_keys)]


def assert_events(before, after, events):
    began, ended = events
    assert_same(difference(after, before), began)
    assert_same(difference(before, after), ended)


def moved(boxes, rng, step):
    low = boxes[:, :3] + rng.uniform(-step, step, size=(len(boxes), 3))
    return np.hstack([low, low + (boxes[:, 3:] - boxes[:, :3])])


CONFIGS = [dict(threads=1), dict(threads=2), dict(threads=4),
           dict(threads=2, method="parallel", parallel_min_boxes=100),
           dict(threads=1, method="sequential"), dict(threads=1, method="brute"),
           dict(threads=2, skin=0.5),
           dict(threads=2, reuse_unchanged_frames=False, skin=0.0)]


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("config", CONFIGS, ids=lambda c: "-".join(f"{k}={v}" for k, v in c.items()))
def test_events_are_the_differences_of_consecutive_pair_lists(config, seed):
    rng = np.random.default_rng(seed)
    boxes = random_boxes(1500, 40.0, 2.5, seed) if seed % 2 else lattice_boxes(1500, 35, 2, seed)
    ids = rng.permutation(10**6)[:len(boxes)].astype(np.uint32)
    engine = sap_broadphase.Broadphase(**config)
    before = EMPTY_PAIRS
    for frame in range(12):
        present = np.ones(len(boxes), bool)
        if frame % 4 in (0, 1):
            boxes = moved(boxes, rng, 0.4)
        elif frame % 4 == 3:
            present = rng.random(len(boxes)) < 0.9  # a tenth leave, to come back next frame
        # frame % 4 == 2: the last frame again, unchanged
        pairs = engine.update(boxes[present], ids=ids[present])
        assert_same(sap_broadphase.find_pairs(boxes[present], ids=ids[present]), pairs)
        assert_events(before, pairs, engine.events())
        before = pairs


def test_first_frame_begins_everything_and_an_unchanged_frame_nothing():
    boxes = lattice_boxes(400, 15, 3, 5)
    engine = sap_broadphase.Broadphase(threads=2)
    pairs = engine.update(boxes)
    assert len(pairs) > 0
    assert_events(EMPTY_PAIRS, pairs, engine.events())
    assert_same(pairs, engine.update(boxes))
    assert_events(pairs, pairs, engine.events())  # reused: nothing began or ended
    assert_events(EMPTY_PAIRS, EMPTY_PAIRS, sap_broadphase.Broadphase().events())


def test_scenery_pairs_begin_and_end_with_the_scenery():
    engine = sap_broadphase.Broadphase(threads=2)
    boxes = random_boxes(500, 20.0, 2.0, 8)
    first = engine.update(boxes)
    engine.set_static_boxes(random_boxes(100, 20.0, 3.0, 9), ids=np.arange(100) + 10000)
    with_scenery = engine.update(boxes)
    assert len(with_scenery) > len(first)
    assert_events(first, with_scenery, engine.events())
    engine.clear_static_boxes()
    assert_same(first, engine.update(boxes))
    assert_events(with_scenery, first, engine.events())


def test_a_refused_frame_has_no_events_and_the_next_compares_with_the_last_list():
    rng = np.random.default_rng(12)
    engine = sap_broadphase.Broadphase(threads=2)
    boxes = random_boxes(600, 20.0, 2.0, 12)
    last = engine.update(boxes)
    bad = moved(boxes, rng, 1.0)
    bad[7, 1] = np.nan
    with pytest.raises(sap_broadphase.InvalidBoxes):
        engine.update(bad)
    assert_events(EMPTY_PAIRS, EMPTY_PAIRS, engine.events())
    boxes = moved(boxes, rng, 1.0)
    pairs = engine.update(boxes)
    assert_events(last, pairs, engine.events())
    engine.reset()
    again = engine.update(boxes)
    assert_same(pairs, again)
    assert_events(EMPTY_PAIRS, again, engine.events())


def test_events_own_their_memory():
    engine = sap_broadphase.Broadphase()
    engine.update(random_boxes(300, 10.0, 1.0, 1))
    began, ended = engine.events()
    kept = began.copy(), ended.copy()
    engine.update(random_boxes(300, 10.0, 1.0, 2))
    np.testing.assert_array_equal(kept[0], began)
    np.testing.assert_array_equal(kept[1], ended)
    assert began.dtype == np.uint32 and ended.shape == (0, 2)
