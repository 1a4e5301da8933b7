"""The brute-force oracle of the Python tests (numpy only) and the boxes they draw."""
import numpy as np


def random_boxes(count, world, max_edge, seed):
    rng = np.random.default_rng(seed)
    low = rng.uniform(0.0, world, size=(count, 3))
    return np.hstack([low, low + rng.uniform(0.0, max_edge, size=(count, 3))])


def lattice_boxes(count, cells, max_edge, seed):
    """Integer corners: many boxes share faces, edges and corners exactly."""
    rng = np.random.default_rng(seed)
    low = rng.integers(0, cells, size=(count, 3)).astype(np.float64)
    return np.hstack([low, low + rng.integers(0, max_edge + 1, size=(count, 3))])


def random_filters(count, seed):
    rng = np.random.default_rng(seed)
    return (rng.integers(1, 8, size=count).astype(np.uint32),
            rng.integers(0, 8, size=count).astype(np.uint32))


def overlap_matrix(boxes_a, boxes_b, groups_a=None, masks_a=None, groups_b=None, masks_b=None):
    """overlap[i, j]: box i of a and box j of b overlap (closed) and their filters agree."""
    overlap = np.all((boxes_a[:, None, :3] <= boxes_b[None, :, 3:])
                     & (boxes_b[None, :, :3] <= boxes_a[:, None, 3:]), axis=2)
    groups_a = np.ones(len(boxes_a), np.uint32) if groups_a is None else groups_a
    masks_a = np.full(len(boxes_a), 0xFFFFFFFF, np.uint32) if masks_a is None else masks_a
    groups_b = np.ones(len(boxes_b), np.uint32) if groups_b is None else groups_b
    masks_b = np.full(len(boxes_b), 0xFFFFFFFF, np.uint32) if masks_b is None else masks_b
    allowed = (((groups_a[:, None] & masks_b[None, :]) != 0)
               & ((groups_b[None, :] & masks_a[:, None]) != 0))
    return overlap & allowed


def oracle_pairs(boxes, ids=None, groups=None, masks=None):
    ids = np.arange(len(boxes), dtype=np.uint32) if ids is None else np.asarray(ids, np.uint32)
    first, second = np.nonzero(np.triu(overlap_matrix(boxes, boxes, groups, masks, groups, masks),
                                       k=1))
    pairs = np.stack([np.minimum(ids[first], ids[second]), np.maximum(ids[first], ids[second])],
                     axis=1).astype(np.uint32)
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))] if len(pairs) else pairs.reshape(0, 2)


def oracle_query(queries, world, world_ids, query_groups=None, query_masks=None,
                 world_groups=None, world_masks=None):
    rows, columns = np.nonzero(overlap_matrix(queries, world, query_groups, query_masks,
                                              world_groups, world_masks))
    hits = np.stack([rows, np.asarray(world_ids)[columns]], axis=1).astype(np.uint32)
    return hits[np.lexsort((hits[:, 1], hits[:, 0]))] if len(hits) else hits.reshape(0, 2)


def assert_same(expected, actual):
    assert actual.dtype == np.uint32
    assert actual.shape == expected.shape, f"expected {len(expected)} rows, got {len(actual)}"
    np.testing.assert_array_equal(actual, expected)
