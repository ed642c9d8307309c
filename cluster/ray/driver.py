#!/usr/bin/env python3
"""A grinlight render as N shards on Ray, then their merge.

    python cluster/ray/driver.py SCENE N OUT [render options...]

Each shard is one Ray task (one CPU) that runs
`grinlight render SCENE --shard K/N -o OUT/shard-K-of-N.partial --threads 1 [options]`;
a task that fails (a lost node) is retried by Ray and continues its own partial (--resume).
When every shard is done, the driver runs `grinlight merge` into OUT/result.exr (with the PNG
and receivers' files beside it): bit for bit what one whole render writes.

Ray joins the cluster named by RAY_ADDRESS, or starts a local one (all of this machine's
cores). Every node must see the scene, OUT and the binary: set GRINLIGHT to its path if it
is not on the nodes' PATH.
"""
import os
import subprocess
import sys

import ray


@ray.remote(num_cpus=1, max_retries=3)
def shard(grinlight, scene, k, n, out, options):
    """Renders shard k/n into its partial file and returns the file's path."""
    partial = os.path.join(out, f"shard-{k}-of-{n}.partial")
    command = [grinlight, "render", scene, "--shard", f"{k}/{n}", "-o", partial,
               "--threads", "1", *options]
    if os.path.exists(partial):
        command.append("--resume")
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        raise RuntimeError(f"shard {k}/{n} failed:\n{run.stderr}")
    return partial


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    scene = os.path.abspath(sys.argv[1])
    n = int(sys.argv[2])
    out = os.path.abspath(sys.argv[3])
    options = sys.argv[4:]
    grinlight = os.environ.get("GRINLIGHT", "grinlight")
    os.makedirs(out, exist_ok=True)
    ray.init(address=os.environ.get("RAY_ADDRESS"), include_dashboard=False,
             log_to_driver=False)
    partials = ray.get([shard.remote(grinlight, scene, k, n, out, options)
                        for k in range(1, n + 1)])
    subprocess.run([grinlight, "merge", *partials, "-o", os.path.join(out, "result.exr")],
                   check=True, stdout=subprocess.DEVNULL)
    print(f"merged {n} shards into {os.path.join(out, 'result.exr')}")


if __name__ == "__main__":
    main()
