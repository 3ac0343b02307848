"""Benchmark of loaded tooth contact analysis (LTCA) on the seed 001 face-milled pair.

Pair: gear convex flank of seed 001 Table 4 against the pinion concave flank from the local synthesis
(``meshing.synthesis.synthesize_pinion``: eta = 6 deg, a = 3.7 mm, 3 arcsec, seed 001 Table 2) or, when the synthesis
is unavailable, the Table 5 pinion (not synthesized: large TE, edge contact). The unloaded flanks that close the FE
teeth (pinion convex, gear concave) are cut with basic settings (``MachineSettings.from_blank``, 20 deg blades) and
turned to the mean normal thicknesses smn = pi mmn / 2 +- (ham1 - ham2) tan 20 deg (an assumption: seed 001 prints no
thickness).

1. FE tooth compliance of the 3-tooth pinion and gear segments of the main job (15 x 8 flank grids, the default FE
   options ``FE_DEFAULTS``, quadratic tetrahedra), both members, against the plain scikit-fem build a competent user
   writes: ``asm(linear_elasticity, basis)`` with the default quadrature and ``splu`` with default options, the same
   batched solves (median of N runs each); then the finer bench model (3 elements across the tooth, 3 rim layers):
   first build, then the cached read.
2. The torque of the 0.00635 mm approach at the mean contact point (seed 001 §4.3.2) and one loaded mesh cycle
   (21 positions, three pairs) at that torque, against a baseline measured in the same run: the same cycle with the
   primal active-set method alone (no warm-started semismooth iteration).

Run: OPENBLAS_NUM_THREADS=1 python bench/bench_ltca.py [--quick]  (BLAS threads oversubscribe small dense solves).
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import math  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from types import SimpleNamespace  # noqa: E402

import numpy as np  # noqa: E402
from _timing import median_time, report  # noqa: E402

from spiralbevel._core import ltca as _k  # noqa: E402
from spiralbevel.conventions import Member, Side  # noqa: E402
from spiralbevel.generation import generate_flank  # noqa: E402
from spiralbevel.job.facemilled import tooth_rotation  # noqa: E402
from spiralbevel.machine import Blade, HeadCutter, MachineSettings, seed001_blank, seed001_settings  # noqa: E402
from spiralbevel.meshing.generated_surface import phased_for_pair  # noqa: E402
from spiralbevel.meshing.kinematics import BevelPairKinematics  # noqa: E402
from spiralbevel.meshing.ltca.compliance import tooth_compliance  # noqa: E402
from spiralbevel.meshing.ltca.from_tca import FE_DEFAULTS, ltca_model  # noqa: E402
from spiralbevel.meshing.ltca.mesher import grid_normals, mesh_tooth_segment  # noqa: E402
from spiralbevel.meshing.tca import solve_tca  # noqa: E402

ARCSEC = math.pi / 648000


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def seed001_pair():
    """(pinion surface, gear surface, kinematics, TCA, pinion grids, gear grids, label)."""
    b = seed001_blank()
    st = seed001_settings()
    mmn = 2 * b.Rm * math.sin(b.delta1) * math.cos(b.beta_m1) / b.z1
    smn1 = 0.5 * math.pi * mmn + (b.ham1 - b.ham2) * math.tan(math.radians(20.0))
    blank = SimpleNamespace(**vars(b), mmn=mmn, smn1=smn1, smn2=math.pi * mmn - smn1)
    fl = {(Member.GEAR, Side.CONVEX): generate_flank(*st[(Member.GEAR, Side.CONVEX)], b, Member.GEAR, Side.CONVEX)}
    for m, s in ((Member.GEAR, Side.CONCAVE), (Member.PINION, Side.CONVEX)):
        bl = Blade.for_side(s)
        c = HeadCutter(b.rc0 + bl.sign * 2.29 / 2, math.radians(20.0), 2.29, 1.31, bl)
        fl[(m, s)] = generate_flank(c, MachineSettings.from_blank(b, m, s, c), b, m, s)
    kin = BevelPairKinematics(b.Sigma, b.z1, b.z2)
    try:
        from spiralbevel.meshing.synthesis import synthesize_pinion

        gc, gs = st[(Member.GEAR, Side.CONVEX)]
        syn = synthesize_pinion(gc, gs, b, side=Side.CONCAVE, eta=math.radians(6.0), semi_major_axis=3.7,
                                te_magnitude=3 * ARCSEC)
        fl[(Member.PINION, Side.CONCAVE)] = syn.pinion_flank
        # phased for the pair as the job assembles it (meshing.pair.meshing_pair)
        c1, c2 = phased_for_pair(syn.pinion_flank, fl[(Member.GEAR, Side.CONVEX)])
        tca = solve_tca(c1, c2, kin, n_positions=21, start=np.r_[c1.reference_params, c2.reference_params, 0.0])
        label = "synthesized pinion (eta 6 deg, a 3.7 mm, 3 arcsec)"
    except Exception as err:  # noqa: BLE001 - the synthesis is optional here
        print(f"(synthesis unavailable: {err!r}; Table 5 pinion)")
        fl[(Member.PINION, Side.CONCAVE)] = generate_flank(*st[(Member.PINION, Side.CONCAVE)], b, Member.PINION,
                                                           Side.CONCAVE)
        c1, c2 = phased_for_pair(fl[(Member.PINION, Side.CONCAVE)], fl[(Member.GEAR, Side.CONVEX)])
        tca = solve_tca(c1, c2, kin, n_positions=21, start=np.r_[c1.reference_params, c2.reference_params, 0.0])
        label = "Table 5 pinion (not synthesized)"
    rot = {m: tooth_rotation(blank, {k: SimpleNamespace(flank=v) for k, v in fl.items()}, m)
           for m in (Member.PINION, Member.GEAR)}
    g = {k: f.grid(15, 8, curvature=False).points for k, f in fl.items()}
    # the concave flank is the convex one's tooth turned by rot; the TCA surfaces carry their phasing rotation
    pin = (g[(Member.PINION, Side.CONVEX)] @ _rz(c1.rotation - rot[Member.PINION]).T,
           g[(Member.PINION, Side.CONCAVE)] @ _rz(c1.rotation).T)
    gear = (g[(Member.GEAR, Side.CONVEX)] @ _rz(c2.rotation).T,
            g[(Member.GEAR, Side.CONCAVE)] @ _rz(c2.rotation + rot[Member.GEAR]).T)
    return c1, c2, kin, tca, pin, gear, label


def plain_scikit_fem_compliance(mesh, side):
    """Baseline: scikit-fem's generic assembly and a default splu, then the same 64-column batched solves."""
    import skfem
    from scipy.sparse.linalg import splu
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    m = skfem.MeshTet(mesh.vertices.T.copy(), mesh.tets.T.copy())
    basis = skfem.Basis(m, skfem.ElementVector(skfem.ElementTetP2()))
    K = skfem.asm(linear_elasticity(*lame_parameters(206000.0, 0.3)), basis)
    facets = np.flatnonzero(np.all(mesh.fixed[m.facets], axis=0))
    clamped = np.union1d(basis.get_dofs(facets=facets).all(), basis.nodal_dofs[:, mesh.fixed].ravel())
    free = np.setdiff1d(np.arange(basis.N), clamped)
    pos = np.full(basis.N, -1)
    pos[free] = np.arange(len(free))
    nodes = np.concatenate([mesh.flank_nodes[(k, side)].ravel() for k in mesh.teeth])
    nrm = np.concatenate([grid_normals(mesh.vertices[mesh.flank_nodes[(k, side)]]).reshape(-1, 3)
                          for k in mesh.teeth])
    rows = pos[basis.nodal_dofs[:, nodes]]
    live = rows >= 0
    nrm, rows = np.where(live.T, nrm, 0.0), np.where(live, rows, 0)
    lu = splu(K[free][:, free].tocsc())
    G = np.empty((len(nodes), len(nodes)))
    for start in range(0, len(nodes), 64):
        sl = slice(start, min(len(nodes), start + 64))
        B = np.zeros((len(free), sl.stop - sl.start))
        for c in range(3):
            B[rows[c, sl], np.arange(sl.stop - sl.start)] += nrm[sl, c]
        U = lu.solve(B)
        G[:, sl] = sum(nrm[:, c, None] * U[rows[c]] for c in range(3))
    return 0.5 * (G + G.T)


