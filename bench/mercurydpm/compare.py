#!/usr/bin/env python3
"""The paper's DPM free-cooling test in MercuryDPM and in hgridlab, side by side.

    MERCURYDPM_SRC=/path/to/MercuryDPM bash bench/mercurydpm/build.sh    # once
    python3 bench/mercurydpm/compare.py [--scale default] [--rounds 2]

Runs, in each round and in turn: hgridlab's scene experiments/dpm_free_cooling.toml
(its optimal HGrid and its linked cell, `hgrid run --json`), then MercuryDPM on the
same discs (the scene's own cached packing, exported with `hgrid export --xyz`),
the same initial velocities, walls, contact law and time step, with MercuryDPM's
HGrid at hgridlab's optimal sizes, at one level of the scene's reference size
(the linked cell) and at MercuryDPM's default choice. Keeps the fastest run of
each, and writes one JSON file (default results/mercurydpm_free_cooling.json,
written under a temporary name, then renamed) with the times, the ratios, the
energy curves and where and with what they were measured. Progress on stderr.
Without the MercuryDPM build (MERCURYDPM_BUILD, default build-mercurydpm/) it
says so and exits 0.
"""
import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "experiments", "dpm_free_cooling.toml")


def log(msg):
    print("mercurydpm compare: " + msg, file=sys.stderr, flush=True)


