"""What the groups observed: per group a row of the table, and every fault named in one line."""
import json
import re
import sys
import time
from collections import Counter

# Fault kinds and the total each one adds to.
KINDS = {
    "crash": "crashes (exit >= 3, or a signal we did not send)",
    "hang": "hangs (past the cap)",
    "500": "status 500s (or other 5xx but 503)",
    "stray": "stray files",
    "body": "bad error bodies",
    "lines": "multi-line errors",
    "slow": "slow answers (/api/models, shutdown)",
    "loss": "user files lost or changed",
    "leak": "child processes left running",
    "wrong": "other wrong results",
}
MAX_PRINTED_FAULTS = 150
MAX_FAULT_CHARS = 240


def shown(value, limit=70):
    """A value as bash would need it ($'..' for control characters), shortened past `limit`."""
    if isinstance(value, bytes):
        value = value.decode("utf-8", "surrogateescape")
    if len(value) > limit:
        value = f"{value[:limit // 2]}…({len(value)} chars)"
    if re.fullmatch(r"[A-Za-z0-9_@%+=:,./-]+", value):
        return value
    if value.isprintable():  # (lone surrogates, i.e. undecodable bytes, are not printable)
        return "'" + value.replace("'", "'\\''") + "'"
    out = []
    for ch in value:
        code = ord(ch)
        if 0xDC80 <= code <= 0xDCFF:
            out.append(f"\\x{code - 0xDC00:02x}")
        elif ch in "\\'":
            out.append("\\" + ch)
        elif ch.isprintable():
            out.append(ch)
        else:
            out.append({"\n": "\\n", "\r": "\\r", "\t": "\\t", "\x1b": "\\e"}.get(ch, f"\\x{code:02x}"))
    return "$'" + "".join(out) + "'"


def shown_argv(argv):
    return " ".join(shown(a) for a in argv)


class Group:
    def __init__(self, name):
        self.name = name
        self.runs = 0
        self.codes = Counter()
        self.worst_wall = 0.0
        self.worst_rss = 0.0
        self.faults = []  # (kind, text)
        self.note = ""
        self.started = time.monotonic()
        self.took = 0.0

    def count(self, label, wall=0.0, rss=0.0):
        self.runs += 1
        self.codes[str(label)] += 1
        self.worst_wall = max(self.worst_wall, wall)
        self.worst_rss = max(self.worst_rss, rss or 0.0)

    def fault(self, kind, text):
        assert kind in KINDS, kind
        self.faults.append((kind, text))

    def codes_text(self):
        def key(item):
            label = item[0]
            return (0, int(label), "") if label.isdigit() else (1, 0, label)
        return " ".join(f"{k}:{v}" for k, v in sorted(self.codes.items(), key=key))


class Summary:
    def __init__(self):
        self.groups = []
        self.models_latency = None   # (seconds, phase) worst GET /api/models
        self.server_exit_s = None
        self.elapsed_s = 0.0
        self.notes = []
        self.measures = {}  # name: text or {what: seconds}, e.g. the worst answer per route to definition objects
        self.started = time.monotonic()

    def group(self, name):
        print(f"[{time.monotonic() - self.started:5.0f} s] {name}", file=sys.stderr, flush=True)
        self.close_group()
        g = Group(name)
        self.groups.append(g)
        return g

    def close_group(self):
        """Ends the timing of the latest group."""
        if self.groups and self.groups[-1].took == 0.0:
            self.groups[-1].took = time.monotonic() - self.groups[-1].started

    def faults(self):
        return [(g.name, kind, text) for g in self.groups for kind, text in g.faults]

    def totals(self):
        counts = Counter(kind for _, kind, _ in self.faults())
        return {kind: counts.get(kind, 0) for kind in KINDS}

    def table(self):
        head = ("group", "runs", "exit codes / HTTP statuses", "worst s", "worst MiB", "faults", "took s")
        rows = [(g.name, str(g.runs), g.codes_text(),
                 f"{g.worst_wall:.2f}", f"{g.worst_rss:.0f}" if g.worst_rss else "-", str(len(g.faults)),
                 f"{g.took:.0f}")
                for g in self.groups]
        widths = [max(len(r[i]) for r in [head] + rows) for i in range(len(head))]
        widths[2] = min(widths[2], 60)

        def line(r):
            cells = []
            for i, cell in enumerate(r):
                align = "<" if i in (0, 2) else ">"
                cells.append(f"{cell:{align}{widths[i]}}")
            return "  ".join(cells).rstrip()
        out = [line(head), "  ".join("-" * w for w in widths)]
        out += [line(r) for r in rows]
        notes = [f"  {g.name}: {g.note}" for g in self.groups if g.note]
        if notes:
            out += ["", "notes:"] + notes
        return "\n".join(out)

    def totals_text(self):
        t = self.totals()
        lat = self.models_latency
        lines = [f"  {KINDS[k]:<50} {v}" for k, v in t.items()]
        lines.append(f"  {'worst GET /api/models latency':<50} "
                     + (f"{lat[0]:.3f} s (during {lat[1]})" if lat else "-"))
        lines.append(f"  {'server exit after SIGTERM':<50} "
                     + (f"{self.server_exit_s:.3f} s" if self.server_exit_s is not None else "-"))
        for name, value in self.measures.items():
            if isinstance(value, dict):
                value = ", ".join(f"{k} {v:.1f} s" if isinstance(v, float) else f"{k} {v}" for k, v in value.items())
            lines.append(f"  {name:<50} {value}")
        lines.append(f"  {'faults in all':<50} {sum(t.values())}")
        lines.append(f"  {'run time':<50} {self.elapsed_s:.0f} s")
        return "\n".join(lines)

    def faults_text(self, per_kind=12):
        """One line per fault, at most `per_kind` per group and kind (then a count of the rest)."""
        out, shown_count, hidden = [], Counter(), Counter()
        for name, kind, text in self.faults():
            if shown_count[name, kind] >= per_kind or len(out) >= MAX_PRINTED_FAULTS:
                hidden[name, kind] += 1
                continue
            shown_count[name, kind] += 1
            line = f"FAULT {name} [{kind}] {text}"
            out.append(line if len(line) <= MAX_FAULT_CHARS else line[:MAX_FAULT_CHARS - 1] + "…")
        for (name, kind), n in hidden.items():
            out.append(f"FAULT {name} [{kind}] … and {n} more like these (all of them in --json)")
        return "\n".join(out)

    def to_json(self):
        lat = self.models_latency
        return json.dumps({
            "groups": [{"name": g.name, "note": g.note, "runs": g.runs, "codes": dict(g.codes),
                        "worst_wall_s": round(g.worst_wall, 3), "worst_rss_mib": round(g.worst_rss, 1),
                        "took_s": round(g.took, 1),
                        "faults": len(g.faults)} for g in self.groups],
            "totals": self.totals(),
            "worst_models_latency_s": round(lat[0], 4) if lat else None,
            "worst_models_latency_phase": lat[1] if lat else None,
            "server_exit_s": None if self.server_exit_s is None else round(self.server_exit_s, 4),
            "elapsed_s": round(self.elapsed_s, 1),
            "notes": self.notes,
            "measures": self.measures,
            "faults": [{"group": n, "kind": k, "what": t} for n, k, t in self.faults()],
        }, indent=2, ensure_ascii=True)