def fe_build(pin, gear, repeat):
    """Both members' FE compliance with the job's default FE options, package against plain scikit-fem."""
    opts = {k: v for k, v in FE_DEFAULTS.items() if k != "order"}
    meshes = [(mesh_tooth_segment(*pin, 23, **opts), "concave"), (mesh_tooth_segment(*gear, 65, **opts), "convex")]
    # CPU time (single-threaded: one BLAS thread), which other jobs on a shared machine do not stretch as they do
    # the wall clock
    t_pkg, tcs = median_time(lambda: [tooth_compliance(m, s, use_cache=False) for m, s in meshes], repeat, cpu=True)
    t_base, Gs = median_time(lambda: [plain_scikit_fem_compliance(m, s) for m, s in meshes], repeat, cpu=True)
    dG = max(np.max(np.abs(tc.G - G)) / np.max(np.abs(G)) for tc, G in zip(tcs, Gs))
    n = sum(tc.G.shape[0] for tc in tcs)
    report(f"FE compliance, pinion + gear, job defaults (P2, {n} load nodes), CPU time", t_pkg, t_base,
           "plain scikit-fem asm + default splu", repeat)
    print(f"    target <= 8 s; same flexibility: max |dG| / max |G| = {dG:.1e} (target <= 1e-12); machine load "
          f"{os.getloadavg()[0]:.1f}")


