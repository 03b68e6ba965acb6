# SPDX-License-Identifier: GPL-3.0-or-later
# The example script pipelines/examples/index_folder.py on a tiny generated folder.
import os
import subprocess
import sys

from conftest import write_family_folder


def test_index_folder_example(tmp_path, source_dir):
    folder = tmp_path / "meshes"
    write_family_folder(folder)
    script = source_dir / "pipelines" / "examples" / "index_folder.py"
    db = tmp_path / "folder.sqlite"
    result = subprocess.run(
        [sys.executable, str(script), str(folder), "--db", str(db), "--query", "block-2",
         "-k", "2", "--scales", "2", "--d2-samples", "2000"],
        capture_output=True, text=True, env=dict(os.environ), timeout=120)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].startswith("indexed 6 meshes")
    assert "nearest neighbours of block-2" in lines[1]
    assert lines[2].split()[:2] == ["1", "block-1"]
    assert len(lines) == 4 and db.exists()


def test_readme_python_example(tmp_path, monkeypatch, source_dir):
    # The README's Python example runs as written (in an empty folder), and every mesh it adds to
    # the index is indexed.
    readme = (source_dir / "README.md").read_text()
    section = readme[readme.index("\n## Python\n"):]
    code = section[section.index("```python\n") + len("```python\n"):]
    code = code[:code.index("```")]
    import morphex

    summaries = []

    class RecordingIndex(morphex.Index):
        def add(self, *args, **kwargs):
            summaries.append(super().add(*args, **kwargs))
            return summaries[-1]

    monkeypatch.setattr(morphex, "Index", RecordingIndex)
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md", "exec"), {"__name__": "__main__"})
    assert summaries and all(s["failed"] == 0 and s["indexed"] > 0 for s in summaries), summaries
