#!/usr/bin/env python3
"""A switch-off parameter study on a Dask cluster of two single-thread
workers, against the same study run serially here (a bench, not a test):
`benches/sweep-dask` installs the package into target/python-venv and runs
this.

The study: `time_to_distance_s` of the built-in switch-off assembly over
the pre-stress factor (`load_scale:F_x2,helical_spring`, 1 to 2) × the
hybrid joint's torsion stiffness (`joints[hybrid].torsion_stiffness`, 1 to
20 N m/rad, geometric), 12 × 12 = 144 points, the switch-off's defaults
(3 ms in steps of 1 µs).

Each round runs the study serially in this process (`threads=1`: the CPU
time of the points alone, `serial_cpu`), then on two threads here
(`threads=2`, rayon: what two threads get from this machine now, which may
be shared), then with `client=` on a `LocalCluster(n_workers=2,
threads_per_worker=1, processes=True)` started once (a warm-up study first,
so that the workers have imported the package), and reports

- cores used: the CPU time the two worker processes spent during the study
  (`time.process_time()` on each, before and after) ÷ its wall time; beside
  it the same ratio of the two-thread run here;
- overhead per point: (2 × wall − serial_cpu) ÷ 144, the worker time per
  point that did not compute points (task dispatch, pickling, the model's
  scatter, the shards' join and mode tracking here, the wait for the last
  shard, and on a shared machine the time other processes took the cores);
  beside it the workers' CPU time beyond serial_cpu ÷ 144, the work Dask
  and the tasks' set-up add, which other processes do not inflate.

- the same two measures for the two local threads (rayon), as the
  machine's own floor: what two cores give one process here;
- the idle workers' own CPU (heartbeats, monitors) at the rate measured
  while no task runs, over the study's wall time, per point; and the same
  for every process of the cluster (client and scheduler, nannies,
  workers), which take the same two cores;
- the cost of the dispatch alone: the same 144 points of a cheap quantity
  (`first_bending_hz` of the bare blade over its height × E, a fraction of a
  millisecond each), (Dask wall − serial wall ÷ 2) ÷ 144.

The result must equal the serial one (`to_dict()`), else the bench stops.
The load average before each round is printed.
"""

import argparse
import os
import statistics
import time
from typing import Any, Dict, List

import ancf_modal

PARAMS: Dict[str, Any] = {
    "load_scale:F_x2,helical_spring": (1.0, 2.0, 12),
    "joints[hybrid].torsion_stiffness": (1.0, 20.0, 12, "log"),
}
QUANTITY = "time_to_distance_s"
CHEAP: Dict[str, Any] = {"height": (0.8e-3, 1.4e-3, 12), "blade.young": (100e9, 150e9, 12)}


def worker_cpu(client: Any) -> float:
    """The CPU time [s] of the workers' processes, summed."""
    return float(sum(client.run(time.process_time).values()))


