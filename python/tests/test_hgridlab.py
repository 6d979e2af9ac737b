"""The Python module hgridlab: recommend, pairs, count, read_packing.

Run by ctest (Python.Pytest) with PYTHONPATH=<build>/python; seeds are
parameters, tolerances named constants."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import hgridlab

SEED = 7
SAME_SIZES_REL_TOL = 1e-12  # the module and the command run the same code on the same doubles


def power_law_radii(rng, n, alpha=-3.0, omega=10.0):
    """Radii r^alpha on [1, omega] by inverse CDF."""
    u = rng.random(n)
    e = alpha + 1.0
    return (1.0 + u * (omega**e - 1.0)) ** (1.0 / e)


def scene(n=300, nu=0.3, d=3, seed=SEED):
    rng = np.random.default_rng(seed)
    radii = power_law_radii(rng, n)
    vol = np.sum(np.pi * radii**2) if d == 2 else np.sum(4.0 / 3.0 * np.pi * radii**3)
    side = (vol / nu) ** (1.0 / d)
    positions = rng.random((n, d)) * side
    return positions, radii, np.full(d, side)


def brute_pairs(positions, radii, box, periodic):
    diff = positions[:, None, :] - positions[None, :, :]
    if periodic:
        diff -= box * np.round(diff / box)
    dist2 = np.sum(diff**2, axis=-1)
    reach = (radii[:, None] + radii[None, :]) ** 2
    i, j = np.nonzero(np.triu(dist2 <= reach, k=1))
    return set(zip(i.tolist(), j.tolist()))


@pytest.fixture(autouse=True)
def no_calibration(monkeypatch, tmp_path):
    monkeypatch.setenv("HGRID_CALIBRATION", str(tmp_path / "none.json"))


def test_version():
    assert hgridlab.__version__.count(".") == 2


def test_recommend_matches_the_command(tmp_path):
    _, radii, _ = scene(n=2000)
    r = hgridlab.recommend(radii, nu=0.6, d=3)
    assert r["K_source"] == "paper" and r["K"] == 0.2
    assert r["levels"] >= 2 and r["levels"] == len(r["sizes"])
    assert all(a < b for a, b in zip(r["sizes"], r["sizes"][1:]))
    assert r["sizes"][-1] == 2 * radii.max()
    assert r["speedup"] == pytest.approx(r["linked_cell_T_over_N"] / r["T_over_N"], rel=1e-15)
    c = r["lammps_collections"]
    assert all(a < b for a, b in zip(c, c[1:])) and c[-1] == 2 * radii.max()
    assert r["lammps"][1].startswith("neigh_modify collection/interval %d " % len(c))
    path = tmp_path / "r.txt"
    path.write_text("".join("%r\n" % v for v in radii.tolist()))
    out = subprocess.run([os.environ["HGRID_BINARY"], "recommend", str(path), "--nu", "0.6", "--d", "3", "--json"],
                         check=True, capture_output=True, text=True).stdout
    j = json.loads(out)
    assert j["sizes"] == pytest.approx(r["sizes"], rel=SAME_SIZES_REL_TOL)
    assert set(r) == set(j) - {"file", "format", "frames", "n", "nu_source", "box", "tilt", "boundary"}
    assert hgridlab.recommend(radii, 0.6, 3, K=0.8)["K_source"] == "given"


BEDS = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "beds")


@pytest.mark.parametrize("name", ["bed3d_o5_s1.dump", "bed2d_o10_s2.dump"])
def test_recommend_from_positions_takes_the_density_field(name):
    # A bed LAMMPS poured under a tall empty box: the box's nu
    # predicts half the work; the field model predicts what the grid counts.
    p = hgridlab.read_packing(os.path.join(BEDS, name))
    d, periodic = p["d"], p["boundary"] == "periodic"
    r = hgridlab.recommend(p["radii"], d=d, positions=p["positions"], box=p["box"][:d], periodic=periodic)
    f = r["field"]
    assert f["far_from_homogeneous"] and f["sizes_from"] == "field"
    assert f["mean_local_nu"] > 2.5 * f["box_nu"] and r["nu"] == f["effective_nu"]
    got = hgridlab.count(p["positions"], p["radii"], p["box"][:d], periodic, sizes=r["sizes"], threads=1)
    assert r["T_over_N"] == pytest.approx(got["T_over_N"], rel=0.10)
    h = hgridlab.recommend(p["radii"], nu=p["nu"], d=d)
    assert h["field"] is None and h["T_over_N"] < 0.6 * got["T_over_N"]
    with pytest.raises(ValueError, match="box"):
        hgridlab.recommend(p["radii"], d=d, positions=p["positions"])
    with pytest.raises(ValueError, match="nu"):
        hgridlab.recommend(p["radii"], d=d)


def test_recommend_in_a_tilted_box_takes_the_mapped_packing():
    # A packing LAMMPS sheared to xy = lx / 2: the sizes of the mapped
    # packing its grid searches, as `hgrid recommend` gives the file.
    path = os.path.join(BEDS, "shear3d_o5.dump")
    p = hgridlab.read_packing(path)
    r = hgridlab.recommend(p["radii"], d=3, K=0.2, box=p["box"], tilt=p["tilt"])
    assert r["tilt_inflation"] > 1.2
    j = json.loads(subprocess.run([os.environ["HGRID_BINARY"], "recommend", path, "--K", "0.2", "--json"], check=True,
                                  capture_output=True, text=True).stdout)
    assert r["sizes"] == pytest.approx(j["sizes"], rel=SAME_SIZES_REL_TOL)
    got = hgridlab.count(p["positions"], p["radii"], p["box"], True, sizes=r["sizes"], threads=1, tilt=p["tilt"])
    assert r["T_over_N"] == pytest.approx(got["T_over_N"], rel=0.10)
    with pytest.raises(ValueError, match="tilt"):
        hgridlab.recommend(p["radii"], d=3, box=p["box"], tilt=[1.0])


def test_recommend_refuses_bad_input():
    with pytest.raises(ValueError, match="radii"):
        hgridlab.recommend(np.array([1.0, -1.0]), nu=0.5, d=3)
    with pytest.raises(ValueError, match="nu"):
        hgridlab.recommend(np.array([1.0, 2.0]), nu=-1, d=3)


@pytest.mark.parametrize("d,periodic", [(3, True), (3, False), (2, True)])
def test_pairs_equal_brute_force(d, periodic):
    positions, radii, box = scene(d=d, nu=0.4)
    if not periodic:
        positions = np.clip(positions, 0, box)
    got = hgridlab.pairs(positions, radii, box, periodic)
    assert got.dtype == np.uint32 and got.ndim == 2 and got.shape[1] == 2
    assert np.all(got[:, 0] < got[:, 1])
    assert set(map(tuple, got.tolist())) == brute_pairs(positions, radii, box, periodic)
    assert len(got) > 0
    fixed = hgridlab.pairs(positions, radii, box, periodic, sizes=[4.0, 2 * radii.max()])
    assert set(map(tuple, fixed.tolist())) == brute_pairs(positions, radii, box, periodic)


def test_recommend_cost(monkeypatch, tmp_path):
    radii = np.linspace(1.0, 10.0, 500)
    assert hgridlab.recommend(radii, 0.6, 3, K=0.2, cost="count")["cost"] == "count"
    with pytest.raises(ValueError, match="cost"):
        hgridlab.recommend(radii, 0.6, 3, cost="fast")
    monkeypatch.setenv("HGRID_CALIBRATION", str(tmp_path / "none.json"))  # no calibration stored
    assert hgridlab.recommend(radii, 0.6, 3)["cost"] == "count"  # auto without one: the paper's K
    with pytest.raises(ValueError, match="cost"):
        hgridlab.recommend(radii, 0.6, 3, cost="time")


def test_threads_give_the_same_pairs_and_counts():
    positions, radii, box = scene(nu=0.4)
    want = brute_pairs(positions, radii, box, True)
    counts = []
    for threads in (1, 2, 3, 8):
        got = hgridlab.pairs(positions, radii, box, True, threads=threads)
        assert set(map(tuple, got.tolist())) == want and len(got) == len(want)
        c = hgridlab.count(positions, radii, box, True, threads=threads)
        counts.append((c["cell_accesses"], c["narrow_phase_checks"], c["contacts"], c["checks_by_level"]))
    assert all(c == counts[0] for c in counts)
    with pytest.raises(ValueError, match="threads"):
        hgridlab.pairs(positions, radii, box, True, threads=-1)


def test_count_returns_the_counts():
    positions, radii, box = scene(nu=0.4)
    c = hgridlab.count(positions, radii, box, True, sizes=[4.0, 2 * radii.max()], K=0.5)
    assert c["contacts"] == len(hgridlab.pairs(positions, radii, box, True, sizes=[4.0, 2 * radii.max()]))
    assert c["levels"] == 2 and len(c["accesses_by_level"]) == 2 * 2  # L x L: level of the particle, level searched
    assert sum(c["particles_per_level"]) == len(radii)
    assert c["T_over_N"] == pytest.approx((c["narrow_phase_checks"] + 0.5 * c["cell_accesses"]) / len(radii), rel=1e-15)
    with pytest.raises(ValueError, match="sizes"):
        hgridlab.count(positions, radii, box, True, sizes=[1.0])  # below the largest diameter


def test_count_has_the_fields_of_count_json(tmp_path):
    positions, radii, box = scene(nu=0.3)
    c = hgridlab.count(positions, radii, box, True, K=0.2, threads=1, model=True)
    names = [f[0] for f in hgridlab.measurement_fields()]
    assert list(c) == names  # one table: the same names, in the same order
    path = tmp_path / "p.csv"
    path.write_text("# box %r %r %r\n# boundary periodic\nx,y,z,r\n" % tuple(box)
                    + "".join("%r,%r,%r,%r\n" % (*p, r) for p, r in zip(positions.tolist(), radii.tolist())))
    sizes = ",".join(repr(s) for s in c["sizes_requested"])
    out = subprocess.run([os.environ["HGRID_BINARY"], "count", str(path), "--sizes", sizes, "--threads", "1", "--json"],
                         check=True, capture_output=True, text=True).stdout
    j = json.loads(out)
    assert list(j) == names
    for k in ("cell_accesses", "narrow_phase_checks", "contacts", "accesses_by_level", "checks_by_level",
              "particles_per_level", "levels", "n"):
        assert j[k] == c[k], k
    assert j["model_T_over_N"] == pytest.approx(c["model_T_over_N"], rel=1e-12)
    assert c["seconds_query_best"] is None and c["repeats"] == 0  # not asked: None


def test_read_packing_every_kind(tmp_path):
    csv = tmp_path / "p.csv"
    csv.write_text("# box 10 10 10\n# boundary walls\nid,x,y,z,diameter\n1,1,2,3,1\n2,4,5,6,0.5\n")
    p = hgridlab.read_packing(str(csv))
    assert p["format"] == "table" and p["d"] == 3 and p["boundary"] == "walls"
    assert p["radii"].tolist() == [0.5, 0.25]
    assert p["positions"].shape == (2, 3) and p["positions"][1].tolist() == [4, 5, 6]
    assert p["box"] == [10, 10, 10]
    radii_only = tmp_path / "r.txt"
    radii_only.write_text("0.5\n1\n")
    q = hgridlab.read_packing(str(radii_only))
    assert q["positions"] is None and q["box"] is None and q["nu"] is None
    bad = tmp_path / "bad.txt"
    bad.write_text("x y r\n1 2 0.5\n1 2 zz\n")
    with pytest.raises(ValueError, match="bad.txt:3"):
        hgridlab.read_packing(str(bad))


def test_read_packing_takes_the_last_snapshot_or_the_frame_asked(tmp_path):
    """A MercuryDPM .data file of two 2D snapshots (header 'N t xmin ymin xmax ymax')."""
    path = tmp_path / "run.data"
    path.write_text("1 0 0 0 10 10\n1 1 0 0 0.5 0 0 0\n2 1 0 0 10 10\n2 2 0 0 1 0 0 0\n5 5 0 0 0.5 0 0 0\n")
    last = hgridlab.read_packing(str(path))
    assert last["format"] == "mercury_data" and last["frame"] == 1 and last["frames"] == 2
    assert last["d"] == 2 and list(last["radii"]) == [1.0, 0.5]
    first = hgridlab.read_packing(str(path), frame=0)
    assert list(first["radii"]) == [0.5] and first["box"] == [10.0, 10.0]
    with pytest.raises(ValueError, match="frame"):
        hgridlab.read_packing(str(path), frame=2)


@pytest.mark.parametrize("d", [2, 3])
def test_pairs_in_a_tilted_box_equal_brute_force(d):
    """A tilted (triclinic) periodic box, LAMMPS's: centres at uniform
    fractional coordinates, pairs against numpy's minimum image of the lattice."""
    positions, radii, box = scene(n=400, nu=0.2, d=d, seed=SEED + d)
    tilt = [0.4 * box[0]] if d == 2 else [0.4 * box[0], -0.3 * box[0], 0.25 * box[1]]
    H = np.diag(box)
    H[0, 1] = tilt[0]
    if d == 3:
        H[0, 2], H[1, 2] = tilt[1], tilt[2]
    frac = np.random.default_rng(SEED).random((len(radii), d))
    positions = frac @ H.T
    diff = positions[:, None, :] - positions[None, :, :]
    s = diff @ np.linalg.inv(H).T
    diff = (s - np.round(s)) @ H.T
    dist2 = np.sum(diff**2, axis=-1)
    reach = (radii[:, None] + radii[None, :]) ** 2
    i, j = np.nonzero(np.triu(dist2 < reach, k=1))
    want = sorted(zip(i.tolist(), j.tolist()))
    got = hgridlab.pairs(positions, radii, box, tilt=tilt)
    assert sorted(map(tuple, got.tolist())) == want
    assert len(want) > 0
    c = hgridlab.count(positions, radii, box, tilt=tilt)
    assert c["contacts"] == len(want)
    assert c["tilt"] == pytest.approx(tilt)
    assert c["tilt_inflation"] > 1.0


