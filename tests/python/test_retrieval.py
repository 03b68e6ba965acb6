# SPDX-License-Identifier: GPL-3.0-or-later
# describe(), morphex.Index (add, query, evaluate) and run_pipeline().
from fractions import Fraction

import numpy as np
import pytest

import morphex
from conftest import FAST_DESCRIBE, fast_pipeline, write_family_folder


def test_describe_mirrors_the_command_line(unit_cube):
    box = morphex.box((0, 0, 0), (1, 2, 3))
    d = morphex.describe(box, **FAST_DESCRIBE)
    for key in ("open_radii", "close_radii", "granulometry", "anti_granulometry", "components"):
        assert isinstance(d[key], np.ndarray) and d[key].shape == (2,)
    assert d["pattern_spectrum"].shape == (2,) and d["d2"].shape == (16,)
    assert d["opening_residue"].shape == (12,)  # 6 per scale
    assert np.all(d["granulometry"] <= 1) and np.all(np.diff(d["granulometry"]) <= 0)
    assert abs(d["d2"].sum() - 1) < 1e-9
    assert d["scale_length"] == pytest.approx(6 ** (1 / 3))
    assert sorted(d["vectors"]) == sorted(morphex.descriptor_kinds())
    # similar copies (moved, scaled by 3/2) have the same descriptor, up to rounding
    moved = morphex.box((0, 0, 0), (Fraction(3, 2), 3, Fraction(9, 2))).translated(("1/3", 2, 0))
    e = morphex.describe(moved, **FAST_DESCRIBE)
    for kind in ("morphology", "granulometry"):
        assert np.allclose(d["vectors"][kind], e["vectors"][kind], atol=1e-6)
    with pytest.raises(ValueError, match="open_from/close_from must not exceed"):
        morphex.describe(box, open_from=0.7, open_to=0.6)


def test_describe_keywords_are_the_settings_table():
    box = morphex.box((0, 0, 0), (1, 2, 3))
    # a bad value of a setting is refused by the library, naming the setting
    for name, value in (("scales", 0), ("open_to", -1), ("d2_bins", 2), ("seed", -1),
                        ("pose", "yes")):
        with pytest.raises(morphex.InputError, match=f"^{name}: expected"):
            morphex.describe(box, **{name: value})
    with pytest.raises(TypeError, match="scale"):
        morphex.describe(box, scale=2)
    assert "d2_bins=64" in morphex.describe.__doc__


