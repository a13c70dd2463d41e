#!/usr/bin/python3
"""How long the lab blocks its input (issue 40: no view may block for more than 100 ms on these
machines' software WebGL). Opens the page in the screenshots' state (three models, one a metal given
per channel; every view on), then drives it with real (trusted) input through WebDriver actions:
the light's slider and the metal's roughness moved by keyboard, the 3-D lobe dragged, the sphere
pressed; then the channel,
the plot switches and the lit object's estimator changed by script. The page's own observers record every long
task (the main thread busy > 50 ms: Long Tasks API) and every input event's duration from the input
to the next frame (Event Timing API). Prints the counts and the largest durations, and exits 1 when
a task or an event took longer than --limit (default 100 ms).

    /usr/bin/python3 bench/lab/responsiveness.py [--specula build/release/specula]
"""
import argparse
import json
import sys
import time

from driver import lab
from screenshots import STATE

OBSERVE = """
window.__long = []; window.__events = []; window.__frames = [];
new PerformanceObserver((l) => l.getEntries().forEach((e) => __frames.push([e.duration, e.blockingDuration,
  e.scripts.map((s) => `${s.sourceFunctionName || s.invoker} ${s.sourceURL.split('/').pop()}:${s.sourceCharPosition} ${Math.round(s.duration)}`)])))
  .observe({type: 'long-animation-frame'});
new PerformanceObserver((l) => l.getEntries().forEach((e) => __long.push(e.duration))).observe({type: 'longtask'});
new PerformanceObserver((l) => l.getEntries().forEach((e) => __events.push([e.name, e.duration])))
  .observe({type: 'event', durationThreshold: 16});
"""


def keys(browser, css, sequence):
    element = browser.command("POST", "/element", {"using": "css selector", "value": css})
    browser.command("POST", f"/element/{next(iter(element.values()))}/value", {"text": sequence})


def drag(browser, css, steps, dx, dy):
    element = browser.command("POST", "/element", {"using": "css selector", "value": css})
    browser.run("arguments[0].scrollIntoView({block: 'center'});", element)
    origin = {"element-6066-11e4-a52e-4f735466cecf": next(iter(element.values()))}
    moves = [{"type": "pointerMove", "origin": origin, "x": 0, "y": 0}, {"type": "pointerDown", "button": 0}]
    moves += [{"type": "pointerMove", "origin": "pointer", "x": dx, "y": dy, "duration": 30} for _ in range(steps)]
    moves += [{"type": "pointerUp", "button": 0}]
    browser.command("POST", "/actions", {"actions": [{"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"},
                                                      "actions": moves}]})
    browser.command("DELETE", "/actions")


def select(browser, css, value):
    """A choice as a script makes it (the work it starts is what counts; its event is not an input)."""
    browser.run("const s = document.querySelector(arguments[0]); s.value = arguments[1]; s.dispatchEvent(new Event('change'));",
                css, value)
    settle(browser)


def settle(browser):
    time.sleep(0.3)
    browser.wait("return document.getElementById('status').textContent === 'ready';")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--specula", default="build/release/specula")
    parser.add_argument("--limit", type=float, default=100)
    parser.add_argument("--verbose", action="store_true", help="the longest animation frames and their scripts")
    args = parser.parse_args()
    with lab(args.specula) as browser:
        browser.open(STATE)
        browser.run(OBSERVE)
        for _ in range(5):
            keys(browser, "#light-theta", "\ue012\ue012")  # ArrowLeft: θ_i down 2°, every view again
            settle(browser)
        for _ in range(3):
            keys(browser, "#param-1-alpha", "\ue014")  # ArrowRight: the metal's roughness, a new shader each
            settle(browser)
        drag(browser, "#lobe3d", 20, 6, 2)
        drag(browser, "#sphere-0", 10, 3, -3)
        settle(browser)
        for css, value in [("#channel", "r"), ("#channel", "luminance"), ("#lit-estimator", "uniform")]:
            select(browser, css, value)
        browser.run("document.getElementById('plot-log').click();")
        settle(browser)
        long_tasks = browser.run("return __long;")
        frames = browser.run("return __frames;")
        events = browser.run("return __events;")
    worst = max(events, key=lambda e: e[1], default=["none", 0])
    if args.verbose:
        for duration, blocking, scripts in sorted(frames, reverse=True)[:8]:
            print(f"long frame {duration:.0f} ms (blocking {blocking:.0f}): {'; '.join(scripts)}")
    print(json.dumps({"long_tasks": len(long_tasks), "longest_task_ms": max(long_tasks, default=0),
                      "events_over_16ms": len(events), "slowest_event": worst[0], "slowest_event_ms": worst[1]}))
    sys.exit(1 if max(worst[1], max(long_tasks, default=0)) > args.limit else 0)


if __name__ == "__main__":
    main()
