"""The Python module against a numpy brute-force oracle: pairs, queries, filters, scenery,
infinities and -0.0, refusals in the engine's words, argument checks, threads."""
import os
import pathlib
import subprocess
import sys
import threading

import numpy as np
import pytest

import sap_broadphase
from box_oracle import (assert_same, lattice_boxes, oracle_pairs, oracle_query, random_boxes,
                        random_filters)

INF = np.inf


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("threads", [1, 2, 3, 4])
def test_find_pairs_matches_the_oracle(seed, threads):
    boxes = lattice_boxes(1500, 30, 3, seed) if seed % 2 else random_boxes(1500, 50.0, 4.0, seed)
    assert_same(oracle_pairs(boxes), sap_broadphase.find_pairs(boxes, threads=threads))
    ids = np.random.default_rng(seed).permutation(100000)[:len(boxes)].astype(np.uint32)
    assert_same(oracle_pairs(boxes, ids), sap_broadphase.find_pairs(boxes, ids=ids, threads=threads))


def test_find_pairs_reads_lists_and_other_layouts():
    boxes = random_boxes(300, 10.0, 2.0, 7)
    expected = oracle_pairs(boxes)
    assert_same(expected, sap_broadphase.find_pairs(boxes.tolist()))
    fortran = np.asfortranarray(boxes)
    assert_same(expected, sap_broadphase.find_pairs(fortran))
    wide = np.zeros((len(boxes), 12))
    wide[:, ::2] = boxes  # every other column: not contiguous
    assert_same(expected, sap_broadphase.find_pairs(wide[:, ::2]))
    read_only = boxes.copy()
    read_only.flags.writeable = False
    assert_same(expected, sap_broadphase.find_pairs(read_only))


def test_infinities_negative_zero_and_touching():
    boxes = np.array([
        [-0.0, -0.0, -0.0, 1, 1, 1],         # 0: starts at -0.0
        [-1, -1, -1, 0.0, 0.0, 0.0],         # 1: touches 0 at 0.0 == -0.0
        [5, 5, 5, INF, INF, INF],            # 2: reaches +inf
        [1e308, 1e308, 1e308, INF, INF, INF],  # 3: far out, overlaps 2
        [-INF, -INF, -INF, -INF, INF, INF],  # 4: the plane x = -inf
        [-INF, 0, 0, -INF, 0, 0],            # 5: a point on that plane
        [1, 1, 1, 1, 1, 1],                  # 6: a point on 0's far corner
    ])
    expected = np.array([[0, 1], [0, 6], [2, 3], [4, 5]], dtype=np.uint32)
    assert_same(expected, oracle_pairs(boxes))
    assert_same(expected, sap_broadphase.find_pairs(boxes))
    engine = sap_broadphase.Broadphase(threads=2)
    assert_same(expected, engine.update(boxes))
    queries = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [-INF, -INF, -INF, INF, INF, INF]])
    assert_same(oracle_query(queries, boxes, np.arange(7)), engine.query(queries))


@pytest.mark.parametrize("seed", range(4))
def test_frames_queries_filters_and_scenery_match_the_oracle(seed):
    engine = sap_broadphase.Broadphase(threads=2, parallel_min_boxes=200)
    scenery = random_boxes(300, 40.0, 5.0, 100 + seed)
    scenery_ids = np.arange(300, dtype=np.uint32) + 1000000
    scenery_groups, scenery_masks = random_filters(300, 200 + seed)
    engine.set_static_boxes(scenery, ids=scenery_ids, groups=scenery_groups, masks=scenery_masks)
    assert engine.static_box_count == 300
    rng = np.random.default_rng(seed)
    boxes = random_boxes(1000, 40.0, 3.0, seed)
    groups, masks = random_filters(1000, 300 + seed)
    for frame in range(5):
        boxes[:, :3] += rng.uniform(-0.3, 0.3, size=(1000, 3))
        boxes[:, 3:] = np.maximum(boxes[:, 3:] + rng.uniform(-0.3, 0.3, size=(1000, 3)),
                                  boxes[:, :3])
        ids = np.arange(1000, dtype=np.uint32)
        pairs = engine.update(boxes, groups=groups, masks=masks)
        world = np.vstack([boxes, scenery])
        world_ids = np.concatenate([ids, scenery_ids])
        world_groups = np.concatenate([groups, scenery_groups])
        world_masks = np.concatenate([masks, scenery_masks])
        frame_pairs = oracle_pairs(boxes, ids, groups, masks)
        scenery_hits = oracle_query(boxes, scenery, scenery_ids, groups, masks, scenery_groups,
                                    scenery_masks)
        expected = np.vstack([frame_pairs, scenery_hits])
        expected = expected[np.lexsort((expected[:, 1], expected[:, 0]))]
        assert_same(expected, pairs)
        assert engine.stats["pairs"] == len(pairs)
        for count in (1, 4, 80):  # scanned, then indexed
            queries = random_boxes(count, 40.0, 8.0, 1000 * seed + 10 * frame + count)
            query_groups, query_masks = random_filters(count, 7 * frame + count)
            assert_same(oracle_query(queries, world, world_ids, query_groups, query_masks,
                                     world_groups, world_masks),
                        engine.query(queries, groups=query_groups, masks=query_masks))
    engine.clear_static_boxes()
    assert engine.static_box_count == 0