def dask_cpu() -> float:
    """The CPU time [s] of every process of the cluster: this one (client
    and scheduler) and its children (nannies and workers), by psutil (a
    dependency of distributed)."""
    import psutil

    me = psutil.Process()
    total = sum(me.cpu_times()[:2])
    for child in me.children(recursive=True):
        try:
            total += sum(child.cpu_times()[:2])
        except psutil.NoSuchProcess:
            pass
    return float(total)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=3, help="rounds (default 3)")
    args = parser.parse_args()

    import distributed

    model = ancf_modal.Model.builtin("rcbo_switch_off")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        warm = {"load_scale:F_x2,helical_spring": (1.0, 2.0, 4)}
        ancf_modal.sweep(model, warm, QUANTITY, client=client, end_time=1e-3)
        rows: List[Dict[str, float]] = []
        for r in range(args.rounds):
            load = os.getloadavg()[0]
            start_cpu, start = time.process_time(), time.perf_counter()
            local = ancf_modal.sweep(model, PARAMS, QUANTITY, threads=1)
            serial_cpu = time.process_time() - start_cpu
            serial_wall = time.perf_counter() - start

            start_cpu, start = time.process_time(), time.perf_counter()
            ancf_modal.sweep(model, PARAMS, QUANTITY, threads=2)
            rayon_cpu, rayon_wall = time.process_time() - start_cpu, time.perf_counter() - start
            rayon_cores = rayon_cpu / rayon_wall

            # The workers' own CPU while idle (heartbeats, monitors), per
            # second, over as long as the study will take.
            idle0, all0, start = worker_cpu(client), dask_cpu(), time.perf_counter()
            time.sleep(max(2.0, serial_wall / 4))
            idle_rate = (worker_cpu(client) - idle0) / (time.perf_counter() - start)
            all_idle_rate = (dask_cpu() - all0) / (time.perf_counter() - start)

            cpu0, start = worker_cpu(client), time.perf_counter()
            remote = ancf_modal.sweep(model, PARAMS, QUANTITY, client=client)
            wall = time.perf_counter() - start
            cpu = worker_cpu(client) - cpu0
            if remote.to_dict() != local.to_dict():
                raise SystemExit("the Dask study differs from the serial one")
            n = len(remote.result)

            blade = ancf_modal.Model.builtin("beam_free_free")
            start = time.perf_counter()
            here = ancf_modal.sweep(blade, CHEAP, "first_bending_hz", threads=1)
            cheap_serial = time.perf_counter() - start
            start = time.perf_counter()
            there = ancf_modal.sweep(blade, CHEAP, "first_bending_hz", client=client)
            cheap_wall = time.perf_counter() - start
            if there.to_dict() != here.to_dict():
                raise SystemExit("the Dask study differs from the serial one")
            row = {
                "dispatch_ms": 1e3 * (cheap_wall - cheap_serial / 2) / n,
                "cores": cpu / wall,
                "rayon_cores": rayon_cores,
                "overhead_ms": 1e3 * (2 * wall - serial_cpu) / n,
                "cpu_overhead_ms": 1e3 * (cpu - serial_cpu) / n,
                "rayon_overhead_ms": 1e3 * (2 * rayon_wall - serial_cpu) / n,
                "rayon_cpu_overhead_ms": 1e3 * (rayon_cpu - serial_cpu) / n,
                "idle_ms": 1e3 * idle_rate * wall / n,
                "all_idle_ms": 1e3 * all_idle_rate * wall / n,
                "wall_overhead_ms": 1e3 * (wall - serial_wall / 2) / n,
            }
            rows.append(row)
            print(
                f"round {r + 1}: load {load:.2f}; serial {serial_wall:.2f} s wall, "
                f"{serial_cpu:.2f} s CPU ({1e3 * serial_cpu / n:.1f} ms a point); "
                f"2 threads here {rayon_cores:.2f} cores; "
                f"Dask {wall:.2f} s wall, workers' CPU {cpu:.2f} s: {row['cores']:.2f} cores, "
                f"overhead {row['overhead_ms']:.2f} ms a point "
                f"(CPU beyond the serial run's {row['cpu_overhead_ms']:.2f} ms a point); "
                f"cheap points {1e3 * cheap_serial:.0f} ms serial, {1e3 * cheap_wall:.0f} ms "
                f"on Dask: dispatch {row['dispatch_ms']:.2f} ms a point; "
                f"the idle workers' own CPU over the study {row['idle_ms']:.2f} ms a point "
                f"(every process of the cluster, nannies and scheduler too: "
                f"{row['all_idle_ms']:.2f} ms); "
                f"the same measures for 2 threads here: overhead "
                f"{row['rayon_overhead_ms']:.2f} ms, CPU beyond serial "
                f"{row['rayon_cpu_overhead_ms']:.2f} ms a point; wall beyond serial/2 on Dask "
                f"{row['wall_overhead_ms']:.2f} ms a point",
                flush=True,
            )
    def median(key: str) -> float:
        return statistics.median(r[key] for r in rows)

    print(
        f"{n}-point switch-off study on 2 single-thread Dask workers, median of "
        f"{len(rows)} rounds: {median('cores'):.2f} cores used (≥ 1.6 asked; 2 threads "
        f"here: {median('rayon_cores'):.2f}), overhead {median('overhead_ms'):.2f} ms a "
        f"point (≤ 5 ms asked; CPU beyond the serial run's: "
        f"{median('cpu_overhead_ms'):.2f} ms a point; the dispatch alone: "
        f"{median('dispatch_ms'):.2f} ms a point; the idle workers' own CPU: "
        f"{median('idle_ms'):.2f} ms a point, the whole idle cluster's: "
        f"{median('all_idle_ms'):.2f} ms); two threads here by the same measure: "
        f"{median('rayon_overhead_ms'):.2f} ms a point (CPU beyond serial "
        f"{median('rayon_cpu_overhead_ms'):.2f} ms)"
    )


if __name__ == "__main__":
    main()
