"""GearSet against the main job: a GearSet built from each bundled design and from basic data runs every method, and
each result's ``to_dict()`` equals the matching section of the job's report.json (the job and the API give the same
numbers).

The comparison is of JSON values. Both sides run the same functions on the same flanks, so they agree to the last
bit; the tolerance (relative 1e-12) only allows a different summation order of the same sums.
"""

import json
import math
import warnings

import pytest

import spiralbevel as sb
from spiralbevel.errors import DesignError
from spiralbevel.io.design_file import bundled_designs, load_design

DESIGNS = sorted(bundled_designs())


def _fast(spec, **output):
    """The design with the small grids and outputs of a test: 9 x 5 flank grids, 11 TCA positions, 5 LTCA
    positions, no plots or CAD (the numbers compared do not depend on the files), no crowning."""
    out = {**dict(plots=False, stl=False, step=False, toolpaths=False, draft=False, grid=(9, 5)), **output}
    # no [crowning]: the mismatch study of a log-spiral pair has no GearSet method, and it is the slow part
    upd = {"output": spec.output.model_copy(update=out), "tca": spec.tca.model_copy(update={"positions": 11}),
           "crowning": None}
    if spec.ltca is not None:
        upd["ltca"] = spec.ltca.model_copy(update={"positions": 5})
    return spec.model_copy(update=upd)


