#!/usr/bin/python3
"""In-process beamfea.run against the program per case, on the three-link chain of example 05.

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_run_rate.py [--exe build/cli/beamfea] [--n 400]

The models are examples/05_pashkevich_chain/models/B_Pi_{lumped,beam}.json (the Pashkevich
chain U_p R_a R_a S_p in the Pi posture: lumped = rigid links + one 6-D virtual spring per
link, beam = 8 co-rotational beams per link) with their analyses replaced by the `stiffness`
analysis of the end node E (its supports and the loads removed, as scripts/compare_models.py
does for the unloaded stiffness). Per model it times:
  api       beamfea.run(dict) in a loop (one thread);
  api x T   the same cases on a ThreadPoolExecutor of T threads;
  cli       what a script did before the module: write model.json, run
            `beamfea run model.json --out DIR --no-vtk -q`, read DIR/results.json.
and prints a markdown table (runs per second, and the ratio to the cli).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from find_beamfea import import_beamfea  # noqa: E402

beamfea = import_beamfea()


def stiffness_model(name):
    with open(os.path.join(ROOT, "examples", "05_pashkevich_chain", "models", name)) as f:
        d = json.load(f)
    d["supports"] = [s for s in d.get("supports", []) if s.get("node") != "E"]
    d["prescribed"] = [s for s in d.get("prescribed", []) if s.get("node") != "E"]
    d.pop("loads", None)
    d["analyses"] = [{"id": "K", "type": "stiffness", "node": "E"}]
    return d


def rate(fn, n):
    fn()  # warm up
    t0 = time.perf_counter()
    fn(n)
    return n / (time.perf_counter() - t0)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "cli", "beamfea"))
    ap.add_argument("--n", type=int, default=400, help="in-process runs per measurement")
    ap.add_argument("--n-cli", type=int, default=100, help="program runs per measurement")
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    rows = []
    tmp = tempfile.mkdtemp(prefix="beamfea_bench_")
    for name in ("B_Pi_lumped.json", "B_Pi_beam.json"):
        doc = stiffness_model(name)
        check = beamfea.check(doc)
        res = beamfea.run(doc)
        dofs = res["analyses"]["K"].get("free_dofs", "")
        api = rate(lambda n=1: [beamfea.run(doc) for _ in range(n)], args.n)

        def threaded(n=1):
            with ThreadPoolExecutor(args.threads) as pool:
                list(pool.map(lambda _: beamfea.run(doc), range(n)))
        api_t = rate(threaded, args.n)

        def cli(n=1):
            for _ in range(n):
                model = os.path.join(tmp, "model.json")
                with open(model, "w") as f:
                    json.dump(doc, f)
                subprocess.run([args.exe, "run", model, "--out", tmp, "--no-vtk", "-q"], check=True)
                with open(os.path.join(tmp, "results.json")) as f:
                    json.load(f)
        cli_rate = rate(cli, args.n_cli)
        rows.append((name, check["nodes"], check["joints"], dofs, api, api_t, cli_rate))
    print(f"load average {os.getloadavg()[0]:.1f}, {os.cpu_count()} cores")
    print(f"| model | nodes | joints | api runs/s | api x {args.threads} threads runs/s | cli runs/s | api / cli |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name, nodes, joints, dofs, api, api_t, cli_rate in rows:
        print(f"| {name} | {nodes} | {joints} | {api:.0f} | {api_t:.0f} | {cli_rate:.1f} | {api / cli_rate:.0f}x |")


if __name__ == "__main__":
    main()
