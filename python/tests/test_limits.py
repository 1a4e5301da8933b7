"""Every Python keyword against the limits table: out of range is a ValueError naming the
keyword, never a clamp, a crash or an interpreter ended by libgomp."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import sap_broadphase

# The cap of docs/ROBUSTNESS.md: 4 threads a processor (omp_get_num_procs, which is the
# processors this process may run on, as os.sched_getaffinity counts them).
MAX_THREADS = 4 * len(os.sched_getaffinity(0))

BOXES = np.array([[0, 0, 0, 1, 1, 1], [0.5, 0.5, 0.5, 2, 2, 2], [5, 5, 5, 6, 6, 6]], float)


def test_threads_above_four_a_processor_are_refused():
    # Issue 29: threads=100000 segfaulted, threads=300 under a small address space ended the
    # interpreter from libgomp.
    for threads in (MAX_THREADS + 1, 300, 100000, 2**31 - 1):
        with pytest.raises(ValueError, match=r"^threads: threads must be an integer from 0 to 4 "
                                             r"a processor"):
            sap_broadphase.Broadphase(threads=threads)
        with pytest.raises(ValueError, match=r"threads must be"):
            sap_broadphase.find_pairs(BOXES, threads=threads)
    engine = sap_broadphase.Broadphase(threads=MAX_THREADS)
    assert engine.config["threads"] == MAX_THREADS
    assert engine.update(BOXES).tolist() == [[0, 1]]


def test_threads_300_in_a_small_address_space_is_an_exception():
    """The interpreter survives, in a child limited to 1 GB of address space."""
    code = ("import resource, sap_broadphase\n"
            "resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))\n"
            "try:\n"
            "    sap_broadphase.Broadphase(threads=%d)\n"
            "except ValueError as error:\n"
            "    print('refused:', error)\n" % max(300, MAX_THREADS + 1))
    child = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           timeout=120)
    assert child.returncode == 0, child.stderr
    assert "refused: threads" in child.stdout


@pytest.mark.parametrize("name, value", [
    ("parallel_min_boxes", -1), ("threads", -5), ("third_axis_slabs", 65),
    ("third_axis_slabs", -1), ("axis_swap_threshold", -math.inf),
    ("axis_swap_threshold", math.nan), ("skin", 1e300), ("skin", "1e300"), ("skin", math.inf),
    ("skin", -1.0), ("skin", math.nan), ("threads", 2**63 - 1), ("threads", -2**63),
    ("parallel_min_boxes", 2**63 - 1), ("threads", 1.5), ("max_pairs", 0), ("max_pairs", -1),
])
def test_out_of_range_is_refused_not_clamped(name, value):
    with pytest.raises(ValueError, match=r"^%s: %s must be" % (name, name)):
        sap_broadphase.Broadphase(**{name: value})


# A property over every numeric keyword's type extremes: each is refused with ValueError or
# TypeError, or accepted and then the engine answers a frame exactly. Nothing else happens.
EXTREMES = [0, -0.0, -1, 1, 2**31 - 1, -2**31, 2**63 - 1, -2**63, 2**64, math.inf, -math.inf,
            math.nan, 1e300, -1e300, 5e-324, 3e38, "", "nan", "-inf", True]


@pytest.mark.parametrize("name", ["threads", "axis_swap_threshold", "parallel_min_boxes",
                                  "third_axis_slabs", "skin", "max_pairs"])
def test_every_numeric_keyword_over_its_extremes(name):
    for value in EXTREMES:
        try:
            engine = sap_broadphase.Broadphase(**{name: value})
        except (ValueError, TypeError) as error:
            assert name in str(error), (value, error)
            continue
        if name == "threads":
            assert 0 <= engine.config["threads"] <= MAX_THREADS
        assert engine.update(BOXES).tolist() == [[0, 1]], (name, value)


def test_a_frame_past_max_pairs_is_refused_and_the_engine_goes_on():
    crowd = np.tile([0.0, 0.0, 0.0, 1.0, 1.0, 1.0], (100, 1))  # 4950 pairs
    engine = sap_broadphase.Broadphase(max_pairs=4949)
    with pytest.raises(sap_broadphase.TooManyPairs, match=r"more than 4949 pairs \(max_pairs\)"):
        engine.update(crowd)
    assert len(engine.update(crowd[:99])) == 99 * 98 // 2
    assert len(sap_broadphase.Broadphase(max_pairs=4950).update(crowd)) == 4950
    # 1500 boxes at one place (1 124 250 pairs): the pairing threads stop past the bound, on
    # every method, and the engine answers the next frame.
    pile = np.tile([0.0, 0.0, 0.0, 1.0, 1.0, 1.0], (1500, 1))
    for method in ("auto", "parallel", "sequential", "brute"):
        engine = sap_broadphase.Broadphase(method=method, max_pairs=50000)
        with pytest.raises(ValueError, match=r"more than 50000 pairs"):
            engine.update(pile)
        assert engine.update(BOXES).tolist() == [[0, 1]], method
