"""Median time of `Model.modal()` on the built-in assembly over 1,000 calls
(compare with `cargo bench --bench modal`'s in-process figure).

    target/python-venv/bin/python python/benches/modal.py
"""

import statistics
import time

import ancf_modal


def main(calls: int = 1000) -> None:
    model = ancf_modal.Model.builtin()
    model.modal()  # warm-up
    times = []
    for _ in range(calls):
        start = time.perf_counter()
        model.modal()
        times.append(time.perf_counter() - start)
    times.sort()
    print(
        f"Model.modal(), built-in assembly, {calls} calls: median {1e6 * statistics.median(times):.1f} µs, "
        f"10 % {1e6 * times[calls // 10]:.1f} µs, 90 % {1e6 * times[9 * calls // 10]:.1f} µs"
    )


if __name__ == "__main__":
    main()
