# SPDX-License-Identifier: GPL-3.0-or-later
# Shared fixtures of the Python module's tests (ctest runs them: `ctest -R python`).
import os
from fractions import Fraction
from pathlib import Path

import pytest

import morphex

SOURCE_DIR = Path(__file__).resolve().parents[2]
DATA_DIR = SOURCE_DIR / "tests" / "data"

# Descriptor settings small enough for tests (a fraction of a second per mesh), the describe
# stage's options in pipelines.
FAST_DESCRIBE = {"scales": 2, "d2_samples": 2000, "d2_bins": 16, "facet_budget": 0}


@pytest.fixture
def unit_cube():
    return morphex.box((0, 0, 0), (1, 1, 1))


@pytest.fixture
def data_dir():
    return DATA_DIR


@pytest.fixture
def source_dir():
    return SOURCE_DIR


def fast_pipeline():
    """The index's descriptor pipeline with FAST_DESCRIBE settings."""
    return {"pipeline": [{"type": "read", "path": "${input}"},
                         dict({"type": "describe"}, **FAST_DESCRIBE)]}


def write_family_folder(folder):
    """Six boxes in three shape families (bar, plate, block), each with a scaled and moved copy,
    written as exact OFF files; returns {name: family}."""
    shapes = {"bar": (1, 1, 4), "plate": (4, 4, Fraction(1, 2)), "block": (2, 3, 3)}
    labels = {}
    os.makedirs(folder, exist_ok=True)
    for family, size in shapes.items():
        base = morphex.box((0, 0, 0), size)
        scaled = morphex.box((0, 0, 0), tuple(Fraction(3, 2) * s for s in size))
        copies = [base, scaled.translated(("1/3", 5, "-2/7"))]
        for k, mesh in enumerate(copies, start=1):
            name = f"{family}-{k}"
            mesh.write(os.path.join(folder, name + ".off"), exact=True)
            labels[name] = family
    return labels
