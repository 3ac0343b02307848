"""Seed 001 (Liu, Chen, Li, Machines 2024, 12, 34) end to end: a face-milled spiral bevel pair with a predesigned
fourth-order combined motion curve (CMC) by multi-point control of the pinion's blank offset.

Steps (seed 001 §2.2, §4.3, §5; equations as decoded in docs/theory/tca.md, docs/theory/generation.md,
docs/theory/ltca.md):

1. gear: Table 1 blank and Table 4 settings (gear convex side, inner blade);
2. local synthesis of the pinion concave side at the mean contact point M (Table 2: eta = 6 deg, a = 3.7 mm, a
   parabolic TE of 3 arcsec);
3. CMC by Steps 1-4 with an envelope depth of 3 arcsec (Table 3 is inconsistent and not used,
   docs/theory/example.md#table-3);
4. multi-point control: at 11 pinion rotations over one mesh cycle the pinion's instantaneous blank offset E_m1 is
   solved so that the TE equals the CMC (Eq. (17), absolute tolerance 1e-9 rad); E_m1(psi_c1) is interpolated between
   the nodes (natural cubic spline; "linear" as in the paper is available with --interpolation linear, without TCA);
5. TCA of three tooth pairs of the final pair, in the paper's model (straight blades continued to the tip, Eq. (16))
   and with the real edge radii (where the contact of one pair runs onto the gear's top edge before the transfer:
   the edge contact of that edge against the pinion flank).

Run:  python examples/seed001_cmc.py [OUTDIR] [--figures docs/figures] [--interpolation spline]
Writes OUTDIR/seed001_cmc.json (default examples/out/) and the PNG figures (Figures 5-8 of the paper).
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

from spiralbevel.conventions import Member, Side
from spiralbevel.machine import seed001_blank, seed001_settings
from spiralbevel.meshing.motion_curves import ARCSEC
from spiralbevel.meshing.synthesis.cmc_design import design_seed001_style, te_summary
from spiralbevel.meshing.synthesis.multipoint import multipoint_tca

PAPER_MAX_TE = -3.1527          # arcsec, seed 001 §5


def run(interpolation="spline"):
    blank = seed001_blank()
    gear_cutter, gear_settings = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    t0 = time.perf_counter()
    design = design_seed001_style(gear_cutter, gear_settings, blank, eta=math.radians(6.0), semi_major_axis=3.7,
                                  te_magnitude=3.0 * ARCSEC, interpolation=interpolation, straight_blades=True)
    elapsed = time.perf_counter() - t0
    real = None
    if design.tca is not None:
        real = multipoint_tca(design.multipoint, n_positions=61)
    return design, real, elapsed


def summary(design, real, elapsed):
    s = design.summary()
    s["elapsed_s"] = elapsed
    s["paper"] = {"max_transmission_error_arcsec": PAPER_MAX_TE, "predesigned_arcsec": 3.0}
    if real is not None:
        s["tca_real_flanks"] = te_summary(real, design.multipoint)
    return s


def figures(design, real, outdir: Path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    mp, tca = design.multipoint, design.tca
    cmc = mp.cmc
    z1 = design.synthesis.mean.kinematics.z1
    T = 2 * math.pi / z1
    c0 = float(cmc(0.0))
    out = {}

    # Figure 5: predesigned CMC, one pair and three pairs
    x = np.linspace(-1.5 * T, 1.5 * T, 601)
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.2))
    xs = np.linspace(-T / 2, T / 2, 301)
    ax[0].plot(np.degrees(xs), cmc(xs) / ARCSEC, "k")
    ax[0].set_title("(a) CMC, one tooth pair")
    for k in (-1, 0, 1):
        ax[1].plot(np.degrees(x), cmc(x - k * T) / ARCSEC, lw=1)
    ax[1].plot(np.degrees(x), cmc.envelope(x, T) / ARCSEC, "k", lw=2, alpha=0.4)
    ax[1].set_ylim(-6, 0.5)
    ax[1].set_title("(b) three tooth pairs")
    for a in ax:
        a.set_xlabel("pinion rotation phi1 - phi10 (deg)")
        a.set_ylabel("TE (arcsec)")
        a.grid(alpha=0.3)
    out["seed001_cmc.png"] = fig

    # Figure 6: blank offset variation along the path
    fig, ax = plt.subplots(figsize=(5, 3.2))
    psi = np.linspace(mp.psi_c1.min(), mp.psi_c1.max(), 400)
    ax.plot(np.degrees(psi), mp.law.increment(psi) * 1e3, "k", label=f"{mp.law.kind} law")
    ax.plot(np.degrees(mp.psi_c1), mp.offset_increments * 1e3, "o", color="C3", label="control points")
    ax.set_xlabel("cradle angle psi_c1 (deg)")
    ax.set_ylabel("E_m1 - E_m10 (um)")
    ax.set_title(f"Blank offset, pinion concave (E_m10 = {mp.law.base:.4f} mm)")
    ax.legend()
    ax.grid(alpha=0.3)
    out["seed001_blank_offset.png"] = fig

    # Figure 7: TE of three pairs by TCA, with the control points
    fig, ax = plt.subplots(figsize=(6, 3.4))
    xt = np.degrees(tca.phi1 - tca.phi1_mean)
    top = tca.te_max
    for kk, k in enumerate(tca.pairs):
        ax.plot(xt, (tca.te_pairs[:, kk] - top) / ARCSEC, lw=1.2, label=f"pair {k:+d}")
    ax.plot(np.degrees(tca.transfer_phi1 - tca.phi1_mean), (tca.transfer_te - top) / ARCSEC, "kv", ms=5,
            label="transfer (exact)")
    if real is not None:
        xr = np.degrees(real.phi1 - real.phi1_mean)
        ax.plot(xr, (real.te - real.te_max) / ARCSEC, color="0.5", lw=1.0, ls=":", label="real edge radii")
        e = real.edge_contact
        ax.plot(xr[e], (real.te[e] - real.te_max) / ARCSEC, "x", color="0.3", ms=4, label="edge contact (gear top)")
    ax.plot(np.degrees(mp.control_points), (mp.target + c0 - float(np.nanmax(cmc.envelope(tca.phi1, T)))) / ARCSEC
            - (top - np.nanmax(tca.te)) / ARCSEC, "ko", ms=4, label="control points")
    ax.plot(xt, (cmc.envelope(tca.phi1, T) - np.nanmax(cmc.envelope(tca.phi1, T))) / ARCSEC, "k--", lw=0.8,
            label="predesigned CMC")
    lo = (tca.te_min - top) / ARCSEC
    lo_real = (real.te_min - real.te_max) / ARCSEC if real is not None else lo
    ax.set_ylim(min(lo, lo_real, -3.0) - 1.0, 0.5)
    ax.set_xlabel("pinion rotation phi1 - phi10 (deg)")
    ax.set_ylabel("TE (arcsec)")
    ax.set_title(f"TCA: max TE {lo:.4f} arcsec (paper {PAPER_MAX_TE}, design -3)")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(alpha=0.3)
    out["seed001_te.png"] = fig

    # Figure 8: contact pattern on the gear flank, scattered over three segments
    res = tca
    gear = design.synthesis.gear_flank
    ol = gear.outline
    fig, ax = plt.subplots(figsize=(6, 3.4))
    R = np.linspace(ol.Ri, ol.Re, 50)
    ax.plot(np.r_[R, R[::-1], R[0]], np.r_[ol.h_face(R), ol.h_root(R)[::-1], ol.h_face(R[:1])], "k", lw=1)
    rot = design.synthesis.phi2_mean
    c, s = math.cos(rot), math.sin(rot)
    Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    for kk, k in enumerate(res.pairs):
        sel = res.pair == kk
        if not np.any(sel):
            continue
        p = res.point2[sel, kk] @ Rz          # back to the unrotated gear flank
        Rr, h = ol.Rh(p[:, 2], np.hypot(p[:, 0], p[:, 1]))
        ax.plot(Rr, h, "o", ms=3, label=f"driven by pair {k:+d}")
    ax.set_xlabel("cone distance R (mm)")
    ax.set_ylabel("height over pitch line h (mm)")
    ax.set_title("Contact pattern of one gear tooth (rigid TCA, paper model)")
    ax.legend(fontsize=7)
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    out["seed001_contact.png"] = fig
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir", nargs="?", default="examples/out")
    ap.add_argument("--figures", default=None, help="directory for the PNG figures (default: OUTDIR)")
    ap.add_argument("--interpolation", default="spline", choices=["spline", "linear", "polynomial"])
    a = ap.parse_args(argv)
    outdir = Path(a.outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    design, real, elapsed = run(a.interpolation)
    s = summary(design, real, elapsed)
    (outdir / "seed001_cmc.json").write_text(json.dumps(s, indent=1))
    mp = design.multipoint
    d = mp.offset_increments
    print(f"control points: {len(mp.control_points)}, max |TE - CMC| there {np.max(mp.control_point_errors):.3g} rad")
    print(f"blank offset E_m10 = {mp.law.base:.6f} mm, variation {d.min() * 1e3:.4f} .. {d.max() * 1e3:.4f} um")
    if design.tca is not None:
        t = s["tca"]
        print(f"max TE (paper model, straight blades) {t['max_transmission_error_arcsec']:.4f} arcsec; predesigned "
              f"-3, paper {PAPER_MAX_TE}; deviation from the CMC on the controlled range "
              f"{t['controlled_range_deviation_arcsec']:.4f} arcsec")
        tr = s["tca_real_flanks"]
        edges = sorted({f"{m} {e}" for _, _, m, e in real.edges})
        where = np.degrees(real.phi1[real.edge_contact]) if np.any(real.edge_contact) else np.zeros(0)
        print(f"max TE (real edge radii, surface and edge contacts of the real flanks) "
              f"{tr['max_transmission_error_arcsec']:.4f} arcsec; edge contact ({', '.join(edges) or 'none'}) at "
              f"{tr['edge_contact_positions']} of {tr['positions']} positions"
              + (f", pinion rotation {where.min():.2f} to {where.max():.2f} deg" if where.size else "")
              + f"; transfer at {', '.join(f'{t:.3f}' for t in tr['transfer_points_deg'])} deg")
        figdir = Path(a.figures) if a.figures else outdir
        figdir.mkdir(parents=True, exist_ok=True)
        import matplotlib.pyplot as plt

        for name, fig in figures(design, real, figdir).items():
            fig.savefig(figdir / name, dpi=120, bbox_inches="tight")
            plt.close(fig)
    print(f"elapsed {elapsed:.2f} s; summary in {outdir / 'seed001_cmc.json'}")


if __name__ == "__main__":
    main()
