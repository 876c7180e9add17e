#!/usr/bin/python3
"""Iterate a casmap dataset through its manifest (docs/commands/dataset.md).

    /usr/bin/python3 examples/python/read_dataset.py DIR [--split train] [--limit N]

`Dataset(DIR, split=None)` yields one `Sample` per successful manifest line: the raw elevation
map H (m, NaN-free: unknown cells are 0 as in the paper), the certainty map C (counts), the
exact truth (m, negative below the datum), the CAS classes and the per-beam truth labels
(0 valid, 1 mixed, 2 missing, 3 spike, 4 no_target, 5 dazzled), as numpy arrays read with h5py. Pure
Python (numpy + h5py); the `casmap` bindings are not needed.
"""
import argparse
import json
import os
from dataclasses import dataclass, field

import h5py
import numpy as np

LABELS = ["valid", "mixed", "missing", "spike", "no_target", "dazzled"]


@dataclass
class Sample:
    index: int
    split: str
    raw_m: np.ndarray
    certainty: np.ndarray
    truth_m: np.ndarray
    labels: np.ndarray
    cas_classes: np.ndarray = None
    filtered: dict = field(default_factory=dict)
    meta: dict = field(default_factory=dict)


class Dataset:
    """The successful samples of a casmap dataset, in index order."""

    def __init__(self, root, split=None):
        self.root = root
        self.split = split
        with open(os.path.join(root, "manifest.jsonl"), encoding="utf-8") as f:
            lines = [json.loads(line) for line in f if line.strip()]
        self.entries = [e for e in lines
                        if e["status"] == "ok" and (split is None or e["split"] == split)]

    def __len__(self):
        return len(self.entries)

    def __getitem__(self, k):
        e = self.entries[k]
        with h5py.File(os.path.join(self.root, e["dir"], "run.h5"), "r") as h5:
            maps = h5["maps"]
            filtered = {name: maps["filtered"][name][()] for name in maps.get("filtered", {})}
            return Sample(index=e["index"], split=e["split"],
                          raw_m=maps["elevation_m"][()], certainty=maps["certainty"][()],
                          truth_m=maps["truth_m"][()], labels=h5["scans"]["labels"][()],
                          cas_classes=maps["cas_classes"][()] if "cas_classes" in maps else None,
                          filtered=filtered, meta=e)

    def __iter__(self):
        for k in range(len(self)):
            yield self[k]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("root", help="dataset directory (holds manifest.jsonl)")
    parser.add_argument("--split", choices=["train", "val", "test"])
    parser.add_argument("--limit", type=int, default=0, help="stop after N samples (0: all)")
    args = parser.parse_args()
    data = Dataset(args.root, args.split)
    totals = np.zeros(len(LABELS), dtype=np.int64)
    for n, s in enumerate(data):
        if args.limit and n >= args.limit:
            break
        totals += np.bincount(s.labels.ravel(), minlength=len(LABELS))[:len(LABELS)]
        observed = s.certainty > 0
        err = np.abs(s.raw_m - s.truth_m)[observed]
        print(f"sample {s.index:6d} {s.split:5s} {s.meta['scene']['type']:7s} "
              f"{s.meta['rig']['motion']:7s} map {s.raw_m.shape[0]}x{s.raw_m.shape[1]} "
              f"observed {observed.mean():5.1%} median |H - truth| "
              f"{np.median(err) if err.size else float('nan'):.4f} m "
              f"truth min {s.truth_m.min():+.3f} m PI(cas) {s.meta['pi']['cas']}")
    print("labels:", ", ".join(f"{name} {count}" for name, count in zip(LABELS, totals)))


if __name__ == "__main__":
    main()