def main():
    import sys

    c1, c2, kin, tca, pin, gear, label = seed001_pair()
    fe_build(pin, gear, 1 if "--quick" in sys.argv else 3)
    te = tca.te_arcsec
    print(f"seed 001, {label}: unloaded TCA {tca.summary()}")
    fe = dict(thickness_divisions=3, space_divisions=2, rim_layers=3)
    with tempfile.TemporaryDirectory() as cache:
        t0 = time.perf_counter()
        model = ltca_model(c1, c2, kin, tca, pinion_grids=pin, gear_grids=gear, fe_options=fe, cache_dir=cache)
        t1 = time.perf_counter()
        ltca_model(c1, c2, kin, tca, pinion_grids=pin, gear_grids=gear, fe_options=fe, cache_dir=cache)
        t2 = time.perf_counter()
    nl = model.pinion_compliance.G.shape[0] + model.gear_compliance.G.shape[0]
    print(f"FE compliance, pinion + gear 3-tooth segments (P2, {nl} load nodes) + contact positions: build "
          f"{t1 - t0:.1f} s (target <= 120 s), cached {t2 - t1:.2f} s")
    t0 = time.perf_counter()
    T = model.approach_torque()
    t1 = time.perf_counter()
    print(f"torque for the 0.00635 mm approach at the mean contact point: {T:.0f} N mm ({t1 - t0:.2f} s)")
    model.run(T, approach_target=None)  # warm-up
    t0 = time.process_time()
    res = model.run(T, approach_target=None)
    t1 = time.process_time()
    orig = _k.pdas
    _k.pdas = lambda C, w, h, T, active, **_: (np.zeros(len(w)), None, None, active, 0, False)
    try:
        t2 = time.process_time()
        base = model.run(T, approach_target=None)
        t3 = time.process_time()
    finally:
        _k.pdas = orig
    assert np.allclose(res.te_loaded, base.te_loaded, atol=1e-9)
    n = sum(len(f) for f in res.force) / len(res.force)
    print(f"loaded mesh cycle: 21 positions x 3 pairs (~{n:.0f} potential points per position): {t1 - t0:.3f} s CPU "
          f"(target <= 0.2 s); primal-active-set baseline {t3 - t2:.3f} s; ratio {(t3 - t2) / (t1 - t0):.1f}x")
    fin = np.isfinite(te)
    print(f"  unloaded TE (TCA) {np.min(te[fin]):.2f} .. {np.max(te[fin]):.2f} arcsec; loaded TE "
          f"{res.te_loaded.min():.2f} .. {res.te_loaded.max():.2f} arcsec (paper: -3.15 unloaded, -22.08 loaded, "
          f"CMC-designed pinion); peak pressure {res.peak_pressure:.0f} N/mm^2")
    shared = np.sum(np.sum(res.load_share > 1e-3, axis=1) > 1)
    print(f"  positions with two pairs loaded: {shared} of {len(res.te_loaded)}; load share of each pair:")
    for name, row in zip(res.pair_names, res.load_share.T):
        print(f"    {name}: " + " ".join(f"{v:.2f}" for v in row))


if __name__ == "__main__":
    main()
