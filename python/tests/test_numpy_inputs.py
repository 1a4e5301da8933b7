"""numpy as it comes: float64, float32 and integer boxes in any layout, empty inputs, integer
ids, groups and masks of any dtype, each answered exactly as the float64 oracle answers the
same values; and the refusals, which name what was expected."""
import numpy as np
import pytest

import sap_broadphase
from box_oracle import (assert_same, lattice_boxes, oracle_pairs, oracle_query, random_boxes,
                        random_filters)

INTEGER_TYPES = [np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16, np.uint32, np.uint64]
EMPTY_PAIRS = np.zeros((0, 2), np.uint32)


def as_layout(boxes, layout):
    """boxes (any dtype) in another memory layout, same values."""
    if layout == "fortran":
        return np.asfortranarray(boxes)
    if layout == "strided":
        wide = np.zeros((len(boxes), 12), boxes.dtype)
        wide[:, ::2] = boxes
        return wide[:, ::2]
    if layout == "reversed_rows":
        return boxes[::-1].copy()[::-1]
    if layout == "byte_swapped":
        return boxes.astype(boxes.dtype.newbyteorder(">" if np.little_endian else "<"))
    if layout == "unaligned":
        raw = np.zeros(boxes.nbytes + 1, np.uint8)
        unaligned = raw[1:].view(boxes.dtype).reshape(boxes.shape)
        unaligned[...] = boxes
        return unaligned
    assert layout == "c"
    return np.ascontiguousarray(boxes)


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("layout", ["c", "fortran", "strided", "reversed_rows", "byte_swapped",
                                    "unaligned"])
def test_float32_frames_match_the_oracle_in_every_layout(seed, layout):
    boxes32 = random_boxes(800, 30.0, 3.0, seed).astype(np.float32)
    expected = oracle_pairs(boxes32.astype(np.float64))  # float32 -> float64 is exact
    arranged = as_layout(boxes32, layout)
    assert_same(expected, sap_broadphase.find_pairs(arranged, threads=2))
    engine = sap_broadphase.Broadphase(threads=2)
    assert_same(expected, engine.update(arranged))


@pytest.mark.parametrize("layout", ["fortran", "strided", "reversed_rows", "byte_swapped",
                                    "unaligned"])
def test_float64_in_other_layouts_matches_the_oracle(layout):
    boxes = lattice_boxes(600, 20, 3, 11)
    assert_same(oracle_pairs(boxes), sap_broadphase.find_pairs(as_layout(boxes, layout)))


def test_float32_bounds_are_read_exactly():
    tenth = np.float32(0.1)
    above = np.nextafter(tenth, np.float32(1.0))
    boxes = np.array([[0, 0, 0, tenth, 1, 1],    # 0: ends at float32(0.1)
                      [tenth, 0, 0, 1, 1, 1],    # 1: starts there: touches 0
                      [above, 0, 0, 1, 1, 1]],   # 2: one float32 step further: misses 0
                     dtype=np.float32)
    assert_same(np.array([[0, 1], [1, 2]], np.uint32), sap_broadphase.find_pairs(boxes))
    assert_same(oracle_pairs(boxes.astype(np.float64)), sap_broadphase.find_pairs(boxes))


@pytest.mark.parametrize("dtype", INTEGER_TYPES, ids=lambda t: np.dtype(t).name)
@pytest.mark.parametrize("layout", ["c", "fortran", "strided"])
def test_integer_frames_match_the_oracle(dtype, layout):
    cells = 100 if np.iinfo(dtype).max > 200 else 60  # int8 holds corners up to 127
    for seed in range(3):
        boxes = lattice_boxes(700, cells, 4, 20 + seed)
        integers = as_layout(boxes.astype(dtype), layout)
        expected = oracle_pairs(boxes)
        assert_same(expected, sap_broadphase.find_pairs(integers))
        assert_same(expected, sap_broadphase.Broadphase(threads=2).update(integers))


@pytest.mark.parametrize("dtype", [np.int64, np.uint64])
def test_64_bit_integers_are_exact_up_to_2_to_the_53(dtype):
    top = 2**53
    boxes = np.array([[top - 2, 0, 0, top - 1, 1, 1],  # 0
                      [top, 0, 0, top, 1, 1],          # 1: starts one past 0's end: misses 0
                      [top - 1, 0, 0, top, 1, 1]],     # 2: touches 0 and 1
                     dtype=dtype)
    assert_same(np.array([[0, 2], [1, 2]], np.uint32), sap_broadphase.find_pairs(boxes))
    beyond = boxes.copy()
    beyond[1, 3] = top + 1  # rounds to 2^53 in float64: refused, not rounded
    with pytest.raises(ValueError, match=r"^boxes: expected .* values from 0 to 9007199254740993: "
                                         r"beyond 2\^53 in magnitude"):
        sap_broadphase.find_pairs(beyond)
    if dtype == np.int64:
        below = boxes.copy()
        below[0, 0] = -top - 1
        with pytest.raises(ValueError, match=r"from -9007199254740993 .*beyond 2\^53"):
            sap_broadphase.Broadphase().update(below)


@pytest.mark.parametrize("empty", [[], (), np.zeros((0, 6)), np.zeros((0, 6), np.float32),
                                   np.zeros((0, 6), np.int32), np.zeros(0), np.zeros((6, 0)).T],
                         ids=["list", "tuple", "float64", "float32", "int32", "zeros(0)",
                              "fortran"])
