"""The designer's files and `design --merge` (docs/designer.md, "Shards" and "What it writes").

Forged shard directories, each derived from a real shard (a small search run first): a member
claiming error 0 for c ^ 3, a NaN lobe claiming 0.001, 81 members, 10^6 members in a 100-MB file,
/dev/zero as design.json, settings the CLI refuses (form "hv", ops ["system"], negative counts,
max_cost 99, a range outside n's, seed -1 and 1.5, zone 2, shard 5 of 2), values of the wrong JSON
type, no JSON, shards of different zones. Each must be refused with exit 2 and one line in specula's
terms naming the file (and the key), or merged with every error measured again (the claim of 0
must not survive). --no-timing holds under --merge. Targets: a subnormal one (c^n*1e-320) designs,
and its files read back (merged, loaded); targets the fits cannot take (1e308*c^n, log(c)*n) are
refused at once. Every models.toml written loads with `specula --models FILE models`, the empty
front's included (a --time spent before any lobe).

Runs are judged as in cli_cases (exit codes, one-line errors, no stray file, a cap); a wrong
result is a fault of kind "wrong".
"""
import csv
import io
import json
import os
import tempfile

from cli_cases import first_line, rmtree
from tally import shown_argv

CAP_S = 120.0       # a design or a merge of the small search
REFUSAL_CAP_S = 20.0
SMALL = ["--range", "n=1:10", "--ops", "fma,mul", "--max-cost", "2", "--no-timing", "-q"]
HUGE_MEMBERS = 1_000_000


class Shards:
    """A folder of shard directories, each holding one design.json."""

    def __init__(self, cli):
        self.top = tempfile.mkdtemp(dir=cli.fixture_dir, prefix="shards-")  # shown as FIXTURES/shards-…
        self.base = None  # the real shard's design.json, as a dict

    def write(self, name, content):
        """content: a dict (dumped as JSON) or str; returns the directory."""
        path = os.path.join(self.top, name)
        os.makedirs(path, exist_ok=True)
        with open(os.path.join(path, "design.json"), "w", encoding="utf-8") as f:
            f.write(content if isinstance(content, str) else json.dumps(content))
        return path

    def forged(self, name, change):
        """A copy of the real shard with change(dict) applied."""
        data = json.loads(json.dumps(self.base))
        change(data)
        return self.write(name, data)


def what_of(cli, args):
    return "specula " + shown_argv([cli.short_path(a) for a in args])


def run(cli, g, work, args, cap, expect, outputs=("d",), ok_codes=(0,)):
    """ok_codes: the exit codes after which `outputs` may be in work (a run that reads an earlier
    run's output leaves it whatever its code)."""
    r = cli.run(args, cap, work)
    cli.judge(g, r, work, cap, expect=expect, outputs=set(outputs), ok_codes=ok_codes)
    return r


def check_refusal(cli, g, r, what, words):
    """An exit-2 message in specula's terms that names each of `words`."""
    if r.code != 2:
        return
    line = r.stderr.decode("utf-8", "replace")
    for bad in ("json.exception", "internal error", "stod", "type_error"):
        if bad in line:
            g.fault("wrong", f"{what}: {bad!r} in the message: {first_line(r.stderr)}")
    for word in words:
        if word not in line:
            g.fault("wrong", f"{what}: the message does not name {cli.short_path(word)!r}: "
                             f"{cli.short_path(first_line(r.stderr, 200))}")


def members_of(work, out="d"):
    with open(os.path.join(work, out, "front.csv"), encoding="utf-8") as f:
        return [row for row in csv.DictReader(io.StringIO(f.read())) if row["kind"] == "member"]


def models_load(cli, g, work, what, out="d"):
    """The models.toml a run wrote loads back (`specula --models FILE models`: exit 0)."""
    r = run(cli, g, work, ["--models", os.path.join(out, "models.toml"), "models"], 20, (0, 2), outputs=(out,),
            ok_codes=(0, 2))
    if r.code != 0:
        g.fault("wrong", f"{what}: its models.toml does not load: {first_line(r.stderr)}")


def merge_case(cli, g, dirs, extra=(), expect=(2,), words=()):
    """design --merge DIRS --out d: refused naming `words`, or merged (then its files load back).
    Returns (run, the merged members or None)."""
    work = cli.workdir()
    try:
        args = ["design", "--merge", *dirs, "--out", "d", "-q", *extra]
        what = what_of(cli, args)
        r = run(cli, g, work, args, CAP_S if 0 in expect else REFUSAL_CAP_S, expect)
        check_refusal(cli, g, r, what, words)
        members = None
        if r.code == 0:
            members = members_of(work)
            models_load(cli, g, work, what)
        return r, members
    finally:
        rmtree(work)


# ----------------------------------------------------------------------------- forgeries

