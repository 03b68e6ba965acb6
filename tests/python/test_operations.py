# SPDX-License-Identifier: GPL-3.0-or-later
# Booleans, morphology, Minkowski sums and repair: exact volumes and the command line's errors.
from concurrent.futures import ThreadPoolExecutor
from fractions import Fraction

import numpy as np
import pytest

import morphex


def test_booleans_of_cubes_shifted_by_half(unit_cube):
    shifted = unit_cube.translated((Fraction(1, 2), 0, 0))
    assert morphex.union(unit_cube, shifted).volume() == Fraction(3, 2)
    assert morphex.intersection(unit_cube, shifted).volume() == Fraction(1, 2)
    assert morphex.difference(unit_cube, shifted).volume() == Fraction(1, 2)
    assert (unit_cube | shifted).check().volume == Fraction(3, 2)
    assert (unit_cube & shifted).check().valid


def test_inclusion_exclusion_is_exact(unit_cube):
    a = unit_cube
    b = unit_cube.translated(("1/3", "1/3", "1/3"))
    union, inter, diff = a | b, a & b, a - b
    assert inter.volume() == Fraction(2, 3) ** 3
    assert union.volume() + inter.volume() == a.volume() + b.volume()
    assert diff.volume() == a.volume() - inter.volume() == Fraction(19, 27)
    # the constructed corners are exact thirds, not their doubles
    assert {Fraction(p[0]) for p in inter.exact_vertices()} == {Fraction(1, 3), Fraction(1)}
    for result in (union, inter, diff):
        assert result.check().valid


def test_invalid_operand_raises_invalid_solid(data_dir, unit_cube):
    open_cube = morphex.Mesh.read(data_dir / "open_cube.off")
    with pytest.raises(morphex.InvalidSolid, match=r"open_cube.off: second operand is not a "
                                                   r"valid solid: mesh is not closed"):
        morphex.union(unit_cube, open_cube)
    assert issubclass(morphex.InvalidSolid, ValueError)
    with pytest.raises(ValueError, match="first operand is not a valid solid"):
        morphex.Mesh(open_cube.vertices, open_cube.faces) - unit_cube
    with pytest.raises(morphex.InvalidSolid, match="open_cube.off: mesh is not closed"):
        morphex.dilate(open_cube, "cube:r=1/4")


def test_dilation_and_erosion_are_exact(unit_cube):
    dilated = morphex.dilate(unit_cube, "cube:r=1/4")
    assert dilated.volume() == Fraction(27, 8) and dilated.check().valid
    assert morphex.erode(unit_cube, "cube:r=1/4").volume() == Fraction(1, 8)
    assert morphex.opening(unit_cube, "cube:r=1/4").volume() == 1
    assert morphex.closing(unit_cube, "cube:r=1/4", threads=1).volume() == 1
    # the same structuring element given as a mesh, and as a Minkowski sum
    se = morphex.structuring_element("cube:r=1/4")
    assert se.volume() == Fraction(1, 8)
    assert morphex.dilate(unit_cube, se).volume() == Fraction(27, 8)
    assert morphex.minkowski_sum(unit_cube, se).volume() == Fraction(27, 8)
    # an octahedron of radius 1/3: the dilation adds faces (1/3 each), edges and corners exactly
    r = Fraction(1, 3)
    octa = morphex.dilate(unit_cube, "octahedron:r=1/3")
    assert octa.volume() == 1 + 6 * r + 12 * r * r / 2 + 8 * r ** 3 / 6


def test_bad_structuring_element(unit_cube):
    with pytest.raises(ValueError, match=r"se cube:r=-1: cube: r: expected a positive number"):
        morphex.dilate(unit_cube, "cube:r=-1")
    with pytest.raises(ValueError, match="unknown shape|expected cube"):
        morphex.erode(unit_cube, "sphere:r=1")
    with pytest.raises(ValueError, match="threads"):
        morphex.dilate(unit_cube, "cube:r=1/4", threads=0)


def test_repair_of_crossing_cubes(data_dir):
    crossing = morphex.Mesh.read(data_dir / "crossing_cubes.off")
    assert not crossing.check().valid
    with pytest.raises(morphex.InvalidSolid, match="crossing_cubes.off"):
        morphex.erode(crossing, "cube:r=1/8")
    repaired, report = morphex.repair(crossing, report=True)
    assert repaired.check().valid and report["changed"]
    assert report["intersecting_pairs"] > 0
    # the union of two unit cubes overlapping in a cube of side 1/2, exactly
    assert repaired.volume() == 2 - Fraction(1, 8)
    with pytest.raises(ValueError, match="open_cube.off: cannot repair"):
        morphex.repair(morphex.Mesh.read(data_dir / "open_cube.off"))


def test_threads_run_concurrently(unit_cube):
    shifts = [Fraction(k, 7) for k in range(1, 5)]
    with ThreadPoolExecutor(max_workers=2) as pool:
        volumes = list(pool.map(
            lambda s: morphex.union(unit_cube, unit_cube.translated((s, s, 0)), threads=1).volume(),
            shifts))
    assert volumes == [2 - (1 - s) ** 2 for s in shifts]


def test_generators_are_exact():
    box = morphex.box(("-1/3", 0, 0), (1, "1/2", 2))
    assert box.volume() == Fraction(4, 3) * Fraction(1, 2) * 2
    cube = morphex.cube("1/5", centre=(1, 1, 1))
    assert cube.volume() == Fraction(8, 125)
    assert np.allclose(cube.vertices.min(axis=0), 0.8)


def test_repair_has_a_work_budget():
    # 500 random tetrahedra crossing each other: refused at once instead of gigabytes of work
    rng = np.random.default_rng(7)
    corners = rng.random((500, 1, 3)) + (1 + 3 * rng.random((500, 1, 1))) * rng.random((500, 4, 3))
    tetra = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    faces = (tetra[None, :, :] + 4 * np.arange(500)[:, None, None]).reshape(-1, 3)
    soup = morphex.Mesh(corners.reshape(-1, 3), faces)
    with pytest.raises(ValueError, match="repair would exceed its budget"):
        morphex.repair(soup)
    with pytest.raises(ValueError, match="budget"):
        morphex.repair(soup, budget=-1)


def test_errors_form_one_hierarchy_mapped_to_python_kinds(tmp_path, unit_cube):
    # morphex/error.h: input problems are ValueErrors, storage failures OSErrors, all morphex.Error.
    assert issubclass(morphex.InputError, morphex.Error) and issubclass(morphex.InputError, ValueError)
    assert issubclass(morphex.InvalidSolid, morphex.InputError)
    assert issubclass(morphex.LossyOutputError, morphex.OutputError)
    assert issubclass(morphex.OutputError, morphex.Error)
    assert issubclass(morphex.StorageError, morphex.Error) and issubclass(morphex.StorageError, OSError)
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n")
    with pytest.raises(morphex.InputError, match="bad.off"):
        morphex.Mesh.read(bad)
    with pytest.raises(morphex.StorageError, match="cannot"):
        unit_cube.write(tmp_path / "missing-folder" / "out.off")
    # An operation's result is a Solid: chaining it checks nothing again and stays exact.
    dilated = morphex.dilate(unit_cube, "cube:r=1/4")
    assert (dilated - unit_cube).volume() == dilated.volume() - unit_cube.volume()
