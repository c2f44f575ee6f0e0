"""Long calls release the GIL: another Python thread runs meanwhile."""

import threading
import time

import pytest

import ancf_modal


def modal_of_a_fine_cantilever():
    # 1,000 elements: sparse shift-invert.
    model = ancf_modal.Model.builtin("cantilever").with_params({"beams[0].elements": 1000})
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
        time.sleep(0.05)
        before = count[0]
        start = time.perf_counter()
        call()
        elapsed = time.perf_counter() - start
        during = count[0] - before
    finally:
        stop.set()
        thread.join()
    assert elapsed > 0.02, elapsed
    # With the GIL held for the call the counter could not move while it
    # runs; released, it counts at the interpreter's pace (millions per s).
    assert during > 1000 * elapsed / 0.02, (during, elapsed)
