# SPDX-License-Identifier: GPL-3.0-or-later
# The data of the plots (evaluate_retrieval, Index.evaluate's curves and classes, describe's
# curves) and the SVG that plot_svg writes, read back with an XML parser.
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import morphex
from conftest import fast_pipeline, write_family_folder

SVG = "{http://www.w3.org/2000/svg}"


def parse(svg):
    root = ET.fromstring(svg.encode("utf-8"))
    assert root.tag == SVG + "svg"
    assert root.get("viewBox") == "0 0 %s %s" % (root.get("width"), root.get("height"))
    return root


def texts(root):
    return ["".join(t.itertext()) for t in root.iter(SVG + "text")]


def paths(root, kind):
    return [p for p in root.iter(SVG + "path") if p.get("class") == kind]


def test_evaluate_retrieval_of_a_hand_checked_example():
    # rankings: a1: b1 a2 b2   a2: b1 a1 b2   b1: a2 a1 b2   b2: b1 a1 a2
    names, classes = ["a1", "a2", "b1", "b2"], ["A", "A", "B", "B"]
    d = [[0, 1, 0.7, 3], [1, 0, 0.5, 4], [0.7, 0.5, 0, 1], [3, 4, 1, 0]]
    r = morphex.evaluate_retrieval(names, classes, d)
    assert r["queries"] == 4 and r["nearest_neighbor"] == 0.25 and r["second_tier"] == 0.75
    # one class mate each: its rank n gives precision 1/n at every recall level
    pr = r["precision_recall"]
    assert np.allclose(pr["recall"], np.linspace(0, 1, 21))
    assert np.allclose(pr["precision"], (1 / 2 + 1 / 2 + 1 / 3 + 1) / 4)
    assert r["per_class"]["A"] == pytest.approx({
        "nearest_neighbor": 0, "first_tier": 0, "second_tier": 1, "e_measure": 0.5, "dcg": 1,
        "queries": 2, "models": 2})
    assert r["per_class"]["B"]["nearest_neighbor"] == 0.5
    with pytest.raises(ValueError, match="n x n distance matrix"):
        morphex.evaluate_retrieval(names, classes, d[:3])


def test_index_evaluate_has_curves_and_classes(tmp_path):
    labels = write_family_folder(tmp_path / "meshes")
    paths_ = sorted(str(p) for p in (tmp_path / "meshes").glob("*.off"))
    with morphex.Index(tmp_path / "index.sqlite") as index:
        index.add(paths_, pipeline=fast_pipeline())
        scores = index.evaluate(labels)
    m = scores["morphology"]
    # each class has a copy at distance ~0: precision 1 at every recall, every class perfect
    assert np.allclose(m["precision_recall"]["precision"], 1)
    assert set(m["per_class"]) == {"bar", "plate", "block"}
    assert all(c["models"] == 2 and c["first_tier"] == 1 for c in m["per_class"].values())
    chart = morphex.precision_recall_chart(scores, title="families <&>")
    assert [s["name"] for s in chart["series"]] == list(scores)
    root = parse(morphex.plot_svg(chart))
    assert len(paths(root, "line")) == len(scores)  # one line per descriptor kind
    shown = texts(root)
    assert "families <&>" in shown  # escaped in the file, the same text once parsed
    for kind in scores:
        assert kind in shown


def test_exact_cube_granulometry_and_its_figure(tmp_path):
    # The unit cube (half side 1/2, L = 1, thickness 1/2) opened by cubes of half side r keeps
    # everything while r < 1/2 and nothing after; convex, no closing adds anything.
    d = morphex.describe(morphex.box((0, 0, 0), (1, 1, 1)), scales=6, open_from=0.1,
                         open_to=1.6, d2_samples=2000, d2_bins=16)
    r = d["open_radii"]
    assert np.all(np.abs(r - 0.5) > 1e-3) and (r < 0.5).any() and (r > 0.5).any()
    assert np.allclose(d["granulometry"], np.where(r < 0.5, 1.0, 0.0), atol=1e-12)
    assert np.allclose(d["pattern_spectrum"], -np.diff(np.concatenate(([1.0], d["granulometry"]))))
    assert np.allclose(d["anti_granulometry"], 0, atol=1e-12)
    figure = morphex.descriptor_figure(d, "unit cube")
    charts = figure["charts"]
    assert [c["title"].split(":")[0] for c in charts] == [
        "Granulometry", "Anti-granulometry", "Pattern spectrum", "D2"]
    assert np.array_equal(charts[0]["series"][0]["x"], d["open_radii"])
    assert np.array_equal(charts[0]["series"][0]["y"], d["granulometry"])
    spectrum = charts[2]["series"][0]
    assert spectrum["bars"] and np.array_equal(spectrum["x"][1:], d["open_radii"])
    assert spectrum["x"][0] == 0
    out = tmp_path / "cube.svg"
    svg = morphex.plot_svg(figure, out)
    assert out.read_text(encoding="utf-8") == svg
    root = parse(svg)
    assert len([g for g in root.iter(SVG + "g") if g.get("class") == "chart"]) == 4
    assert len(paths(root, "line")) == 2 and len(paths(root, "bars")) == 2
    assert root.get("width") == "1280" and "unit cube: L = cbrt(volume) = 1" in texts(root)[0]


def test_plot_svg_of_own_charts():
    charts = [{"title": "a <b> & c", "x_label": "x", "y_label": "y",
               "series": [{"name": "up & <down>", "x": [0, 1, 2], "y": [1, 3, 2]},
                          {"name": "caf\u00e9", "x": [0, 1, 2], "y": [2, float("nan"), 1]}]},
              {"title": "bars", "series": [{"name": "h", "x": [0, 1, 2], "y": [4, 5],
                                            "bars": True}], "y_min": 0, "y_max": 10}]
    svg = morphex.plot_svg(charts, title="two panels", columns=1)
    assert "up &amp; &lt;down&gt;" in svg and "<down>" not in svg
    root = parse(svg)
    assert root.get("width") == "640" and root.get("height") == str(36 + 2 * 420)
    shown = texts(root)
    assert "up & <down>" in shown and "caf\u00e9" in shown and "a <b> & c" in shown
    assert len(paths(root, "line")) == 2 and len(paths(root, "markers")) == 2
    assert paths(root, "line")[1].get("d").count("M") == 2  # the NaN leaves a gap
    assert "10" in shown  # the fixed y range's end is a tick
    assert svg == morphex.plot_svg(charts, title="two panels", columns=1)
    with pytest.raises(ValueError, match="series 'h': 2 x values for 2 y values"):
        morphex.plot_svg({"series": [{"name": "h", "x": [0, 1], "y": [1, 2], "bars": True}]})
    with pytest.raises(ValueError, match="expected x and y"):
        morphex.plot_svg([{"series": [{"name": "s"}]}])
