# SPDX-License-Identifier: GPL-3.0-or-later
# morphex.Mesh: numpy and exact coordinates, files, checks and errors.
import pickle
from fractions import Fraction

import numpy as np
import pytest

import morphex

CUBE_VERTICES = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0],
                          [0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]], dtype=np.float64)
CUBE_FACES = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                       [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])


def test_numpy_round_trip():
    mesh = morphex.Mesh(CUBE_VERTICES * 0.5, CUBE_FACES)
    assert len(mesh) == mesh.num_faces == 12 and mesh.num_vertices == 8
    assert mesh.vertices.dtype == np.float64 and mesh.vertices.shape == (8, 3)
    assert np.array_equal(mesh.vertices, CUBE_VERTICES * 0.5)
    assert np.array_equal(mesh.faces, CUBE_FACES)
    assert mesh.volume() == Fraction(1, 8)
    report = mesh.check()
    assert report.valid and bool(report) and report.problems == ""
    assert report.volume == Fraction(1, 8) and report.faces == 12 and report.genus == 0
    assert report.bbox == ((0, 0, 0), (0.5, 0.5, 0.5))


def test_doubles_are_taken_exactly():
    mesh = morphex.Mesh(CUBE_VERTICES * 0.1, CUBE_FACES)
    x = Fraction(mesh.exact_vertices()[7][0])
    assert x == Fraction(0.1) and x != Fraction(1, 10)  # the double nearest 0.1, exactly
    assert mesh.volume() == Fraction(0.1) ** 3


def test_exact_coordinates_and_rounding(unit_cube):
    moved = unit_cube.translated(("1/3", 0, "-2/7"))
    exact = moved.exact_vertices()
    assert all(isinstance(c, str) for p in exact for c in p)
    xs = {Fraction(p[0]) for p in exact}
    assert xs == {Fraction(1, 3), Fraction(4, 3)}
    # numpy coordinates are the nearest doubles of the exact ones
    for p, q in zip(exact, moved.vertices):
        assert tuple(q) == tuple(float(Fraction(c)) for c in p)
    assert moved.volume() == 1
    again = morphex.Mesh.from_exact([tuple(map(Fraction, p)) for p in exact], moved.faces)
    assert again.exact_vertices() == exact


def test_files_exact_and_plain(tmp_path, unit_cube):
    third = unit_cube.translated(("1/3", "1/3", "1/3"))
    exact_path = tmp_path / "third.off"
    third.write(exact_path, exact=True)
    back = morphex.Mesh.read(exact_path)
    assert back.exact_vertices() == third.exact_vertices()
    assert back.source == str(exact_path)
    plain = tmp_path / "third.obj"
    third.write(str(plain))
    rounded = morphex.Mesh.read(plain)
    # a plain format holds doubles (read back exactly: dyadic rationals) within an ulp of the
    # exact thirds, so the volume is near 1 but not 1
    def points(mesh):  # sorted: a reader may number vertices in its own order
        return sorted({tuple(map(Fraction, p)) for p in mesh.exact_vertices()})

    assert len(points(rounded)) == 8
    for p, q in zip(points(third), points(rounded)):
        for exact, read in zip(p, q):
            assert read.denominator & (read.denominator - 1) == 0
            assert abs(read - exact) <= exact * Fraction(1, 2 ** 52)
    assert rounded.volume() != 1 and abs(rounded.volume() - 1) < Fraction(1, 10 ** 14)
    assert rounded.check().valid


def test_rounded_stays_a_valid_solid(tmp_path, unit_cube):
    # Two unit cubes 1e-10 apart: in doubles the gap stays, in floats their walls coincide and
    # rounding vertex by vertex would make the faces overlap; rounded() resolves them into one box.
    right = unit_cube.translated(("10000000001/10000000000", 0, 0))
    both = morphex.Mesh.from_exact(unit_cube.exact_vertices() + right.exact_vertices(),
                                   np.vstack([unit_cube.faces, right.faces + 8]))
    assert both.check().valid
    floats = both.rounded("float")
    assert floats.check().valid and floats.volume() == 2
    assert np.array_equal(floats.vertices, floats.vertices.astype(np.float32))
    doubles = both.rounded()
    assert doubles.check().valid and doubles.volume() == both.volume()
    with pytest.raises(ValueError, match="precision"):
        both.rounded("half")
    report = both.write(tmp_path / "both.stl")
    assert report["rounds"] >= 1 and report["moved_vertices"] > 0
    assert abs(report["relative_volume_change"]) < 1e-9
    assert morphex.Mesh.read(tmp_path / "both.stl").check().valid
    assert both.write(tmp_path / "both.off", exact=True) is None


def test_pickle_is_exact(unit_cube):
    mesh = unit_cube.translated(("1/3", "1/7", 0))
    copy = pickle.loads(pickle.dumps(mesh))
    assert copy.exact_vertices() == mesh.exact_vertices()
    assert np.array_equal(copy.faces, mesh.faces)


def test_bad_file_names_the_file(tmp_path):
    bad = tmp_path / "broken.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n")
    with pytest.raises(ValueError, match="broken.off") as info:
        morphex.Mesh.read(bad)
    assert "line" in str(info.value)
    with pytest.raises(ValueError, match="missing.off"):
        morphex.Mesh.read(tmp_path / "missing.off")


def test_bad_arrays():
    with pytest.raises(ValueError, match=r"faces\[1\]\[2\]: vertex index 8 out of range"):
        morphex.Mesh(CUBE_VERTICES, [[0, 1, 2], [0, 1, 8]])
    with pytest.raises(ValueError, match="shape"):
        morphex.Mesh(CUBE_VERTICES[:, :2], CUBE_FACES)
    with pytest.raises(TypeError, match="integer"):
        morphex.Mesh(CUBE_VERTICES, CUBE_FACES.astype(float))
    with pytest.raises(ValueError, match="finite"):
        morphex.Mesh(CUBE_VERTICES * np.nan, CUBE_FACES)
    with pytest.raises(ValueError, match="half_side"):
        morphex.cube(0)


def test_check_reports_problems(data_dir):
    open_cube = morphex.Mesh.read(data_dir / "open_cube.off")
    report = open_cube.check()
    assert not report.valid and not report.closed and report.border_edges == 4
    assert report.problems.startswith("mesh is not closed")
    inward = morphex.Mesh.read(data_dir / "inward_cube.off")
    assert inward.volume() < 0 and not inward.check().outward
