"""Samples per second of the plugin's loader at 512 x 1024, without augmentation and with FDA-R
and FDA-E, 2 DataLoader workers (the baseline is the plain loader in the same run).

    PYTHONPATH=python:build/python python3 bench/bench_loader.py [release] [--samples 24]

Without a release it makes one (1 sequence of 7 frames, 512 x 1024, 1 spp, ERP only)."""
import argparse
import os
import subprocess
import tempfile
import time

import torch

import flowscape


def rate(dataset, samples, workers):
    loader = torch.utils.data.DataLoader(dataset, batch_size=1, num_workers=workers, shuffle=False)
    start, seen = time.time(), 0
    while seen < samples:
        for _ in loader:
            seen += 1
            if seen >= samples:
                break
    return seen / (time.time() - start)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("release", nargs="?")
    parser.add_argument("--samples", type=int, default=24)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    release = args.release
    if release is None:
        release = tempfile.mkdtemp(prefix="flowscape-bench-loader-")
        binaries = os.environ.get("FLOWSCAPE_BIN", "build/apps")
        subprocess.run([f"{binaries}/gen_flowscape", "--maps", "1", "--sequences-per-map", "1",
                        "--frames", "7", "--spp", "1", "--no-cube", "--weather", "sunny",
                        "--out", release], check=True, capture_output=True)
        subprocess.run([f"{binaries}/flowscape_split", release, "--no-panoflow"], check=True,
                       capture_output=True)
    print(f"bench_loader: {args.samples} samples of {release}, {args.workers} workers, "
          f"native extension {'yes' if flowscape.native_available() else 'no (numpy)'}")
    plain = rate(flowscape.FlowScape(release, "train"), args.samples, args.workers)
    print(f"  baseline: no augmentation   {plain:6.2f} samples/s")
    for fda in ("r", "e"):
        augmented = flowscape.FlowScape(release, "train", transform=flowscape.Augmentation(
            fda=fda, fda_probability=1.0, shift=False, jitter=False, seed=1))
        print(f"  FDA-{fda.upper()} on every sample     {rate(augmented, args.samples, args.workers):6.2f} samples/s")


if __name__ == "__main__":
    main()
