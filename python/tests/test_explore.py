"""`Scene.explore()`: the page served from Python, its areas against the
CLI's `detach pave --json` (a separate process), and the parameters the
page ends on read back from Python."""

import http.client
import json
import urllib.parse

import detach
from conftest import cli_json


def post(url, path, doc):
    u = urllib.parse.urlsplit(url)
    c = http.client.HTTPConnection(u.hostname, u.port, timeout=120)
    c.request("POST", f"{path}?{u.query}", body=json.dumps(doc))
    r = c.getresponse()
    return r.status, json.loads(r.read())


def test_the_page_serves_the_scene_at_its_parameters():
    rod = detach.Scene.load("painleve-rod", mu="0.5")
    with rod.explore() as page:
        assert page.url.startswith("http://127.0.0.1:") and "token=" in page.url
        assert "<iframe" in page._repr_html_()
        # Before any atlas: the parameters it was started with.
        assert page.params["mu"] == "0.5"
        status, s = post(page.url, "/api/scene", {"client": "t", "seq": 1, "start": True})
        assert status == 200 and s["name"] == "painleve-rod"
        assert {p["name"]: p["value"] for p in s["params"]}["mu"] == "0.5"


def test_the_page_areas_are_those_of_pave_and_its_last_view_is_read_back():
    rod = detach.Scene.load("painleve-rod")
    with rod.explore() as page:
        req = {"client": "t", "seq": 1, "scene": "painleve-rod", "params": {"mu": "1.25"},
               "eps": 1 / 1024, "width": 800, "height": 600}
        status, a = post(page.url, "/api/atlas", req)
        assert status == 200, a
        assert a["width"] * a["height"] == sum(a["rle"][1::2])
        want = cli_json("pave", "--scene", "painleve-rod", "--param", "mu=1.25",
                        "--eps", repr(1 / 1024), "--json")
        got = {r["name"]: (r["inner"], r["outer"]) for r in a["areas"]}
        assert got == {r["name"]: (r["inner_area"], r["outer_area"]) for r in want["regions"]}
        assert page.params == {"m": "1", "l": "1", "g": "9.81", "mu": "1.25"}


def test_a_stopped_page_answers_no_more():
    page = detach.Scene.load("viscous-disc").explore()
    url = page.url
    page.stop()
    u = urllib.parse.urlsplit(url)
    c = http.client.HTTPConnection(u.hostname, u.port, timeout=5)
    try:
        c.request("GET", f"/?{u.query}")
        c.getresponse()
        answered = True
    except OSError:
        answered = False
    assert not answered


def download(url, doc):
    u = urllib.parse.urlsplit(url)
    c = http.client.HTTPConnection(u.hostname, u.port, timeout=300)
    c.request("POST", f"/api/download?{u.query}", body=json.dumps(doc))
    r = c.getresponse()
    return r.status, r.getheader("Content-Disposition"), r.read()


def test_the_view_downloads_as_svg_png_csv_and_a_valid_proof(tmp_path):
    rod = detach.Scene.load("painleve-rod", mu="1.4")
    with rod.explore() as page:
        view = {"client": "t", "scene": "painleve-rod", "params": {"mu": "1.4"},
                "eps": 1 / 64, "width": 800, "height": 600}
        files = {}
        for seq, kind in enumerate(["svg", "png", "csv", "proof"]):
            status, disposition, body = download(page.url, dict(view, kind=kind, seq=seq))
            assert status == 200, body[:200]
            assert "attachment" in disposition
            files[kind] = body
        assert files["svg"].startswith(b"<svg") and b"certified tubes" in files["svg"]
        assert files["png"].startswith(b"\x89PNG\r\n\x1a\n")
        # The leaves CSV is the paving `detach pave --leaves` writes: as
        # many rows as the CLI's paving of the same view has leaves.
        rows = [l for l in files["csv"].decode().splitlines() if l and not l.startswith("#")]
        want = cli_json("pave", "--scene", "painleve-rod", "--param", "mu=1.4",
                        "--eps", repr(1 / 64), "--json")
        assert len(rows) - 1 == want["leaves"]
        proof = tmp_path / "view.json"
        proof.write_bytes(files["proof"])
        assert detach.verify(proof).verdict == "VALID"
        status, _, body = download(page.url, dict(view, kind="exe", seq=9))
        assert status == 400 and b"unknown download" in body


def test_an_atlas_is_answered_while_a_parameter_plane_computes():
    import threading
    import time

    rod = detach.Scene.load("painleve-rod")
    with rod.explore() as page:
        plane = {"client": "t", "seq": 1, "scene": "painleve-rod", "params": {},
                 "x": {"name": "mu", "lo": "0", "hi": "3"},
                 "y": {"name": "l", "lo": "0.5", "hi": "2"}, "eps": 1 / 1024}
        done = {}
        worker = threading.Thread(target=lambda: done.update(r=post(page.url, "/api/params", plane)))
        start = time.monotonic()
        worker.start()
        time.sleep(0.5)
        atlas = {"client": "t", "seq": 1, "scene": "painleve-rod", "params": {"mu": "1.2"},
                 "eps": 1 / 64, "width": 400, "height": 300}
        status, a = post(page.url, "/api/atlas", atlas)
        answered = time.monotonic()
        assert status == 200 and a["leaves"] > 0
        assert worker.is_alive(), "the plane was finished before the atlas: no overlap shown"
        # A newer plane supersedes the running one, which stops and says so.
        status, _ = post(page.url, "/api/params", dict(plane, seq=2, eps=1 / 4))
        worker.join(timeout=60)
        assert done["r"][1].get("superseded") is True
        assert answered - start < 30
