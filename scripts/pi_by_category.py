#!/usr/bin/python3
"""Eq. 11's PI of each pipeline split by truth category, from `casmap bench --maps` outputs.

  pi_by_category.py BENCH_DIR [BENCH_DIR ...] [--pipelines a,b,...] [--diff A,B]

BENCH_DIR holds bench.json and runs/<courseNN_TEST>/*.tif (written by `casmap bench --maps`).
Per run, each cell's squared error (map - truth)^2 is divided by the run's sum of (raw -
truth)^2, so a pipeline's categories add up to its PI in bench.json. Categories (truth only;
a cell is in exactly one):
  pole       truth above 0.8 m (the courses' poles)
  halo       the 8 cells around a pole
  trail      the rest of the 7 x 7 block around a pole (where mixed-pixel trails lie)
  edge_in    box outline cells on the top side (a 4-neighbour's truth differs by > 5 cm,
             truth > 5 cm), outside the pole blocks
  edge_out   box outline cells on the floor side
  near_in    box-top cells within 2 cells of an outline cell
  near_out   floor cells within 2 cells of an outline cell
  top        the rest of the box tops
  floor      the rest of the floor
each split by whether the raw map observed the cell ("/k", certainty > 0) or not ("/u").
Prints per test (T, TR, TP, TRP) the mean over runs of each pipeline's share per category
(with --diff A,B: A's minus B's, the categories where A loses are positive). Pipelines
default to raw and every CAS variant whose map is there. Exit status 2 for bad input
(missing file, not a bench output, a map that is not an uncompressed float TIFF), naming it.
"""
import argparse
import json
import os
import struct
import sys

import numpy as np

TESTS = ["T", "TR", "TP", "TRP"]
CATEGORIES = ["pole", "halo", "trail", "edge_in", "edge_out", "near_in", "near_out", "top",
              "floor"]


def fail(message):
    print(f"pi_by_category.py: {message}", file=sys.stderr)
    sys.exit(2)


def read_tiff(path):
    """A single-channel float32 / uint8 TIFF without compression (what casmap writes)."""
    try:
        with open(path, "rb") as f:
            b = f.read()
    except OSError as e:
        fail(f"{path}: cannot be read ({e})")
    if len(b) < 8 or b[:2] not in (b"II", b"MM"):
        fail(f"{path}: not a TIFF file")
    e = "<" if b[:2] == b"II" else ">"
    try:
        off = struct.unpack(e + "I", b[4:8])[0]
        n = struct.unpack(e + "H", b[off:off + 2])[0]
        tags = {}
        for k in range(n):
            p = off + 2 + 12 * k
            tag, typ, cnt = struct.unpack(e + "HHI", b[p:p + 8])
            if typ == 3 and cnt == 1:
                val = struct.unpack(e + "H", b[p + 8:p + 10])[0]
            else:
                val = struct.unpack(e + "I", b[p + 8:p + 12])[0]
            tags[tag] = (typ, cnt, val)

        def array(tag):
            typ, cnt, val = tags[tag]
            if cnt == 1:
                return [val]
            size = 2 if typ == 3 else 4
            return list(struct.unpack(e + ("H" if typ == 3 else "I") * cnt,
                                      b[val:val + cnt * size]))

        width, height = tags[256][2], tags[257][2]
        bits = tags.get(258, (3, 1, 1))[2]
        if tags.get(259, (3, 1, 1))[2] != 1:
            fail(f"{path}: compression (expected an uncompressed TIFF)")
        if tags.get(277, (3, 1, 1))[2] != 1:
            fail(f"{path}: channels (expected one)")
        fmt = tags.get(339, (3, 1, 1))[2]
        dtype = {(32, 3): "f4", (8, 1): "u1"}.get((bits, fmt))
        if dtype is None:
            fail(f"{path}: sample format (expected float32 or uint8)")
        data = b"".join(b[o:o + c] for o, c in zip(array(273), array(279)))
        return np.frombuffer(data, dtype=np.dtype(e + dtype)).reshape(height, width).astype(
            np.float64)
    except (KeyError, struct.error, ValueError) as err:
        fail(f"{path}: not a readable TIFF ({err})")


