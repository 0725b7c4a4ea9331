#!/usr/bin/python3
"""Temporal power spectrum of frame sequences made from a static reference (thesis §4.4.1.1).

The reference shows the same image in every frame, so motion compensation is the identity and
each pixel's sequence of values is its temporal signal. Prints, per sequence, the mean temporal
energy (variance over frames, averaged over pixels and channels) and the power of every
non-zero temporal frequency relative to the mean over them (white noise: 1 everywhere).

Usage: spectrum.py NAME=PATTERN... --count N
       e.g. spectrum.py f2=out/noisy/static-f2/%04d.png f4=... --count 32
Needs Debian's python3-numpy and python3-pil.
"""
import argparse

import numpy as np
from PIL import Image


def load(pattern, count):
    frames = [np.asarray(Image.open(pattern % i), dtype=np.float64) / 255.0 for i in range(count)]
    return np.stack(frames)  # (frames, height, width, channels)


def spectrum(frames):
    signal = frames.reshape(frames.shape[0], -1)
    energy = float(signal.var(axis=0).mean())
    energy = energy if energy > 1e-20 else 0.0  # rounding residue of a static sequence
    power = (np.abs(np.fft.rfft(signal, axis=0)) ** 2 / signal.shape[0]).mean(axis=1)
    nonzero = power[1:]
    mean = nonzero.mean()
    return energy, nonzero / mean if mean > 1e-20 else None  # None: a static sequence


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sequences", nargs="+", help="NAME=PATTERN (printf pattern, from 0)")
    parser.add_argument("--count", type=int, default=32, help="frames per sequence")
    args = parser.parse_args()
    rows = []
    for item in args.sequences:
        name, pattern = item.split("=", 1)
        energy, relative = spectrum(load(pattern, args.count))
        rows.append((name, energy, relative))
    bins = args.count // 2
    print("| sequence | temporal energy | " + " | ".join(str(k) for k in range(1, bins + 1)) +
          " | min..max |")
    print("|---|---|" + "---|" * bins + "---|")
    for name, energy, relative in rows:
        if relative is None:
            print(f"| {name} | {energy:.1e} | " + " | ".join("–" for _ in range(bins)) + " | – |")
            continue
        print(f"| {name} | {energy:.2e} | " + " | ".join(f"{p:.2f}" for p in relative) +
              f" | {relative.min():.2f}..{relative.max():.2f} |")


if __name__ == "__main__":
    main()