def brute_pairs_per_axis(positions, radii, box, periodic, origin):
    """The pairs with distance < r_i + r_j, minimum image on the periodic axes."""
    x = positions - origin
    per = np.asarray(periodic)
    x[:, per] = np.mod(x[:, per], box[per])
    diff = x[None, :, :] - x[:, None, :]
    diff[:, :, per] -= box[per] * np.round(diff[:, :, per] / box[per])
    dist2 = np.sum(diff**2, axis=-1)
    reach = (radii[:, None] + radii[None, :]) ** 2
    i, j = np.nonzero(np.triu(dist2 < reach, k=1))
    return set(zip(i.tolist(), j.tolist()))


@pytest.mark.parametrize("d,periodic", [(3, (True, True, False)), (2, (False, True)), (3, (True, True, True))])
def test_contact_list_follows_a_trajectory(d, periodic):
    positions, radii, box = scene(n=400, nu=0.3, d=d, seed=SEED + d)
    origin = np.linspace(-2.0, 5.0, d)
    positions = positions + origin
    rng = np.random.default_rng(SEED)
    cl = hgridlab.ContactList(box, periodic=periodic, origin=origin, skin=0.5, threads=2)
    assert cl.d == d
    walled = ~np.asarray(periodic)
    for step in range(30):
        if step:
            positions = positions + rng.uniform(-0.05, 0.05, positions.shape)
            positions[:, walled] = np.clip(positions[:, walled], origin[walled], (origin + box)[walled])
        cl.update(positions, radii if step == 0 else None)
        got = cl.pairs()
        assert got.dtype == np.uint32 and got.shape[1] == 2
        assert set(map(tuple, got.tolist())) == brute_pairs_per_axis(positions, radii, box, periodic, origin)
        assert [tuple(p) for p in got.tolist()] == sorted(map(tuple, got.tolist()))
    start, partners = cl.neighbours()
    assert start[-1] == len(partners) == len(got)
    s = cl.stats
    assert s["steps"] == 30 and 1 <= s["builds"] < 10 and s["contacts"] == len(got)


