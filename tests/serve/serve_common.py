# SPDX-License-Identifier: GPL-3.0-or-later
"""What the `morphex serve` tests share: an index of a few generated meshes (and one that fails),
a server started on 127.0.0.1 with a free port, and small HTTP helpers (standard library only)."""
import http.client
import json
import os
import shutil
import signal
import subprocess
import sys


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)


def run(args, expect_code=0):
    result = subprocess.run(args, capture_output=True, text=True)
    if result.returncode != expect_code:
        fail(f"exit {result.returncode} (expected {expect_code}): {' '.join(args)}\n"
             f"{result.stdout}{result.stderr}")
    return result.stdout


def make_index(morphex, data, work):
    """A fresh folder with 12 generated meshes in 6 classes (labels.cla) indexed with the default
    pipeline, plus data/sheet.off, which bounds no volume and is recorded as failed."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    collection = os.path.join(work, "coll")
    run([morphex, "generate", collection, "--per-class", "2", "--seed", "1"])
    index = os.path.join(work, "index.sqlite")
    run([morphex, "index", os.path.join(collection, "*.off"), os.path.join(data, "sheet.off"),
         "--db", index, "--quiet"], expect_code=1)
    return index, collection


class Server:
    """`morphex serve` on 127.0.0.1, port 0; the port is read from its first line."""

    def __init__(self, morphex, index, *extra, tmpdir=None):
        env = dict(os.environ)
        if tmpdir:
            env["TMPDIR"] = tmpdir  # where uploads are written, so that a test can look
        self.process = subprocess.Popen(
            [morphex, "serve", "--db", index, "--port", "0", *extra],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        line = self.process.stdout.readline()
        if "serving http://127.0.0.1:" not in line or "local only" not in line:
            self.process.kill()
            fail("serve did not say where it listens: " + line + self.process.stderr.read())
        self.port = int(line.split("127.0.0.1:")[1].split("/")[0])
        self.url = f"http://127.0.0.1:{self.port}"

    def request(self, method, path, body=None, headers=None):
        """(status, headers, body bytes); the path is sent exactly as given."""
        connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=120)
        try:
            own_host = any(k.lower() == "host" for k in headers or {})
            connection.putrequest(method, path, skip_host=own_host, skip_accept_encoding=True)
            for name, value in (headers or {}).items():
                connection.putheader(name, value)
            if body is not None and not any(k.lower() == "transfer-encoding" for k in headers or {}):
                connection.putheader("Content-Length", str(len(body)))
            connection.endheaders()
            if body is not None:
                connection.send(body)
            response = connection.getresponse()
            return response.status, dict(response.getheaders()), response.read()
        finally:
            connection.close()

    def json(self, path, expect=200, method="GET", body=None, headers=None):
        status, head, content = self.request(method, path, body, headers)
        check(status == expect, f"{method} {path}: status {status}, expected {expect}: {content[:300]!r}")
        check(head.get("Content-Type", "").startswith("application/json"),
              f"{method} {path}: not JSON but {head.get('Content-Type')}")
        return json.loads(content)

    def error(self, path, expect, method="GET", body=None, headers=None):
        """A refusal: the status, and a JSON object {"error": message}; returns the message."""
        answer = self.json(path, expect, method, body, headers)
        check(isinstance(answer.get("error"), str) and answer["error"],
              f"{method} {path}: no error message in {answer}")
        return answer["error"]

    def stop(self):
        """SIGTERM: the server stops cleanly, exit 0."""
        self.process.send_signal(signal.SIGTERM)
        try:
            out, err = self.process.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            self.process.kill()
            fail("serve did not stop on SIGTERM")
        check(self.process.returncode == 0, f"serve exited {self.process.returncode}: {err}")
        check("stopped" in out, "serve did not say it stopped: " + out)

    def kill(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()


def multipart(field, filename, content):
    """A multipart/form-data body with one file, as a browser's FormData sends it."""
    boundary = "morphex-test-boundary-7d1f"
    body = (f"--{boundary}\r\nContent-Disposition: form-data; name=\"{field}\"; "
            f"filename=\"{filename}\"\r\nContent-Type: application/octet-stream\r\n\r\n"
            ).encode() + content + f"\r\n--{boundary}--\r\n".encode()
    return body, {"Content-Type": "multipart/form-data; boundary=" + boundary}