def same(a, b, path="report"):
    """Assert two JSON values equal (floats to a relative 1e-12), naming the first key that differs."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and set(a) == set(b), f"{path}: keys {sorted(a)} != {sorted(b)}"
        for k in a:
            same(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), f"{path}: lengths differ"
        for i, (x, y) in enumerate(zip(a, b)):
            same(x, y, f"{path}[{i}]")
    elif isinstance(a, float) and isinstance(b, (int, float)):
        assert math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-300), f"{path}: {a!r} != {b!r}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


def _run(gs, out):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        gs.report(out)
    return json.loads((out / "report.json").read_text())


@pytest.fixture(scope="module", params=DESIGNS)
def job(request, tmp_path_factory):
    """(GearSet, the report.json its report() wrote, the directory) of a bundled design: the same code path as
    ``spiralbevel run``."""
    # the plain log-spiral pair also writes its STL files, forging draft and tool paths (a few seconds): to_stl is
    # checked against them and the draft and tool-path sections against the schema
    ls = request.param == "aviation_23x65_logspiral"
    spec = _fast(load_design(bundled_designs()[request.param]), stl=ls, draft=ls, toolpaths=ls)
    gs = sb.GearSet.from_dict(spec.model_dump(mode="json"))
    out = tmp_path_factory.mktemp(request.param) / "out"
    return gs, _run(gs, out), out


def _check_facemilled(gs, report, out):
    same(gs.machine_summary().to_dict(), {"flanks": report["flanks"], "machine_settings": report["machine_settings"]})
    for side in ("drive", "coast"):
        same(gs.tca(side).to_dict(), report["tca"][side], f"tca.{side}")
    if gs.is_hypoid:
        same(gs.easeoff().to_dict(), report["easeoff"], "easeoff")
        same(gs.sensitivity().to_dict(), report["tca"]["misalignment_sensitivity"], "tca.misalignment_sensitivity")
        # the FE loaded TCA with the offset kinematics (gearset/hypoid_ltca.py), as the job's [ltca] section
        assert "ltca" not in {e["section"] for e in report["hypoid"]["not_available"]}
        if gs.design.ltca is not None:
            same(gs.ltca(torque=gs.design.ltca.torque).to_dict(), report["ltca"], "ltca")
        # the ISO 10300 rating has a hypoid branch: the bundled hypoid carries a [rating] section
        assert gs.design.rating is not None
        same(gs.rate().to_dict(), report["rating"], "rating")
        _check_measurement(gs, report, out)
        return
    same(gs.sensitivity().to_dict(), report["tca"]["misalignment_sensitivity"], "tca.misalignment_sensitivity")
    same(gs.easeoff().to_dict(), report["easeoff"], "easeoff")
    _check_measurement(gs, report, out)
    if gs.design.ltca is not None:
        same(gs.ltca(torque=gs.design.ltca.torque).to_dict(), report["ltca"], "ltca")
    if gs.design.rating is not None:
        same(gs.rate().to_dict(), _without(report["rating"], ("ltca_comparison", "fe_root_stress")), "rating")


def _check_measurement(gs, report, out):
    """The CMM grids of GearSet.measurement_grid() are the files the job wrote (hypoid members in their own views of
    the blank as well)."""
    from spiralbevel.io.measurement_csv import measurement_grid_csv

    grids = gs.measurement_grid()
    assert len(grids.grids) == 4
    for (m, s), g in grids.grids.items():
        name = report["measurement"][f"{m.value}_{s.value}"]
        assert (out / name).read_text() == measurement_grid_csv(g)


def _without(d, keys):
    return {k: v for k, v in d.items() if k not in keys}


def _check_logspiral(gs, report, out):
    for side, sec in report["logspiral"]["tca"].items():
        same(gs.tca(side).to_dict(), sec, f"logspiral.tca.{side}")
    if gs.design.output.stl:
        for path in gs.to_stl(out.parent / "api"):
            assert path.read_bytes() == (out / path.name).read_bytes(), path.name
        pytest.importorskip("OCP")   # STEP needs the 'cad' extra
        from spiralbevel.conventions import Member
        from spiralbevel.io.step import read_step_surfaces

        paths = gs.to_step(out.parent / "api", whole_gear=False)
        assert sorted(p.name for p in paths) == ["gear_tooth.step", "pinion_tooth.step"]
        tooth, _, _ = gs._tooth_grids()
        for member in (Member.PINION, Member.GEAR):
            (convex, _), (concave, _) = tooth[member]
            faces = read_step_surfaces(out.parent / "api" / f"{member.value}_tooth.step")
            # the flank faces interpolate the flank grid (as the job writes them): at the nodes within 1e-4 mm, the
            # bound of the STEP tests
            assert max(faces[0].distance(convex.reshape(-1, 3)).max(),
                       faces[1].distance(concave.reshape(-1, 3)).max()) < 1e-4
    for method in ("machine_summary", "sensitivity", "easeoff", "measurement_grid", "ltca"):
        with pytest.raises(DesignError, match="needs a face-milled design"):
            getattr(gs, method)()


def test_gearset_matches_the_job(job):
    gs, report, out = job
    assert report["design"]["title"] == gs.title
    if gs.kind == "face-milled":
        _check_facemilled(gs, report, out)
    else:
        _check_logspiral(gs, report, out)


def test_gearset_from_basic_data_matches_the_job(tmp_path):
    # the aviation set of Liu, Chen and Li (2024), Table 1, given in Python; face-milled flanks with the default
    # cutters, basic settings and the developed pinion (default synthesis of both sides)
    gs = sb.GearSet.from_basic_data(pinion_teeth=23, gear_teeth=65, module=3.9, face_width=37.0,
                                    mean_spiral_angle=30.0, normal_pressure_angle=20.0, pinion_hand="RH",
                                    title="23/65 from basic data")
    assert gs.kind == "face-milled" and gs.blank.z2 == 65
    gs = sb.GearSet(_fast(gs.design))
    out = tmp_path / "out"
    report = _run(gs, out)
    assert report["design"]["title"] == "23/65 from basic data"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _check_facemilled(gs, report, out)
    with pytest.raises(DesignError, match=r"rating.*\[rating\] section"):
        gs.rate()


def test_bad_basic_data_names_the_key():
    with pytest.raises(DesignError, match="gear_set.face_width"):
        sb.GearSet.from_basic_data(pinion_teeth=23, gear_teeth=65, module=3.9, face_width=-1.0,
                                   mean_spiral_angle=30.0)
    with pytest.raises(DesignError, match="side"):
        sb.GearSet.from_design("aviation_23x65_facemilled").tca("sideways")


def test_report_matches_the_schema(job):
    jsonschema = pytest.importorskip("jsonschema")
    from spiralbevel.io.report import report_schema

    schema = report_schema()
    jsonschema.Draft202012Validator.check_schema(schema)
    jsonschema.validate(job[1], schema, cls=jsonschema.Draft202012Validator)


def test_schema_rejects_the_old_conventions(job):
    jsonschema = pytest.importorskip("jsonschema")
    from spiralbevel.io.report import report_schema

    v = jsonschema.Draft202012Validator(report_schema())
    report = job[1]
    for path, key, value in ((("blank",), "units", {"delta1": "deg"}), ((), "blank_warnings", []),
                             ((), "title", "duplicate of design.title"), (("blank", "pinion"), "delta1_rad", 0.3)):
        bad = json.loads(json.dumps(report))
        node = bad
        for p in path:
            node = node[p]
        node[key] = value
        assert not v.is_valid(bad), key
