#!/usr/bin/python3
"""Regenerates the baseline-filter golden files used by tests/mapper/baseline_filters_test.cpp.

Run from anywhere with Debian's python (numpy, scipy):  /usr/bin/python3 make_filter_golden.py
Files (raw little-endian float32, row-major, ROWS x COLS = 24 x 30):
  filter_input.f32    the input elevation map (metres): noisy floor, a box, spikes, holes
  median5.f32         scipy.ndimage.median_filter(size=5, mode='nearest')  (edge replicated)
  average5.f32        scipy.ndimage.uniform_filter(size=5, mode='nearest') (float64, rounded)
  wiener5_n001.f32    scipy.signal.wiener(x, 5, noise=0.001) (zero padding: compare interior)
"""
import os

import numpy as np
import scipy.ndimage as ndi
import scipy.signal as sig

ROWS, COLS = 24, 30
here = os.path.dirname(os.path.abspath(__file__))
rng = np.random.RandomState(20261122)
x = rng.uniform(-0.004, 0.004, size=(ROWS, COLS))
x[6:14, 8:18] += 0.414                     # a box
for _ in range(12):                        # spikes
    x[rng.randint(ROWS), rng.randint(COLS)] = rng.uniform(0.1, 0.9)
for _ in range(10):                        # holes
    x[rng.randint(ROWS), rng.randint(COLS)] = 0.0
x = x.astype(np.float32)


def save(name, a):
    np.asarray(a, dtype='<f4').tofile(os.path.join(here, name))


save('filter_input.f32', x)
save('median5.f32', ndi.median_filter(x, size=5, mode='nearest'))
save('average5.f32', ndi.uniform_filter(x.astype(np.float64), size=5, mode='nearest'))
save('wiener5_n001.f32', sig.wiener(x.astype(np.float64), 5, noise=0.001))
