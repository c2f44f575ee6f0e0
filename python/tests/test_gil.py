"""Long calls release the GIL: another Python thread runs meanwhile."""

import threading
import time

import ancf_modal


def test_a_thread_runs_during_a_modal_analysis():
    # A 1,000-element cantilever: sparse shift-invert, a call long enough
    # for the interpreter to switch threads many times over.
    model = ancf_modal.Model.builtin("cantilever").with_params({"beams[0].elements": 1000})
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
        result = model.modal(modes=8)
        elapsed = time.perf_counter() - start
        during = count[0] - before
    finally:
        stop.set()
        thread.join()
    assert result.solver.startswith("sparse")
    assert elapsed > 0.02, elapsed
    # With the GIL held for the call the counter could not move while it
    # runs; released, it counts at the interpreter's pace (millions per s).
    assert during > 1000 * elapsed / 0.02, (during, elapsed)
