# SPDX-License-Identifier: GPL-3.0-or-later
# Python threads (issue 44, item 6): first calls from several threads at once, one Index shared by
# threads, close() while add() runs. Each case runs in its own interpreter, so that a deadlock is
# a timeout and a crash an exit status instead of the end of the test run.
import os
import subprocess
import sys
import textwrap

import pytest

from conftest import SOURCE_DIR

PRELUDE = textwrap.dedent(f"""
    import sys, threading
    sys.path.insert(0, {str(SOURCE_DIR / "tests" / "python")!r})
    sys.setswitchinterval(1e-6)  # switch threads as often as possible: races show at once
    import morphex
    from conftest import fast_pipeline, write_family_folder
""")


def run_script(body, timeout=120, prelude=PRELUDE):
    try:
        result = subprocess.run([sys.executable, "-c", prelude + textwrap.dedent(body)],
                                capture_output=True, text=True, env=dict(os.environ),
                                timeout=timeout)
    except subprocess.TimeoutExpired:
        pytest.fail("deadlock: the script did not finish")
    assert result.returncode == 0, f"exit {result.returncode}: {result.stderr}"
    return result.stdout


@pytest.mark.parametrize("attempt", range(5))
def test_first_calls_from_threads_at_once(attempt):
    # Every conversion helper's first use at once: exact numbers (numbers, fractions), paths
    # (os.fspath) and JSON (json), from eight threads released together, in an interpreter that
    # has imported none of these modules yet.
    out = run_script(f"""
        import sys, threading
        sys.setswitchinterval(1e-6)
        import morphex
        CUBE = {str(SOURCE_DIR / "tests" / "data" / "unit_cube.off")!r}
        barrier = threading.Barrier(8)
        results = []
        def work():
            barrier.wait()
            box = morphex.box((0, 0, 0), (1, 1, 1)).translated(("1/2", 0, 0))
            report = morphex.run_pipeline(
                {{"pipeline": [{{"type": "read", "path": CUBE}}, {{"type": "check"}}]}})
            results.append((box.volume(), type(report).__name__))
        threads = [threading.Thread(target=work) for _ in range(8)]
        for t in threads: t.start()
        for t in threads: t.join()
        assert [str(v) for v, _ in results] == ["1"] * 8, results
        assert [kind for _, kind in results] == ["dict"] * 8, results
        print("ok")
    """, timeout=60, prelude="")
    assert out.strip() == "ok"


def test_one_index_shared_by_threads(tmp_path):
    out = run_script(f"""
        folder = {str(tmp_path / "meshes")!r}
        write_family_folder(folder)
        import glob
        paths = sorted(glob.glob(folder + "/*.off"))
        index = morphex.Index({str(tmp_path / "shared.sqlite")!r})
        errors = []
        def add(part):
            try:
                for path in part:
                    index.add(path, pipeline=fast_pipeline(), threads=1)
                    index.names(); len(index)
            except Exception as e:
                errors.append(repr(e))
        threads = [threading.Thread(target=add, args=(paths[i::3],)) for i in range(3)]
        for t in threads: t.start()
        for t in threads: t.join()
        assert not errors, errors
        assert len(index) == 6, index.names()
        print("ok")
    """)
    assert out.strip() == "ok"


def test_close_while_add_runs(tmp_path):
    # close() from another thread waits for the running add, which completes; later calls say
    # that the index is closed. Never a crash.
    out = run_script(f"""
        import time
        index = morphex.Index({str(tmp_path / "closed.sqlite")!r})
        runs = []  # 20 adds of 40 meshes each, written first: close() comes during one
        for run in range(20):
            runs.append([])
            for k in range(run * 40 + 1, run * 40 + 41):
                runs[-1].append({str(tmp_path)!r} + f"/box-{{k}}.off")
                morphex.box((0, 0, 0), (1, 2, k)).write(runs[-1][-1], exact=True)
        done, errors = [], []
        def add():
            try:
                for paths in runs:
                    done.append(index.add(paths, pipeline=fast_pipeline(), threads=1))
            except ValueError as e:
                errors.append(str(e))
        worker = threading.Thread(target=add)
        worker.start()
        time.sleep(0.2)
        index.close()
        worker.join()
        assert done and all(s["indexed"] == 40 for s in done), done
        assert len(errors) == 1 and "the index is closed" in errors[0], errors
        try:
            index.names()
        except ValueError as e:
            assert "closed" in str(e)
        else:
            raise AssertionError("a closed index answered")
        del index
        print("ok")
    """)
    assert out.strip() == "ok"