def member(formula, claim, cost=1):
    return {"id": "phong-d1", "formula": formula, "shape": "c ^ 2", "max_abs": claim, "argmax_c": 0.5,
            "argmax_param": 2, "max_rel": claim, "model_cost": cost}


def setting(key, value):
    def change(d):
        d[key] = value
    return change


def member_field(key, value):
    def change(d):
        d["members"][0][key] = value
    return change


def dropped(key):
    def change(d):
        d.pop(key, None)
    return change


# (name, change, words the refusal must hold besides the file)
REFUSED = [
    ("form_hv", setting("form", "hv"), ["'form'", "hv"]),
    ("ops_system", setting("ops", ["system"]), ["'ops'[0]", "system"]),
    ("ops_string", setting("ops", "mul"), ["'ops'"]),
    ("forms_total_negative", setting("forms_total", -1), ["'forms_total'"]),
    ("forms_screened_negative", setting("forms_screened", -5), ["'forms_screened'"]),
    ("max_cost_99", setting("max_cost", 99), ["max_cost"]),
    ("max_cost_text", setting("max_cost", "3"), ["'max_cost'"]),
    ("range_outside", setting("lo", 0), ["range"]),
    ("seed_negative", setting("seed", -1), ["'seed'"]),
    ("seed_fraction", setting("seed", 1.5), ["'seed'"]),
    ("zone_2", setting("zone", 2), ["zone"]),
    ("shard_5_of_2", lambda d: d.update(shard=5, shards=2), ["shard"]),
    ("objective_unknown", setting("objective", "best"), ["objective"]),
    ("target_number", setting("target", 5), ["'target'"]),
    ("params_text", setting("params", "x"), ["'params'"]),
    ("stopped_text", setting("stopped", "no"), ["'stopped'"]),
    ("zone_missing", dropped("zone"), ["'zone'"]),
    ("members_object", setting("members", {}), ["'members'"]),
    ("formula_number", member_field("formula", 3), ["'members'[0].'formula'"]),
    ("formula_malformed", member_field("formula", "c +"), ["'members'[0].'formula'"]),
    ("formula_not_in_c_n", member_field("formula", "c * u"), ["'members'[0].'formula'"]),
    ("max_abs_text", member_field("max_abs", "x"), ["'members'[0].'max_abs'"]),
    ("max_abs_negative", member_field("max_abs", -1), ["'members'[0].'max_abs'"]),
    ("max_abs_null", member_field("max_abs", None), ["'members'[0].'max_abs'"]),
    ("argmax_c_2", member_field("argmax_c", 2), ["'members'[0].'argmax_c'"]),
    ("model_cost_negative", member_field("model_cost", -3), ["'members'[0].'model_cost'"]),
    ("nan_lobe", lambda d: d.update(members=[member("c * sqrt(c - 2)", 0.001)]), ["'members'[0]", "not finite"]),
    ("members_81", lambda d: d.update(members=[member("c ^ 3", 0.5)] * 81), ["'members'", "81"]),
]


def write_huge(shards):
    """A design.json of HUGE_MEMBERS members (about 100 MB), streamed."""
    path = os.path.join(shards.top, "huge")
    os.makedirs(path, exist_ok=True)
    head = dict(shards.base, members=[])
    text = json.dumps(head)
    one = json.dumps(member("c ^ 3", 0))
    with open(os.path.join(path, "design.json"), "w", encoding="utf-8") as f:
        f.write(text[:text.rindex("[]")] + "[")
        for i in range(HUGE_MEMBERS):
            f.write(("," if i else "") + one)
        f.write("]}")
    return path


def special_shards(shards):
    """Shards whose design.json is no JSON, /dev/zero, a directory, or missing."""
    not_json = shards.write("not_json", '{"target": ')
    zero = os.path.join(shards.top, "zero")
    os.makedirs(zero)
    os.symlink("/dev/zero", os.path.join(zero, "design.json"))
    directory = os.path.join(shards.top, "directory")
    os.makedirs(os.path.join(directory, "design.json"))
    missing = os.path.join(shards.top, "missing")
    os.makedirs(missing)
    return [(not_json, ["not JSON"]), (zero, ["larger than"]), (directory, []), (missing, [])]


# ----------------------------------------------------------------------------- the checks

def real_shard(cli, g, shards):
    """The small search whose design.json every forgery starts from."""
    args = ["design", "--target", "phong", *SMALL, "--out", "base"]
    r = run(cli, g, shards.top, args, CAP_S, (0,), outputs=("base",))
    path = os.path.join(shards.top, "base", "design.json")
    if r.code != 0 or not os.path.isfile(path):
        g.fault("wrong", f"specula {shown_argv(args)}: no shard to forge ({first_line(r.stderr)}); the group is skipped")
        return False
    with open(path, encoding="utf-8") as f:
        shards.base = json.load(f)
    return True


