"""Evaluations and benchmarks: each module measured, the paper's figure beside ours."""