def test_bad_boxes_raise_value_error_with_the_engines_words():
    boxes = random_boxes(10, 5.0, 1.0, 3)
    boxes[4, 4] = np.nan
    with pytest.raises(ValueError, match=r"^box 4 \(id 4\): max_y is NaN$"):
        sap_broadphase.find_pairs(boxes)
    boxes = random_boxes(10, 5.0, 1.0, 3)
    boxes[6, 2] = boxes[6, 5] + 1.0
    with pytest.raises(sap_broadphase.InvalidBoxes, match=r"^box 6 \(id 16\): min_z"):
        sap_broadphase.find_pairs(boxes, ids=np.arange(10, 20))
    with pytest.raises(ValueError, match=r"^box 3 \(id 7\): .*id"):
        sap_broadphase.find_pairs(random_boxes(4, 5.0, 1.0, 3), ids=[1, 7, 2, 7])
    engine = sap_broadphase.Broadphase()
    engine.update(random_boxes(50, 5.0, 1.0, 4))
    before = engine.query(random_boxes(5, 5.0, 1.0, 5))
    queries = random_boxes(5, 5.0, 1.0, 5)
    queries[2, 0] = np.nan
    with pytest.raises(ValueError, match=r"^box 2 \(id 2\): min_x is NaN$"):
        engine.query(queries)
    assert_same(before, engine.query(random_boxes(5, 5.0, 1.0, 5)))
    with pytest.raises(ValueError, match=r"^box 1 \(id 1\)"):
        engine.set_static_boxes([[0, 0, 0, 1, 1, 1], [0, 0, 0, 1, -1, 1]])


def test_wrong_shapes_and_dtypes_say_what_was_expected():
    with pytest.raises(ValueError, match=r"^boxes: expected an array of shape \(n, 6\) of float64, float32 or integers.*got shape \(4, 5\)$"):
        sap_broadphase.find_pairs(np.zeros((4, 5)))
    with pytest.raises(ValueError, match=r"got shape \(6,\)"):
        sap_broadphase.find_pairs(np.zeros(6))
    with pytest.raises(ValueError, match=r"expected an array of shape \(n, 6\).*got dtype complex128$"):
        sap_broadphase.find_pairs(np.zeros((4, 6), dtype=np.complex128))
    with pytest.raises(ValueError, match=r"ids: expected integers in \[0, 2\^32\) of shape \(4,\), got shape \(3,\)"):
        sap_broadphase.find_pairs(np.zeros((4, 6)), ids=[1, 2, 3])
    with pytest.raises(ValueError, match=r"ids: .* got values from -1 to 3"):
        sap_broadphase.find_pairs(np.zeros((4, 6)), ids=[-1, 1, 2, 3])
    with pytest.raises(ValueError, match=r"masks: expected integers.*got dtype float64"):
        sap_broadphase.Broadphase().update(np.zeros((2, 6)), masks=[1.0, 2.0])
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'thread'; the options are threads, method"):
        sap_broadphase.Broadphase(thread=2)
    with pytest.raises(ValueError, match=r"^threads: "):
        sap_broadphase.Broadphase(threads=-1)
    with pytest.raises(ValueError, match=r"^method: "):
        sap_broadphase.Broadphase(method="fastest")


