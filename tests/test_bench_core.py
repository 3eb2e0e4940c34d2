"""The core benchmark runs and reports rates (speed itself is never asserted in tests)."""

from __future__ import annotations

from amiro.evaluation.core_bench import bench_bus, bench_engine, bench_lidar, bench_sim


def test_core_benchmarks_run_and_report_positive_rates() -> None:
    assert bench_bus(messages=5000, batch=500) > 0
    assert bench_engine(tasks=200) > 0
    sim = bench_sim(sim_seconds=2.0)
    assert sim["sim_steps_per_s"] > 0 and sim["sim_realtime_factor"] > 0
    assert bench_lidar(scans=5) > 0