def test_empty_inputs_give_empty_answers(empty):
    assert_same(EMPTY_PAIRS, sap_broadphase.find_pairs(empty))
    assert_same(EMPTY_PAIRS, sap_broadphase.find_pairs(empty, ids=[]))
    engine = sap_broadphase.Broadphase()
    assert_same(EMPTY_PAIRS, engine.update(empty, ids=[], groups=[], masks=[]))
    assert_same(EMPTY_PAIRS, engine.query(empty))
    assert_same(EMPTY_PAIRS, engine.query([[0, 0, 0, 1, 1, 1]]))
    engine.set_static_boxes(empty)
    assert engine.static_box_count == 0
    assert engine.stats["boxes"] == 0


def test_scenery_queries_and_filters_of_any_dtype_match_the_oracle():
    scenery = lattice_boxes(200, 40, 5, 31)
    boxes = random_boxes(600, 40.0, 3.0, 32)
    groups, masks = random_filters(600, 33)
    scenery_ids = np.arange(200) + 5000
    engine = sap_broadphase.Broadphase(threads=2)
    engine.set_static_boxes(np.asfortranarray(scenery.astype(np.int16)),
                            ids=scenery_ids.tolist(), groups=np.full(200, 7, np.int64),
                            masks=np.full(200, 7, np.uint8))
    boxes32 = boxes.astype(np.float32)
    exact = boxes32.astype(np.float64)
    pairs = engine.update(boxes32, ids=np.arange(600, dtype=np.int64),
                          groups=groups.astype(np.int32)[::-1].copy()[::-1],
                          masks=masks.astype(">u4"))
    expected = np.vstack([oracle_pairs(exact, None, groups, masks),
                          oracle_query(exact, scenery, scenery_ids, groups, masks,
                                       np.full(200, 7, np.uint32), np.full(200, 7, np.uint32))])
    assert_same(expected[np.lexsort((expected[:, 1], expected[:, 0]))], pairs)
    queries = lattice_boxes(30, 40, 8, 34).astype(np.uint16)
    world = np.vstack([exact, scenery])
    world_ids = np.concatenate([np.arange(600), scenery_ids])
    world_groups = np.concatenate([groups, np.full(200, 7, np.uint32)])
    world_masks = np.concatenate([masks, np.full(200, 7, np.uint32)])
    assert_same(oracle_query(queries.astype(np.float64), world, world_ids, None, None,
                             world_groups, world_masks),
                engine.query(np.asfortranarray(queries), groups=[1] * 30,
                             masks=np.full(30, 0xFFFFFFFF, np.int64)))


@pytest.mark.parametrize("boxes, message", [
    (np.zeros((3, 6), bool), r"got dtype bool$"),
    (np.zeros((3, 6), np.complex128), r"got dtype complex128$"),
    (np.zeros((3, 6), object), r"got dtype object$"),
    (np.array([["0"] * 6]), r"got dtype <U1$"),
    (None, r"got dtype object$"),
    (np.zeros((3, 5)), r"got shape \(3, 5\)$"),
    (np.zeros((3, 6, 1)), r"got shape \(3, 6, 1\)$"),
    (np.zeros((0, 5)), r"got shape \(0, 5\)$"),
    (np.zeros(6), r"got shape \(6,\)$"),
    ([[0, 0, 0, 1, 1, 1], [0, 0, 0]], r"got .*inhomogeneous"),
])
def test_other_dtypes_and_shapes_are_refused_naming_what_was_expected(boxes, message):
    expected = (r"^boxes: expected an array of shape \(n, 6\) of float64, float32 or integers, "
                r"rows min_x min_y min_z max_x max_y max_z, ")
    with pytest.raises(ValueError, match=expected + message):
        sap_broadphase.find_pairs(boxes)
    engine = sap_broadphase.Broadphase()
    for call in (engine.update, engine.query, engine.set_static_boxes):
        with pytest.raises(ValueError, match=expected + message):
            call(boxes)


@pytest.mark.skipif(np.dtype(np.longdouble).itemsize <= 8, reason="long double is float64 here")
def test_long_double_is_refused_rather_than_rounded():
    with pytest.raises(ValueError, match=r"got dtype float(96|128)$"):
        sap_broadphase.find_pairs(np.zeros((2, 6), np.longdouble))


@pytest.mark.parametrize("values, message", [
    ([1.0, 2.0, 3.0], r"got dtype float64$"),
    (np.array([True, False, True]), r"got dtype bool$"),
    ([-1, 2, 3], r"got values from -1 to 3$"),
    (np.array([1, 2, 2**32], np.int64), r"got values from 1 to 4294967296$"),
    (np.array([1, 2, 2**64 - 1], np.uint64), r"got values from 1 to 18446744073709551615$"),
    ([1, 2], r"got shape \(2,\)$"),
    (np.zeros((3, 1), np.uint32), r"got shape \(3, 1\)$"),
])
def test_ids_groups_and_masks_refused_naming_what_was_expected(values, message):
    boxes = np.zeros((3, 6))
    for name in ("ids", "groups", "masks"):
        with pytest.raises(ValueError,
                           match=rf"^{name}: expected integers in \[0, 2\^32\) of shape \(3,\), "
                                 + message):
            sap_broadphase.Broadphase().update(boxes, **{name: values})
    with pytest.raises(ValueError, match=r"^ids: expected integers .*" + message):
        sap_broadphase.find_pairs(boxes, ids=values)
