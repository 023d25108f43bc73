#!/usr/bin/env python3
"""Prints criterion's median per element (ns/sample) for every bench of a
group, from target/criterion/<group>/*/new/estimates.json.

Usage: python3 benches/scripts/medians.py GROUP [ELEMENTS_PER_ITERATION]
"""
import json, os, sys

group = sys.argv[1]
elements = float(sys.argv[2]) if len(sys.argv) > 2 else 1024.0
root = os.path.join("target", "criterion", group)
rows = []
for name in sorted(os.listdir(root)):
    path = os.path.join(root, name, "new", "estimates.json")
    if not os.path.exists(path):
        continue
    with open(path) as f:
        est = json.load(f)
    median = est["median"]["point_estimate"] / elements
    lo = est["median"]["confidence_interval"]["lower_bound"] / elements
    hi = est["median"]["confidence_interval"]["upper_bound"] / elements
    title = json.load(open(os.path.join(root, name, "new", "benchmark.json")))["function_id"]
    rows.append((title, median, lo, hi))
for title, median, lo, hi in rows:
    print(f"{title:<34} {median:8.2f} ns/sample  [{lo:.2f}, {hi:.2f}]")