def scene_values(scale):
    """The scene's [initial], [contact], [run] and [grids] tables with the scale's overrides."""
    with open(SCENE, "rb") as f:
        s = tomllib.load(f)
    over = s.get("scale", {}).get(scale, {})
    out = {}
    for table in ("initial", "contact", "run", "grids"):
        out[table] = dict(s.get(table, {}))
        out[table].update(over.get(table, {}))
    return out


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def git_hash():
    try:
        h = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short=12", "HEAD"], capture_output=True, text=True,
                           check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return h + ("-dirty" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def relative_gap(a, b):
    """Largest |a_i / b_i - 1| over the samples both have."""
    n = min(len(a), len(b))
    return max(abs(a[i] / b[i] - 1) for i in range(n)) if n else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scale", default="default", choices=["smoke", "default", "paper"])
    ap.add_argument("--rounds", type=int, default=2, help="alternations; the fastest run of each grid is kept")
    ap.add_argument("--hgrid", default=os.path.join(ROOT, "build", "hgrid"))
    ap.add_argument("--out", default=None, help="JSON result (default results/mercurydpm_free_cooling[-SCALE].json)")
    a = ap.parse_args()
    if a.rounds < 1:
        sys.exit("mercurydpm compare: rounds: must be >= 1")
    build = os.environ.get("MERCURYDPM_BUILD", os.path.join(ROOT, "build-mercurydpm"))
    driver = os.path.join(build, "drivers", "mercurydpm_free_cooling")
    if not os.path.exists(driver):
        print("MercuryDPM comparison skipped: no %s (MERCURYDPM_SRC=... bash bench/mercurydpm/build.sh builds it)"
              % driver)
        return 0
    with open(os.path.join(build, "COMMIT")) as f:
        mercury_commit = f.read().strip()
    sc = scene_values(a.scale)
    ini, con, run, grids = sc["initial"], sc["contact"], sc["run"], sc["grids"]
    if ini.get("d") != 2 or ini.get("boundary") != "walls" or sc["initial"].get("placement") != "excluded":
        sys.exit("mercurydpm compare: the driver runs 2D discs between walls from an excluded-volume packing")

    with tempfile.TemporaryDirectory(prefix="hgridlab_mercurydpm_") as tmp:
        # The scene's own packing (the cache `hgrid run` uses), as extended XYZ.
        packing = subprocess.run(
            [a.hgrid, "generate", "--d", "2", "--n", str(ini["n"]), "--nu", str(ini["nu"]), "--alpha",
             str(ini["alpha"]), "--omega", str(ini["omega"]), "--boundary", "walls", "--placement", "excluded",
             "--seed", str(ini["seed"]), "--cache", os.path.join(ROOT, "results", "packings"), "--quiet"],
            capture_output=True, text=True, check=True).stdout.strip().splitlines()[-1]
        xyz = os.path.join(tmp, "packing.xyz")
        subprocess.run([a.hgrid, "export", packing, "--xyz", xyz], capture_output=True, check=True)

        best = {}

        def keep(name, result, seconds):
            if name not in best or seconds < best[name][1]:
                best[name] = (result, seconds)

        hg, e_h = None, []
        for r in range(a.rounds):
            log("round %d/%d: hgridlab (optimal HGrid, linked cell)" % (r + 1, a.rounds))
            out = subprocess.run([a.hgrid, "run", SCENE, "--scale", a.scale, "--results", tmp, "--packings",
                                  os.path.join(ROOT, "results", "packings"), "--json"],
                                 capture_output=True, text=True, check=True).stdout
            hg = json.loads(out)
            suffix = "" if a.scale == "default" else "-" + a.scale
            with open(os.path.join(tmp, "dpm_free_cooling%s.csv" % suffix)) as f:
                e_h = [float(l.split(",")[1]) for l in f if l[:1].isdigit()]  # t,E_optimal,...
            keep("hgridlab_optimal", hg["optimal"], hg["optimal"]["seconds_total"])
            keep("hgridlab_linked_cell", hg["linked_cell"], hg["linked_cell"]["seconds_total"])
            sizes = {
                "mercurydpm_optimal": ",".join(repr(s) for s in hg["optimal"]["sizes"]),
                "mercurydpm_linked_cell": repr(float(grids.get("reference_size", 40))),
                "mercurydpm_default": "default",
            }
            for name, grid in sizes.items():
                log("round %d/%d: MercuryDPM, %s (%s)" % (r + 1, a.rounds, name.split("_", 1)[1], grid))
                t0 = time.time()
                res = json.loads(subprocess.run(
                    [driver, xyz, str(run["steps"]), grid, str(run["sample_every"]), str(con["contact_time"]),
                     str(con["restitution"]), str(con["dt_over_tc"]), str(ini["speed"]), str(ini["velocity_seed"])],
                    capture_output=True, text=True, check=True).stdout)
                log("  %.1f s" % (time.time() - t0))
                keep(name, res, res["seconds_total"])

        # MercuryDPM's K: its search of the initial state (no forces) timed
        # (fastest of 5) and counted at the three grids; seconds = c_access
        # accesses + c_check candidates, least squares through the origin;
        # K = c_access / c_check.
        # (Each run timed and counted the search of its initial state.)
        probes = {name: best[name][0] for name in sizes}
        rows = [(p["cell_accesses_initial_state"], p["candidates_initial_state"], p["seconds_search_initial_state"])
                for p in probes.values()]
        saa = sum(a_ * a_ for a_, c_, t_ in rows)
        scc = sum(c_ * c_ for a_, c_, t_ in rows)
        sac = sum(a_ * c_ for a_, c_, t_ in rows)
        sat = sum(a_ * t_ for a_, c_, t_ in rows)
        sct = sum(c_ * t_ for a_, c_, t_ in rows)
        det = saa * scc - sac * sac
        c_access = (sat * scc - sct * sac) / det
        c_check = (sct * saa - sat * sac) / det
        k_m = c_access / c_check
        po, pl = probes["mercurydpm_optimal"], probes["mercurydpm_linked_cell"]

        def T(p, K):
            return p["candidates_initial_state"] + K * p["cell_accesses_initial_state"]

        k_fit = {
            "seconds_per_cell_access": c_access,
            "seconds_per_candidate_check": c_check,
            "K": k_m,
            "grids": {k: {f: v[f] for f in ("cell_accesses_initial_state", "candidates_initial_state",
                                          "seconds_search_initial_state")} for k, v in probes.items()},
            "count_ratio_T_K0.2": T(pl, 0.2) / T(po, 0.2),
            "count_ratio_T_K_mercurydpm": T(pl, k_m) / T(po, k_m),
            "measured_search_speedup_initial_state": pl["seconds_search_initial_state"] / po["seconds_search_initial_state"],
        }

    def sec(name, key="seconds_total"):
        return best[name][0][key]

    m_opt, m_lc = best["mercurydpm_optimal"][0], best["mercurydpm_linked_cell"][0]
    h_opt = best["hgridlab_optimal"][0]
    summary = {
        "scene": os.path.relpath(SCENE, ROOT),
        "scale": a.scale,
        "n": hg["n"],
        "steps": hg["steps"],
        "rounds": a.rounds,
        "machine": cpu_model(),
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "hgridlab_git_hash": git_hash(),
        "mercurydpm_commit": mercury_commit,
        "command": "python3 bench/mercurydpm/compare.py --scale %s --rounds %d" % (a.scale, a.rounds),
        "paper_speedup_total": 9.9,
        "mercurydpm": {
            "speedup_total": sec("mercurydpm_linked_cell") / sec("mercurydpm_optimal"),
            "speedup_forces_loop": sec("mercurydpm_linked_cell", "seconds_forces_loop")
            / sec("mercurydpm_optimal", "seconds_forces_loop"),
            "speedup_search_final_state": sec("mercurydpm_linked_cell", "seconds_search_final_state")
            / sec("mercurydpm_optimal", "seconds_search_final_state"),
            "candidates_ratio_final_state": m_lc["candidates_final_state"] / m_opt["candidates_final_state"],
            "default_over_optimal_total": sec("mercurydpm_default") / sec("mercurydpm_optimal"),
        },
        "hgridlab": {
            "speedup_total": sec("hgridlab_linked_cell") / sec("hgridlab_optimal"),
            "speedup_contact_detection": sec("hgridlab_linked_cell", "seconds_contact_detection")
            / sec("hgridlab_optimal", "seconds_contact_detection"),
        },
        "mercurydpm_over_hgridlab_total": {
            "optimal": sec("mercurydpm_optimal") / sec("hgridlab_optimal"),
            "linked_cell": sec("mercurydpm_linked_cell") / sec("hgridlab_linked_cell"),
        },
        "mercurydpm_K_fit": k_fit,
        "runs": {k: v[0] for k, v in best.items()},
    }
    # The same physics: both codes' kinetic energy at the same sample times.
    summary["runs"]["hgridlab_optimal"]["E"] = e_h
    summary["energy_initial"] = {"mercurydpm": m_opt["E"][0], "hgridlab": e_h[0]}
    summary["energy_final_over_initial"] = {"mercurydpm_optimal": m_opt["E"][-1] / m_opt["E"][0],
                                            "mercurydpm_linked_cell": m_lc["E"][-1] / m_lc["E"][0],
                                            "hgridlab_optimal": h_opt.get("energy_final_over_initial")}
    summary["energy_largest_relative_gap_mercurydpm_vs_hgridlab"] = relative_gap(m_opt["E"], e_h)
    out = a.out or os.path.join(ROOT, "results", "mercurydpm_free_cooling%s.json" %
                                ("" if a.scale == "default" else "-" + a.scale))
    tmp_out = out + ".tmp"
    with open(tmp_out, "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    os.replace(tmp_out, out)
    m = summary["mercurydpm"]
    log("MercuryDPM: whole run %.2fx faster with the optimal HGrid than the linked cell (paper: 9.9x); forces loop "
        "%.2fx; one search %.2fx; hgridlab %.2fx (contact detection %.2fx); MercuryDPM / hgridlab whole run: "
        "optimal %.2f, linked cell %.2f; wrote %s" % (
            m["speedup_total"], m["speedup_forces_loop"], m["speedup_search_final_state"],
            summary["hgridlab"]["speedup_total"], summary["hgridlab"]["speedup_contact_detection"],
            summary["mercurydpm_over_hgridlab_total"]["optimal"],
            summary["mercurydpm_over_hgridlab_total"]["linked_cell"], out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
