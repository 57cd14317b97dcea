"""`detach explore` driven in a real browser (Debian's chromium through
selenium): the page's numbers against `detach pave --json` run separately,
an edit with an error, a downloaded proof checked by `detach verify`, and
the server's refusals.

Run: `DETACH_BIN=target/release/detach pytest tests/browser` (with
`DETACH_SCREENSHOTS=docs` the page's pictures in docs/ are redrawn).
"""

import http.client
import json
import os
import pathlib
import subprocess
import time
import urllib.parse

import pytest
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

BIN = os.environ.get("DETACH_BIN", "target/release/detach")
FINE = 1 / 1024


def detach(*args):
    return subprocess.run([BIN, *args], capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def server():
    p = subprocess.Popen(
        [BIN, "explore", "--scene", "painleve-rod", "--no-browser", "--port", "0"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )
    url = p.stdout.readline().strip()
    assert url.startswith("http://127.0.0.1:"), url
    yield url
    p.terminate()
    p.wait(timeout=10)


@pytest.fixture(scope="module")
def downloads(tmp_path_factory):
    return tmp_path_factory.mktemp("downloads")


@pytest.fixture(scope="module")
def browser(downloads, tmp_path_factory):
    o = webdriver.ChromeOptions()
    o.binary_location = os.environ.get("CHROMIUM", "/usr/bin/chromium")
    # This machine's network is closed: no background connections.
    for flag in ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic",
                 "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--window-size=1500,1400",
                 f"--user-data-dir={tmp_path_factory.mktemp('profile')}"]:
        o.add_argument(flag)
    o.add_experimental_option("prefs", {
        "download.default_directory": str(downloads),
        "download.prompt_for_download": False,
    })
    d = webdriver.Chrome(service=Service(os.environ.get("CHROMEDRIVER", "/usr/bin/chromedriver")),
                         options=o)
    d.execute_cdp_cmd("Page.setDownloadBehavior",
                      {"behavior": "allow", "downloadPath": str(downloads)})
    yield d
    d.quit()


def wait(d, what, timeout=60):
    return WebDriverWait(d, timeout, poll_frequency=0.05).until(lambda _: d.execute_script(what))


def wait_fine(d, mu):
    """Waits for the fine certified frame at μ = `mu` (text as sent)."""
    wait(d, f"""const t = document.querySelector('#areas');
        return document.getElementById('status').dataset.phase === 'fine'
            && t.dataset.params && JSON.parse(t.dataset.params).mu === {json.dumps(mu)};""")


def page_areas(d):
    rows = d.execute_script("""return [...document.querySelectorAll('#areas tbody tr')]
        .map((r) => [r.dataset.name, r.dataset.inner, r.dataset.outer]);""")
    return {n: (float(i), float(o)) for n, i, o in rows}


def pave_areas(mu):
    r = detach("pave", "--scene", "painleve-rod", "--param", f"mu={mu}",
               "--eps", repr(FINE), "--json")
    assert r.returncode == 0, r.stderr
    return {g["name"]: (g["inner_area"], g["outer_area"]) for g in json.loads(r.stdout)["regions"]}


def click(d, canvas, x, y):
    """A click at pixel (x, y) of a canvas."""
    d.execute_script("""const o = document.getElementById(arguments[0]);
        const r = o.getBoundingClientRect();
        o.dispatchEvent(new MouseEvent('click', {clientX: r.left + arguments[1],
                                                 clientY: r.top + arguments[2]}));""", canvas, x, y)


def move_slider(d, name, value):
    d.execute_script(
        "const s = document.getElementById(arguments[0]); s.value = arguments[1];"
        "s.dispatchEvent(new Event('input'));", f"slider-{name}", value)


def test_moving_mu_across_four_thirds_matches_pave(server, browser):
    browser.get(server)
    wait_fine(browser, "1.5")
    assert page_areas(browser) == pave_areas("1.5")
    # Below μ* = 4/3 the rod has no paradox: both paradox cells' outer
    # areas are 0 at μ = 1; above it they are not.
    move_slider(browser, "mu", 1.0)
    assert browser.find_element(By.ID, "text-mu").get_attribute("value") == "1"
    wait_fine(browser, "1")
    below = page_areas(browser)
    assert below == pave_areas("1")
    move_slider(browser, "mu", 1.5)
    wait_fine(browser, "1.5")
    above = page_areas(browser)
    paradox = ["omega_and_not_omega0", "not_omega_and_omega0"]
    assert all(below[c][1] == 0 for c in paradox), below
    assert any(above[c][0] > 0 for c in paradox), above
    if os.environ.get("DETACH_SCREENSHOTS"):
        wait(browser, "return /boxes/.test(document.getElementById('pstatus').textContent)")
        click(browser, "overlay", 120, 200)
        wait(browser, "return /steps/.test(document.getElementById('events').textContent)")
        browser.save_screenshot(str(pathlib.Path(os.environ["DETACH_SCREENSHOTS"]) / "explore.png"))


def test_a_superseded_slider_never_lands(server, browser):
    browser.get(server)
    wait_fine(browser, "1.5")
    # Twenty-one positions in one burst: the page ends on the last, certified.
    browser.execute_script("""const s = document.getElementById('slider-mu');
        for (let i = 0; i <= 20; i++) { s.value = 0.5 + i * 0.06; s.dispatchEvent(new Event('input')); }""")
    wait_fine(browser, "1.7")
    assert page_areas(browser) == pave_areas("1.7")


def test_the_pointer_reads_cell_and_state(server, browser):
    browser.get(server)
    wait_fine(browser, "1.5")
    browser.execute_script("""const o = document.getElementById('overlay');
        o.dispatchEvent(new MouseEvent('mousemove', {clientX: o.getBoundingClientRect().left + 400,
                                                     clientY: o.getBoundingClientRect().top + 300}));""")
    text = browser.find_element(By.ID, "readout").text
    assert text.startswith("θ = ") and "θ̇ = " in text and ("certified" in text), text


def test_a_click_draws_a_certified_trajectory(server, browser):
    browser.get(server)
    wait_fine(browser, "1.5")
    click(browser, "overlay", 300, 250)
    wait(browser, "return /steps/.test(document.getElementById('events').textContent)")


def test_the_parameter_plane_moves_the_point(server, browser):
    browser.get(server)
    wait_fine(browser, "1.5")
    wait(browser, "return /boxes/.test(document.getElementById('pstatus').textContent)", 120)
    assert browser.find_element(By.ID, "px").get_attribute("value") == "mu"
    # A click at the left quarter of the plane: μ = 3/4 of its range [0, 3].
    click(browser, "pover", 100, 150)
    wait_fine(browser, "0.75")


def test_an_edit_with_an_error_is_shown_at_its_line(server, browser):
    browser.get(server)
    wait_fine(browser, "1.5")
    editor = browser.find_element(By.ID, "editor")
    text = editor.get_attribute("value")
    lines = text.split("\n")
    broken = "\n".join(lines[:5] + ["[domain"] + lines[5:])
    browser.execute_script("arguments[0].value = arguments[1];", editor, broken)
    browser.find_element(By.ID, "apply").click()
    wait(browser, "return document.getElementById('editor-error').dataset.line === '6'")
    assert browser.find_element(By.ID, "status").get_attribute("data-phase") == "error"
    # A working edit: μ's default changed in the file redraws at it.
    fixed = text.replace('mu = { value = "1.5"', 'mu = { value = "0.5"')
    assert fixed != text
    browser.execute_script("arguments[0].value = arguments[1];", editor, fixed)
    browser.find_element(By.ID, "apply").click()
    wait(browser, "return document.getElementById('editor-error').textContent === ''")
    wait_fine(browser, "1.5")  # the slider's value is kept over the edit


def test_the_downloaded_proof_of_the_view_verifies(server, browser, downloads):
    browser.get(server)
    wait_fine(browser, "1.5")
    browser.find_element(By.CSS_SELECTOR, "button[data-kind=proof]").click()
    deadline = time.time() + 120
    proof = downloads / "painleve-rod-proof.json"
    while not proof.exists() and time.time() < deadline:
        time.sleep(0.1)
    assert proof.exists(), list(downloads.iterdir())
    r = detach("verify", str(proof))
    assert r.returncode == 0 and "VALID" in r.stdout, r.stdout + r.stderr
    # The proof states the view: its parameters and resolution.
    doc = json.loads(proof.read_text())
    assert "1.5" in json.dumps(doc["statement"])


def request(url, method="GET", path=None, host=None, body=None, token=True):
    u = urllib.parse.urlsplit(url)
    c = http.client.HTTPConnection(u.hostname, u.port, timeout=30)
    q = u.query if token else ""
    c.putrequest(method, (path or "/") + ("?" + q if q else ""), skip_host=True)
    c.putheader("Host", host or u.netloc)
    if body is not None:
        c.putheader("Content-Length", str(len(body)))
    c.endheaders()
    if body is not None:
        try:
            c.send(body)
        except (BrokenPipeError, ConnectionResetError):
            pass
    r = c.getresponse()
    return r.status, r.read()


def test_the_server_refuses_what_it_must(server):
    assert request(server)[0] == 200
    assert request(server, token=False)[0] == 403
    wrong = server.replace("token=", "token=0")
    assert request(wrong)[0] == 403
    # DNS rebinding: the page of another site under its own name.
    assert request(server, host="evil.example:80")[0] == 403
    port = urllib.parse.urlsplit(server).port
    assert request(server, host=f"evil.example:{port}")[0] == 403
    # Bodies are bounded.
    status, _ = request(server, "POST", "/api/atlas", body=b" " * (300 * 1024))
    assert status == 413
    # No path a request names is read.
    assert request(server, path="/etc/passwd")[0] == 404
    assert request(server, path="/../Cargo.toml")[0] == 404
    status, body = request(server, "POST", "/api/atlas", body=b"[1, 2]")
    assert status == 400 and b"JSON object" in body
