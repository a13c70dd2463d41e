#!/usr/bin/python3
"""Screenshots of the lab's views for docs/serve.md: the page in one state with a GGX-F82 metal,
the paper's lobe and Phong, each view's section saved as docs/images/lab-<view>.png.

    /usr/bin/python3 bench/lab/screenshots.py [--specula build/release/specula] [--out docs/images]
"""
import argparse
import pathlib

from driver import lab

GOLD = {"alpha": 0.3, "f0": [1.0, 0.78, 0.34], "tint": [0.94, 0.83, 0.58]}
STATE = {
    "models": [{"id": "log-normalized", "params": {"n": 50}}, {"id": "ggx-f82", "params": GOLD},
               {"id": "phong-normalized", "params": {"n": 20}}],
    "theta": 40, "phi": 135, "reference": "phong-normalized", "size": 200, "estimator": "sampler", "samples": 4000,
    "channel": "luminance",
    "lit": {"model": 1, "obj": "bundled", "probe": "bundled", "estimator": "mis", "samples": 64, "exposure": 0},
}
# each view's screenshot: the CSS selector of its section
VIEWS = {"controls": "#models", "light": "#light", "switches": "#switches", "session": "#session", "spheres": "#spheres-section", "plots": "#plots", "lobe3d": "#lobe3d-section",
         "slices": "#slices", "lit": "#lit", "sampling": "#sampling", "fit": "#fit", "design": "#design"}


def run_jobs(browser):
    """A short fit and a short design, so that their panels show a front."""
    browser.run("document.getElementById('fit-n').value = '1:1000@10'; document.getElementById('fit-generations').value = '100';"
                "document.getElementById('fit-start').click();")
    browser.wait("return /: (done|stopped)/.test(document.getElementById('fit-status').textContent);", 180)
    browser.run("document.getElementById('design-time').value = '10'; document.getElementById('design-cost').value = '3';"
                "document.getElementById('design-timing').checked = false; document.getElementById('design-start').click();")
    browser.wait("return /: (done|stopped)/.test(document.getElementById('design-status').textContent);", 300)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--specula", default="build/release/specula")
    parser.add_argument("--out", default="docs/images")
    args = parser.parse_args()
    with lab(args.specula) as browser:
        browser.open(STATE)
        browser.wait("return document.getElementById('lit-image').dataset.state === 'done';")
        run_jobs(browser)
        browser.run("document.getElementById('session-save').click();")  # its two files offered as links
        for name, css in VIEWS.items():
            path = pathlib.Path(args.out) / f"lab-{name}.png"
            path.write_bytes(browser.screenshot(css))
            print(f"wrote {path}")


if __name__ == "__main__":
    main()