def dilate(mask, k):
    """Binary dilation by a (2k+1) x (2k+1) square."""
    p = np.pad(mask, k)
    out = np.zeros_like(mask)
    for di in range(2 * k + 1):
        for dj in range(2 * k + 1):
            out |= p[di:di + mask.shape[0], dj:dj + mask.shape[1]]
    return out


def categories(truth):
    pole = truth > 0.8
    block = dilate(pole, 3)
    halo = dilate(pole, 1) & ~pole
    box = (truth > 0.05) & ~pole
    edge = np.zeros_like(pole)
    edge[1:, :] |= np.abs(truth[1:, :] - truth[:-1, :]) > 0.05
    edge[:-1, :] |= np.abs(truth[:-1, :] - truth[1:, :]) > 0.05
    edge[:, 1:] |= np.abs(truth[:, 1:] - truth[:, :-1]) > 0.05
    edge[:, :-1] |= np.abs(truth[:, :-1] - truth[:, 1:]) > 0.05
    outline = edge & ~block
    near = dilate(edge, 2) & ~block & ~edge
    return {"pole": pole, "halo": halo, "trail": block & ~halo & ~pole,
            "edge_in": outline & box, "edge_out": outline & ~box,
            "near_in": near & box, "near_out": near & ~box,
            "top": box & ~near & ~edge & ~block,
            "floor": ~box & ~near & ~edge & ~block & ~pole}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dirs", nargs="+", metavar="BENCH_DIR")
    ap.add_argument("--pipelines", help="comma list (default: raw and the CAS variants)")
    ap.add_argument("--diff", help="A,B: A's share minus B's")
    args = ap.parse_args()
    if args.diff is not None and len(args.diff.split(",")) != 2:
        fail(f"--diff {args.diff!r}: expected two pipelines A,B")
    acc = {}  # (test, pipeline) -> category -> sum
    runs_of = {}
    for d in args.dirs:
        path = os.path.join(d, "bench.json")
        try:
            with open(path, encoding="utf-8") as f:
                runs = json.load(f)["runs"]
        except (OSError, ValueError, KeyError, TypeError) as e:
            fail(f"{path}: not a readable bench.json ({e})")
        for r in runs:
            name = f"course{r['course']:02d}_{r['test']}"
            folder = os.path.join(d, "runs", name)
            if not os.path.isdir(folder):
                fail(f"{folder}: missing (run casmap bench with --maps)")
            truth = read_tiff(os.path.join(folder, "truth.tif"))
            raw = read_tiff(os.path.join(folder, "raw.tif"))
            known = read_tiff(os.path.join(folder, "certainty.tif")) > 0
            den = float(((raw - truth) ** 2).sum())
            if den <= 0:
                continue  # PI undefined (raw = truth)
            if args.diff:
                names = args.diff.split(",")
            elif args.pipelines:
                names = args.pipelines.split(",")
            else:
                names = ["raw"] + sorted(p for p in r["filters"] if p.startswith("cas"))
            maps = {}
            for p in names:
                f = os.path.join(folder, f"{p}.tif")
                if not os.path.isfile(f):
                    fail(f"{f}: missing (pipeline {p} not in this bench)")
                maps[p] = raw if p == "raw" else read_tiff(f)
            err = {p: (m - truth) ** 2 / den for p, m in maps.items()}
            if args.diff:
                a, b = names
                err = {f"{a}-{b}": err[a] - err[b]}
            cats = categories(truth)
            runs_of[r["test"]] = runs_of.get(r["test"], 0) + 1
            for p, e in err.items():
                a = acc.setdefault((r["test"], p), {})
                for c, mask in cats.items():
                    for side, m in (("k", mask & known), ("u", mask & ~known)):
                        key = f"{c}/{side}"
                        a[key] = a.get(key, 0.0) + float(e[m].sum())
    keys = [f"{c}/{s}" for c in CATEGORIES for s in ("k", "u")]
    print("| test | pipeline | total | " + " | ".join(keys) + " |")
    print("|---" * (len(keys) + 3) + "|")
    for test in TESTS:
        n = runs_of.get(test)
        if not n:
            continue
        for (t, p), a in acc.items():
            if t != test:
                continue
            cells = [f"{a.get(k, 0.0) / n:+.4f}" if args.diff else f"{a.get(k, 0.0) / n:.4f}"
                     for k in keys]
            total = sum(a.values()) / n
            print(f"| {test} | {p} | {total:.4f} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