def test_every_config_field_by_name():
    defaults = sap_broadphase.Broadphase().config
    assert list(defaults) == ["threads", "method", "primary_axis", "secondary_axis",
                              "axis_swapping", "axis_swap_threshold", "parallel_min_boxes",
                              "third_axis_slabs", "reuse_unchanged_frames",
                              "skin", "exact_final_test", "max_pairs"]
    chosen = dict(threads=1, method="parallel", primary_axis="z", secondary_axis=0,
                  axis_swapping=False, axis_swap_threshold=0.5, parallel_min_boxes=100,
                  third_axis_slabs=4, reuse_unchanged_frames=False,
                  skin=0.25, exact_final_test=False, max_pairs=1000)
    config = sap_broadphase.Broadphase(**chosen).config
    assert config["primary_axis"] == "z" and config["secondary_axis"] == "x"
    assert config["skin"] == "0.25" and config["third_axis_slabs"] == 4
    assert sap_broadphase.Broadphase(**config).config == config
    assert sap_broadphase.Broadphase(skin=None).config["skin"] == "auto"


def test_stats_describe_the_last_frame():
    engine = sap_broadphase.Broadphase(threads=1)
    boxes = random_boxes(500, 10.0, 1.0, 9)
    pairs = engine.update(boxes)
    stats = engine.stats
    assert stats["boxes"] == 500 and stats["pairs"] == len(pairs)
    assert stats["path"] in ("sequential", "parallel", "small", "brute", "empty")
    engine.update(boxes)
    assert engine.stats["path"] == "reused"
    assert stats["ms_total"] >= 0.0


def test_queries_from_python_threads_between_frames():
    engine = sap_broadphase.Broadphase(threads=2)
    for frame in range(3):
        boxes = random_boxes(3000, 30.0, 2.0, 40 + frame)
        engine.update(boxes)
        batches = [random_boxes(count, 30.0, 5.0, 50 * frame + count) for count in (1, 3, 60, 2)]
        answers = [None] * len(batches)

        def ask(which):
            answers[which] = engine.query(batches[which])

        askers = [threading.Thread(target=ask, args=(k,)) for k in range(len(batches))]
        for asker in askers:
            asker.start()
        for asker in askers:
            asker.join()
        for batch, answer in zip(batches, answers):
            assert_same(oracle_query(batch, boxes, np.arange(3000)), answer)


def test_results_own_their_memory():
    engine = sap_broadphase.Broadphase()
    first = engine.update(random_boxes(400, 10.0, 1.0, 1))
    kept = first.copy()
    engine.update(random_boxes(400, 10.0, 1.0, 2))  # the engine reuses its pair list
    np.testing.assert_array_equal(first, kept)


def test_the_example_runs():
    example = pathlib.Path(__file__).resolve().parents[1] / "examples" / "query_example.py"
    result = subprocess.run([sys.executable, str(example)], capture_output=True, text=True,
                            timeout=300, check=False)
    assert result.returncode == 0, result.stderr
    assert "pairs" in result.stdout and "hits" in result.stdout


@pytest.mark.skipif(os.environ.get("SAP_EXPECT_ROS_MESSAGES") != "1",
                    reason="the module is the ROS workspace's package only in the catkin build")
def test_the_ros_messages_share_the_package():
    import sap_broadphase.msg  # pylint: disable=import-outside-toplevel
    import sap_broadphase.srv  # pylint: disable=import-outside-toplevel
    assert hasattr(sap_broadphase.msg, "BoxArray") and hasattr(sap_broadphase.srv, "ComputePairs")
    assert hasattr(sap_broadphase, "find_pairs")


@pytest.mark.skipif("SAP_EXPECT_INSTALLED_IN" not in os.environ,
                    reason="run by scripts/pip_check.sh on the package pip installed")
def test_the_package_is_the_one_pip_installed():
    prefix = pathlib.Path(os.environ["SAP_EXPECT_INSTALLED_IN"]).resolve()
    compiled = pathlib.Path(sap_broadphase._sap_broadphase.__file__).resolve()
    assert prefix in pathlib.Path(sap_broadphase.__file__).resolve().parents
    assert prefix in compiled.parents, f"the compiled module is {compiled}, not under {prefix}"
