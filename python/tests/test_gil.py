"""Long calls release the GIL: another Python thread runs meanwhile."""

import threading
import time

import pytest

import ancf_modal


def modal_of_a_fine_cantilever():
    # 2,000 elements: sparse shift-invert.
    model = ancf_modal.Model.builtin("cantilever").with_params({"beams[0].elements": 2000})
    return lambda: model.modal(modes=8)


def impulse_of_the_assembly():
    # 20,000 steps of the paper's experiment.
    model = ancf_modal.Model.builtin()
    return lambda: model.impulse(end_time=0.02)


@pytest.mark.parametrize("make", [modal_of_a_fine_cantilever, impulse_of_the_assembly])
def test_a_thread_runs_during_a_long_call(make):
    call = make()
    count = [0]
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            count[0] += 1

    thread = threading.Thread(target=spin)
    thread.start()
    try:
        # The counter's pace while this thread sleeps (the GIL free).
        time.sleep(0.02)
        c0, t0 = count[0], time.perf_counter()
        time.sleep(0.05)
        pace = (count[0] - c0) / (time.perf_counter() - t0)
        before = count[0]
        start = time.perf_counter()
        call()
        elapsed = time.perf_counter() - start
        during = count[0] - before
    finally:
        stop.set()
        thread.join()
    # Released, the counter keeps most of its pace (measured here: 0.6–0.8;
    # the call may take the other core). A call that holds the GIL leaves
    # it only the switches at its ends (measured on json.dumps and sorted
    # of 3e6 ints: 0.08–0.13).
    assert during >= 0.3 * pace * elapsed, (during, pace, elapsed)
