"""``rotorcad report`` (issue 16): one self-contained HTML page per design, opened in headless
Chromium (Debian's package: `apt-get install chromium`; .ci/run installs it). The page as the
browser renders it holds every number of `rotorcad rotor --json` (resp. `gear --json`) for the
same design, with a unit, the hobbability verdict of `rotorcad hob --json`, and a screenshot is
taken; the page loads nothing from the network: no http(s) address in any src/href, a
Content-Security-Policy that forbids loads, and Chromium's own network log (with a proxy to
nowhere) shows no request made by the page, while the same log does show the request of a page
that asks for an image from elsewhere (so the check can fail).
"""

from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import pytest

from rotorcad.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--hide-scrollbars",
    "--proxy-server=127.0.0.1:9",  # a proxy to nowhere: nothing could leave the machine
    "--host-resolver-rules=MAP * ~NOTFOUND",
]


def chromium() -> str:
    """The Chromium binary; the test fails (it is not skipped) when there is none."""
    for name in ("chromium", "chromium-browser", "google-chrome", "chrome"):
        found = shutil.which(name)
        if found:
            return found
    pytest.fail(
        "headless Chromium is needed to check `rotorcad report` (Debian: apt-get install -y chromium; .ci/run installs it)"
    )


def browse(tmp_path: Path, page: Path, *action: str) -> tuple[str, list[str]]:
    """Run Chromium on ``page`` with ``action`` (--dump-dom or --screenshot=...); return its
    stdout and the addresses of the requests the page itself made (Chromium's network log:
    requests started by the page have the page's origin as initiator, the browser's own have
    none)."""
    profile = tmp_path / f"profile-{len(list(tmp_path.iterdir()))}"
    netlog = tmp_path / f"netlog-{profile.name}.json"
    env = {**os.environ, "HOME": str(tmp_path)}
    done = subprocess.run(
        [chromium(), *FLAGS, f"--user-data-dir={profile}", f"--log-net-log={netlog}", *action, page.resolve().as_uri()],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    log = json.loads(netlog.read_text())
    types = {v: k for k, v in log["constants"]["logEventTypes"].items()}
    requested = [
        e["params"]["url"]
        for e in log["events"]
        if types.get(e["type"]) == "URL_REQUEST_START_JOB"
        and e.get("params", {}).get("initiator") not in (None, "not an origin")
        and not e["params"]["url"].startswith(("file:", "data:"))
    ]
    return done.stdout, requested


class Cells(HTMLParser):
    """The rows of the page's tables (data-key -> cell texts) and every src / href."""

    def __init__(self) -> None:
        super().__init__()
        self.rows: dict[str, list[str]] = {}
        self.links: list[str] = []
        self._key: str | None = None
        self._cell: list[str] | None = None
        self.text: list[str] = []
        self.csp = ""

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.links += [v for k, v in attrs if k in ("src", "href", "xlink:href") and v]
        if tag == "meta" and a.get("http-equiv", "").lower() == "content-security-policy":
            self.csp = a.get("content", "")
        if tag == "tr" and "data-key" in a:
            self._key = a["data-key"]
            self.rows[self._key] = []
        if tag == "td" and self._key is not None:
            self._cell = []

    def handle_endtag(self, tag):
        if tag == "td" and self._cell is not None and self._key is not None:
            self.rows[self._key].append("".join(self._cell).strip())
            self._cell = None
        if tag == "tr":
            self._key = None

    def handle_data(self, data):
        self.text.append(data)
        if self._cell is not None:
            self._cell.append(data)


def numbers(mapping: dict, prefix: str = "") -> dict[str, object]:
    """Every scalar of a JSON object by its dotted key (lists aside)."""
    out: dict[str, object] = {}
    for key, value in mapping.items():
        if isinstance(value, dict):
            out.update(numbers(value, f"{prefix}{key}."))
        elif not isinstance(value, list):
            out[f"{prefix}{key}"] = value
    return out


def shown(text: str, value: object) -> bool:
    """Whether a cell's text shows ``value`` (numbers to 6 significant digits)."""
    if isinstance(value, bool):
        return text == ("yes" if value else "no")
    if value is None:
        return text == "—"
    if isinstance(value, int | float):
        return math.isclose(float(text.replace("−", "-")), float(value), rel_tol=1e-5, abs_tol=1e-300)
    return text == str(value)


def json_of(capsys, *args) -> dict:
    capsys.readouterr()
    assert main([str(a) for a in args]) == 0
    return json.loads(capsys.readouterr().out)


def check_page(tmp_path: Path, page: Path, expected: dict[str, object], hob: dict) -> Cells:
    dom, requested = browse(tmp_path, page, "--dump-dom")
    assert requested == [], f"the page asked the network for {requested}"
    cells = Cells()
    cells.feed(dom)  # the page as Chromium parsed and rendered it
    assert "default-src 'none'" in cells.csp
    assert not [u for u in cells.links if u.lower().startswith(("http:", "https:", "//", "ftp:"))]
    for key, value in expected.items():
        assert key in cells.rows, f"{key} is not on the page"
        _, text, unit = cells.rows[key]
        if value is None and expected.get(f"{key}_infinite"):  # JSON null for an infinite slip: the page says so
            assert text == "∞", f"{key}: the page shows {text!r} for an infinite value"
            continue
        assert shown(text, value), f"{key}: the page shows {text!r}, the command {value!r}"
        if isinstance(value, int | float) and not isinstance(value, bool):
            assert unit, f"{key} has no unit on the page"
    flat = numbers(hob)
    for key, value in flat.items():
        if value is None and flat.get(f"{key}_infinite"):  # JSON null for an infinite radius: the page says so
            assert cells.rows[key][1] == "∞", key
        else:
            assert shown(cells.rows[key][1], value), key
    text = " ".join("".join(cells.text).split())
    assert f"Hobbability: {'hobbable' if hob['hobbable'] else 'NOT hobbable'}" in text
    for reason in hob["reasons"]:
        assert reason in text
    return cells


def test_rotor_report_holds_the_numbers_of_rotor_json_and_loads_nothing(tmp_path, capsys, rack_report):
    chromium()
    design = ROOT / "samples" / "rack_involute_5_6.toml"
    # `report DESIGN --out report.html --files files --json`, run once in the run (tests/conftest.py)
    made, page = rack_report
    assert made["report"] == str(page) and made["kind"] == "rotor"
    assert {Path(p).name for p in made["files"]} == {
        "male.csv",
        "female.csv",
        "rack.csv",
        "pair.dxf",
        "hob.dxf",
        "pair.svg",
        "sliding.svg",
        "hob.svg",
        "report.html",
    }
    rotor = json_of(capsys, "rotor", design, "--json")
    rotor.pop("files")
    hob = json_of(capsys, "hob", design, "--json")
    hob.pop("files")
    cells = check_page(tmp_path, page, numbers(rotor), hob)
    text = "".join(cells.text)
    for defect in rotor["defects"]:  # the defects, each with its flank
        assert defect["flank"] in text
    for name in made["files"]:  # the files written are listed
        assert name in text
    assert page.read_text().count("<svg") == 3  # the three pictures inline, as SVG
    # a screenshot of the page as a reviewer sees it
    shot = tmp_path / "report.png"
    _, requested = browse(tmp_path, page, f"--screenshot={shot}", "--window-size=1280,3000")
    assert requested == [] and shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    from matplotlib import image

    pixels = image.imread(shot)
    assert pixels.shape[:2] == (3000, 1280) and len({tuple(p) for p in pixels[::40, ::40, :3].reshape(-1, 3)}) > 20


def test_gear_report_and_the_network_check_can_fail(tmp_path, capsys):
    chromium()
    page = tmp_path / "gear.html"
    made = json_of(capsys, "report", ROOT / "samples" / "gear_pair.toml", "--out", page, "--json")
    assert made["kind"] == "gear" and made["files"] == [str(page)]
    gear = json_of(capsys, "gear", ROOT / "samples" / "gear_pair.toml", "--json")
    gear.pop("files")
    hob = json_of(capsys, "hob", ROOT / "samples" / "gear_pair.toml", "--json")
    hob.pop("files")
    check_page(tmp_path, page, numbers(gear), hob)
    # the control: a page that asks for an image from elsewhere is caught by the same log
    leaky = tmp_path / "leaky.html"
    leaky.write_text("<!DOCTYPE html><html><body><img src='http://example.invalid/x.png'></body></html>")
    _, requested = browse(tmp_path, leaky, "--dump-dom")
    assert requested == ["http://example.invalid/x.png"]


def test_report_refuses_a_page_name_that_is_not_html(tmp_path, capsys):
    capsys.readouterr()
    assert main(["report", str(ROOT / "samples" / "gear_pair.toml"), "--out", str(tmp_path / "r.pdf")]) == 2
    assert "--out must name a .html file" in capsys.readouterr().err
    assert not (tmp_path / "r.pdf").exists()