def claims_measured_again(cli, g, shards):
    """A member claiming error 0 for c ^ 3 (≈ 0.6 off cⁿ over n ∈ [1, 10]) is measured again."""
    forged = shards.forged("claims_zero", lambda d: d.update(members=[member("c ^ 3", 0)]))
    base = os.path.join(shards.top, "base")
    _, alone = merge_case(cli, g, [forged], expect=(0,))
    for m in alone or []:
        if m["formula"] == "c ^ 3" and not float(m["max_abs_error"] or 0) > 0.3:
            g.fault("wrong", f"merge of a shard claiming 0 for c ^ 3: front.csv says {m['max_abs_error']!r} "
                             "(the claim, not a measurement)")
    _, both = merge_case(cli, g, [base, forged], expect=(0,))
    formulas = {m["formula"] for m in both or []}
    if both is not None and formulas == {"c ^ 3"}:
        g.fault("wrong", "merge of the real shard and the forged one: the forged c ^ 3 is the whole front")


def forgeries_refused(cli, g, shards):
    for name, change, words in REFUSED:
        dir_ = shards.forged(name, change)
        merge_case(cli, g, [dir_], words=[os.path.join(dir_, "design.json")] + words)
    for dir_, words in special_shards(shards):
        merge_case(cli, g, [dir_], words=[os.path.join(dir_, "design.json")] + words)
    other_zone = shards.forged("zone_0.6", setting("zone", 0.6))
    merge_case(cli, g, [os.path.join(shards.top, "base"), other_zone], words=["zone", "0.5", "0.6"])


def huge_refused(cli, g, shards):
    r, _ = merge_case(cli, g, [write_huge(shards)], words=["larger than"])
    if r.rss_mib > 200:
        g.fault("wrong", f"merge of a {HUGE_MEMBERS}-member design.json: max RSS {r.rss_mib:.0f} MiB (a cap reads 1 MiB)")
    rmtree(os.path.join(shards.top, "huge"))


def no_timing_honoured(cli, g, shards):
    _, members = merge_case(cli, g, [os.path.join(shards.top, "base")], extra=["--no-timing"], expect=(0,))
    timed = [m["id"] for m in members or [] if m["ns_per_eval"]]
    if timed:
        g.fault("wrong", f"design --merge --no-timing timed {', '.join(timed)} (ns_per_eval set)")


def design_case(cli, g, target, options=SMALL, expect=(0,)):
    """design --target TARGET (the small search): its files load back and merge (exit 0), or a
    one-line refusal at once."""
    work = cli.workdir()
    try:
        args = ["design", "--target", target, *options, "--out", "d"]
        what = "specula " + shown_argv(args)
        r = run(cli, g, work, args, CAP_S, expect)
        check_refusal(cli, g, r, what, ["target"])
        if r.code == 0:
            models_load(cli, g, work, what)
            again = run(cli, g, work, ["design", "--merge", "d", "--out", "m", "--no-timing", "-q"], CAP_S, (0, 2),
                        outputs=("d", "m"), ok_codes=(0, 2))
            if again.code != 0:
                g.fault("wrong", f"{what}: its design.json does not merge: {first_line(again.stderr)}")
        return r
    finally:
        rmtree(work)


def targets(cli, g):
    # Every operation: a fitted constant is subnormal (before: "internal error: stod"), and the
    # relative errors are not finite (null in design.json, which --merge must read back).
    design_case(cli, g, "lobe: c^n*1e-320", options=["--range", "n=1:10", "--max-cost", "2", "--no-timing", "-q"])
    for target in ("lobe: 1e308*c^n", "lobe: log(c)*n"):
        r = design_case(cli, g, target, expect=(2,))
        if r.code == 2 and r.wall > 5:
            g.fault("slow", f"design --target {target!r}: refused only after {r.wall:.1f} s (before the run, not after)")
    # No lobe finished (the time spent while the 6293 shapes are enumerated): the empty front's files.
    r = design_case(cli, g, "phong", options=["--range", "n=1:10", "--time", "0.001", "--no-timing", "-q"])
    if r.code == 0 and not r.stdout.split(b"\n")[1].startswith(b"references:"):
        g.note = "design --time 0.001 finished a lobe: the empty front was not exercised"


def group_merge(cli):
    g = cli.summary.group("cli: design files and --merge")
    shards = Shards(cli)
    try:
        if not real_shard(cli, g, shards):
            return
        claims_measured_again(cli, g, shards)
        forgeries_refused(cli, g, shards)
        huge_refused(cli, g, shards)
        no_timing_honoured(cli, g, shards)
        targets(cli, g)
    finally:
        rmtree(shards.top)
