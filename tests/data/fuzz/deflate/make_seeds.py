#!/usr/bin/env python3
"""Writes the seed inputs of deflate_fuzz (io/fuzz/deflate_fuzz.cpp) into this folder.

An input is 7 bytes of layout (uint16 segment_bytes, uint16 distance_a, uint16 distance_b,
uint8 hashed; little-endian) and the bytes to encode. The seeds imitate what the run-file
writer encodes: shuffled float ranges, label rows, time stamps, plus text and random bytes.
Run: /usr/bin/python3 tests/data/fuzz/deflate/make_seeds.py
"""
import pathlib
import struct

import numpy as np

here = pathlib.Path(__file__).resolve().parent
rng = np.random.default_rng(20261128)


def header(segment, distance_a, distance_b, hashed):
    return struct.pack('<HHHB', segment, distance_a, distance_b, hashed)


ranges = (2.0 + 0.01 * np.arange(181)[None, :] +
          0.003 * rng.standard_normal((20, 181))).astype('<f4')
planes = ranges.view(np.uint8).reshape(-1, 4).T.copy().tobytes()
(here / 'seed_ranges_shuffled').write_bytes(header(len(planes) // 4, 1, 181, 1) + planes)
labels = np.zeros((20, 181), np.uint8)
labels[:, 80:84] = 2
labels[5, 10] = 3
(here / 'seed_labels_rows').write_bytes(header(0, 1, 181, 0) + labels.tobytes())
stamps = (np.arange(300) * 0.0133).astype('<f8').tobytes()
(here / 'seed_stamps').write_bytes(header(0, 8, 0, 1) + stamps)
(here / 'seed_text').write_bytes(header(0, 1, 0, 1) + b'casmap run file ' * 40 + bytes(range(256)))
(here / 'seed_random').write_bytes(
    header(300, 3, 32768, 1) + rng.integers(0, 256, 2000, dtype=np.uint8).tobytes())