def test_contact_list_rejects_bad_input_and_keeps_its_state():
    positions, radii, box = scene(n=100, nu=0.3, d=3)
    cl = hgridlab.ContactList(box, periodic=(True, True, False), skin=0.3)
    cl.update(positions, radii)
    before = cl.pairs()
    bad = positions.copy()
    bad[4, 2] = box[2] + 1.0
    with pytest.raises(ValueError, match="particle 4 left the walled axis 3"):
        cl.update(bad)
    with pytest.raises(ValueError, match="positions"):
        cl.update(positions[:, :2])
    with pytest.raises(ValueError, match="radii"):
        cl.update(positions[:50])
    assert np.array_equal(cl.pairs(), before) and cl.stats["steps"] == 1
    with pytest.raises(ValueError, match="skin"):
        hgridlab.ContactList(box, skin=-1.0)
    cl.set_box(box * 0.99)
    cl.update(positions * 0.99)
    assert set(map(tuple, cl.pairs().tolist())) == brute_pairs_per_axis(
        positions * 0.99, radii, box * 0.99, (True, True, False), np.zeros(3))


def test_contact_list_auto_skin_and_sizes_stay_exact():
    positions, radii, box = scene(n=2000, nu=0.3, d=3, seed=SEED + 5)
    rng = np.random.default_rng(SEED)
    velocity = rng.normal(0.0, 0.01, positions.shape)
    cl = hgridlab.ContactList(box, periodic=(True, True, True), skin="auto", sizes="auto")
    for step in range(120):
        positions = positions + velocity
        cl.update(positions, radii if step == 0 else None)
        if step % 20 == 19:
            assert set(map(tuple, cl.pairs().tolist())) == brute_pairs_per_axis(
                positions, radii, box, (True, True, True), np.zeros(3))
    s = cl.stats
    assert s["predicted_seconds_per_step"] is not None and s["predicted_seconds_per_step"] > 0
    assert s["skin"] > 0 and s["builds"] < 60
    with pytest.raises(ValueError, match="skin"):
        hgridlab.ContactList(box, skin="fast")