def test_check_report_as_a_dict_is_the_library_json(unit_cube):
    d = unit_cube.check().to_dict()
    assert d["valid"] and d["closed"] and d["genus"] == 0
    assert d["volume_exact"] == "1" and d["volume"] == 1.0 and d["faces"] == 12
    assert d["bbox"] == {"min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 1.0]}


def test_describe_refuses_or_repairs_invalid_solids(data_dir):
    crossing = morphex.Mesh.read(data_dir / "crossing_cubes.off")
    with pytest.raises(morphex.InvalidSolid, match="crossing_cubes.off"):
        morphex.describe(crossing, **FAST_DESCRIBE)
    d = morphex.describe(crossing, repair=True, **FAST_DESCRIBE)
    assert d["repair"]["changed"] and d["path"].endswith("crossing_cubes.off")


def test_index_add_query_evaluate(tmp_path):
    labels = write_family_folder(tmp_path / "meshes")
    paths = sorted(str(p) for p in (tmp_path / "meshes").glob("*.off"))
    with morphex.Index(tmp_path / "index.sqlite") as index:
        summary = index.add(paths, pipeline=fast_pipeline(), threads=2)
        assert summary == {"indexed": 6, "skipped": 0, "skipped_failed": 0, "failed": 0,
                           "errors": {}}
        assert len(index) == 6 and "bar-1" in index and sorted(index.names()) == sorted(labels)
        # the scaled, moved copy is the nearest neighbour, at distance ~0; the query itself is
        # left out when given by name
        hits = index.query("bar-1", k=3)
        assert len(hits) == 3 and hits[0][0] == "bar-2" and hits[0][1] < 1e-6
        assert [d for _, d in hits] == sorted(d for _, d in hits)
        assert all(name != "bar-1" for name, _ in hits)
        # a Mesh is described with the index's own pipeline: it finds itself and its copy
        plate = morphex.Mesh.read(tmp_path / "meshes" / "plate-1.off")
        hits = index.query(plate, k=2, descriptor="granulometry", metric="l2")
        assert {name for name, _ in hits} == {"plate-1", "plate-2"}
        assert all(d < 1e-6 for _, d in hits)
        stored = index.descriptors("plate-1")
        assert sorted(stored) == sorted(morphex.descriptor_kinds())
        # every class has a copy at distance ~0: perfect retrieval on every morphological kind
        scores = index.evaluate(labels)
        assert scores["morphology"]["nearest_neighbor"] == 1.0
        assert scores["morphology"]["first_tier"] == 1.0 and scores["morphology"]["queries"] == 6
        assert set(scores) == set(morphex.descriptor_kinds())
        # a second run skips what is up to date; an in-memory mesh and a bad file are recorded
        again = index.add(paths, pipeline=fast_pipeline())
        assert again["skipped"] == 6 and again["indexed"] == 0
        bad = tmp_path / "broken.off"
        bad.write_text("OFF\n1 0 0\n")
        result = index.add(bad, pipeline=fast_pipeline())
        assert result["failed"] == 1 and str(bad) in result["errors"]
        assert str(bad) in index.failed() and len(index) == 6
        # the failure is kept and skipped until retry_failed
        assert index.add(bad, pipeline=fast_pipeline())["skipped_failed"] == 1
        assert index.add(bad, pipeline=fast_pipeline(), retry_failed=True)["failed"] == 1
        entries = {e["name"]: e for e in index.entries()}
        assert entries["broken"]["status"] == "failed" and entries["broken"]["error"]
        assert entries["bar-1"]["path"] == str((tmp_path / "meshes" / "bar-1.off").resolve())
        assert entries["bar-1"]["faces"] > 0 and not entries["bar-1"]["repaired"]
        # remove: an unknown key removes nothing; a name and a path remove their entries
        with pytest.raises(ValueError, match="nosuch: no indexed mesh"):
            index.remove(["broken", "nosuch"])
        assert index.remove(["broken", str(bad)]) == 1 and not index.failed()
        extra = morphex.box((0, 0, 0), (1, 1, 5))
        assert index.add(extra, name="long-bar", pipeline=fast_pipeline())["indexed"] == 1
        assert index.query("long-bar", k=1)[0][0] in ("bar-1", "bar-2")
        with pytest.raises(ValueError, match="descriptor: expected one of"):
            index.query("bar-1", descriptor="shape")
        with pytest.raises(ValueError, match="needs a describe stage"):
            index.add(paths, pipeline={"pipeline": [{"type": "read", "path": "${input}"}]})


def test_run_pipeline(tmp_path, data_dir):
    document = {"pipeline": [
        {"type": "read", "path": "${input}"},
        {"type": "dilate", "se": {"shape": "cube", "r": "1/4"}},
        {"type": "write", "path": "${out}/${stem}-dilated.off", "exact": True}]}
    report = morphex.run_pipeline(document, [data_dir / "unit_cube.off"], {"out": str(tmp_path)})
    assert report["ok"] and len(report["inputs"]) == 1
    assert report["inputs"][0]["stages"][1]["volume"] == "27/8"
    written = morphex.Mesh.read(tmp_path / "unit_cube-dilated.off")
    assert written.volume() == Fraction(27, 8)
    # an input that fails is reported, not raised
    report = morphex.run_pipeline(document, [data_dir / "open_cube.off"], {"out": str(tmp_path)})
    assert not report["ok"] and "not closed" in report["inputs"][0]["error"]
    # an invalid pipeline raises ValueError listing every problem with its location
    document["pipeline"][1]["se"]["r"] = -1
    document["pipeline"].append({"type": "dilation"})
    with pytest.raises(ValueError) as info:
        morphex.run_pipeline(document, [data_dir / "unit_cube.off"], {"out": str(tmp_path)})
    message = str(info.value)
    assert "pipeline[1].se.r" in message and "did you mean 'dilate'" in message


def test_index_add_names_a_list_of_meshes(tmp_path):
    # in-memory meshes have no file to be named after: names= (or name= as a list) names them
    meshes = [morphex.box((0, 0, 0), (1, 1, k)) for k in (1, 2, 3)]
    with morphex.Index(tmp_path / "named.sqlite") as index:
        summary = index.add(meshes[:2], names=["short", "tall"], pipeline=fast_pipeline())
        assert summary["indexed"] == 2 and summary["failed"] == 0
        assert index.add(meshes[2:], name=["tallest"], pipeline=fast_pipeline())["indexed"] == 1
        assert index.add(meshes[0], name="again", pipeline=fast_pipeline())["indexed"] == 1
        assert sorted(index.names()) == ["again", "short", "tall", "tallest"]
        assert {e["path"] for e in index.entries()} == {
            "mesh:short", "mesh:tall", "mesh:tallest", "mesh:again"}
        with pytest.raises(ValueError, match="one name per mesh, got 1 names for 2 meshes"):
            index.add(meshes[:2], names=["one"])
        with pytest.raises(ValueError, match="not both"):
            index.add(meshes[:1], name="a", names=["a"])
        with pytest.raises(ValueError, match="needs a name"):
            index.add(meshes[:2])


def test_index_refuses_files_that_are_not_indexes(tmp_path):
    import sqlite3
    foreign = tmp_path / "foreign.sqlite"
    with sqlite3.connect(foreign) as db:
        db.execute("CREATE TABLE meshes(id INTEGER PRIMARY KEY, name TEXT)")
    before = foreign.read_bytes()
    with pytest.raises(ValueError, match="not a morphex index"):
        morphex.Index(foreign)
    assert foreign.read_bytes() == before
    text = tmp_path / "text.sqlite"
    text.write_text("not a database, just text long enough to be read as a header " * 4)
    with pytest.raises(ValueError, match="not a morphex index"):
        morphex.Index(text)


def test_run_pipeline_refuses_deep_nesting(tmp_path, data_dir):
    # issue 44: 20,000 nested brackets (40 KB) crashed the process with SIGSEGV
    deep = tmp_path / "deep.json"
    deep.write_text('{"pipeline": [{"type": "read", "path": ' + "[" * 20000 + "]" * 20000 + "}]}")
    for document in (deep, deep.read_text()):
        with pytest.raises(ValueError, match="nested deeper than 64 levels"):
            morphex.run_pipeline(document, [data_dir / "unit_cube.off"])