def test_contact_list_lees_edwards_offset_grows_every_step():
    positions, radii, box = scene(n=500, nu=0.3, d=2, seed=SEED + 9)
    rng = np.random.default_rng(SEED)
    lx, ly = box
    offset = 0.49 * lx
    cl = hgridlab.ContactList(box, periodic=(True, True), tilt=[offset], skin=0.4)
    for step in range(40):
        if step:
            offset += 0.0005 * lx
            positions = positions + rng.uniform(-0.01, 0.01, positions.shape)
        xy = offset - lx * np.round(offset / lx)  # the Lees-Edwards tilt, |xy| <= lx / 2
        cl.set_box(box, tilt=[xy])
        cl.update(positions, radii)
        h = np.array([[lx, xy], [0.0, ly]])
        d = positions[None, :, :] - positions[:, None, :]
        f = d @ np.linalg.inv(h).T
        d = (f - np.round(f)) @ h.T
        reach = (radii[:, None] + radii[None, :]) ** 2
        i, j = np.nonzero(np.triu(np.sum(d**2, axis=-1) < reach, k=1))
        assert set(map(tuple, cl.pairs().tolist())) == set(zip(i.tolist(), j.tolist()))
    assert cl.stats["builds"] < 40


def test_the_contact_list_example_runs():
    here = os.path.dirname(os.path.abspath(__file__))
    script = os.path.join(here, "..", "..", "examples", "contact_list_steps.py")
    out = subprocess.run([sys.executable, script], check=True, capture_output=True, text=True, env=os.environ.copy())
    assert "list builds" in out.stdout
