"""User models for the hostile test: model files (TOML) and inline definitions, valid, hostile
(text that would leave an export's comments, odd ids) and heavy (formulas at the length limit,
a lobe that oscillates under quadrature), and seeded mutations of a model file and of a formula.
"""
import os
import random

# Text that must stay inside the one-line comments of every export: newlines, a lone CR, a
# comment-ending backslash or trigraph, a block comment's end, a NUL, other line separators and
# non-ASCII letters. Each injected line holds the word "pwned" (compilers.MARKER_WORD).
HOSTILE_TEXTS = [
    "innocent\n#error pwned-nl\nstatic int pwned = 1; //",
    "innocent\r#error pwned-cr\rstatic int pwned = 2; //",
    "ends in a backslash, which continues a // comment \\",
    "ends in a trigraph, a backslash in C++14 ??/",
    "closes a block comment */ static int pwned = 3; /* and opens one",
    "tabs\tform feed\x0c vertical tab\x0b escape\x1b[2J #error pwned-controls",
    "non-ASCII: \u00e9\u00fc \u03c0 \u2028 \u0085 \u202e #error pwned-unicode",
    "\n::end shader\n::begin parameters\nfloat pwned 0 1 0\n",
]


def toml_string(text):
    """A TOML basic string holding `text` exactly (escapes for quotes, backslashes, controls)."""
    out = []
    for ch in text:
        code = ord(ch)
        if ch == '"':
            out.append('\\"')
        elif ch == "\\":
            out.append("\\\\")
        elif code < 0x20 or code == 0x7F:
            out.append({"\n": "\\n", "\r": "\\r", "\t": "\\t", "\b": "\\b", "\f": "\\f"}.get(ch, f"\\u{code:04X}"))
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value) if value == value and abs(value) != float("inf") else ("nan" if value != value else
                                                                                    ("inf" if value > 0 else "-inf"))
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    return toml_string(value)


def model_toml(model):
    """One [[model]] table from a dict like a definition object (params as {name: {key: value}})."""
    lines = ["[[model]]"]
    for key, value in model.items():
        if key != "params":
            lines.append(f"{key} = {toml_value(value)}")
    for name, param in model.get("params", {}).items():
        lines.append(f"[model.params.{name}]")
        lines += [f"{key} = {toml_value(value)}" for key, value in param.items()]
    return "\n".join(lines) + "\n"


N_PARAM = {"n": {"default": 20, "min": 0, "min_exclusive": True, "max": 1e6, "meaning": "specular exponent"}}
RHO_PARAM = {"rho": {"default": 0.8, "min": 0, "max": 1, "meaning": "albedo"}}

LONG_LOBE = "c" + "*c" * 2047            # 4095 characters, inside the 4096 limit
LONG_BRDF = "nl" + "*nl" * 1363 + "/pi"   # 4094 characters
OSCILLATING = "max(0, sin(1000*n*acos(c)))"
DEEP_LOBE = "(" * 60 + "c" + ")" * 60 + "^n"


def hostile_models():
    """Lobes and a BRDF whose every text (name, source, summary, a parameter's meaning) is hostile,
    rotated so that each field meets each text; formulas and lets carry newlines and CRs."""
    fields = ["name", "source", "summary", "meaning"]
    models = []
    for i in range(len(HOSTILE_TEXTS)):
        texts = {f: HOSTILE_TEXTS[(i + k) % len(HOSTILE_TEXTS)] for k, f in enumerate(fields)}
        brdf = i % 4 == 3
        param = dict(RHO_PARAM["rho"] if brdf else N_PARAM["n"])
        param["meaning"] = texts["meaning"]
        m = {"id": f"hostile-{i}", "name": texts["name"], "source": texts["source"], "summary": texts["summary"],
             "kind": "brdf" if brdf else "lobe"}
        if brdf:
            m["let"] = ["q = rho\n/pi", "w = q*\rnl"]
            m["brdf"] = "w\n*nv^0\r+ 0"
            m["params"] = {"rho": param}
        else:
            m["form"] = "nh" if i % 2 else "rv"
            m["let"] = ["d = 1\n- c"]
            m["lobe"] = "max(0,\n1 - n*d/4)\r^4" if i % 3 == 0 else "(1 - d)\n^n"
            m["normalization"] = ["quadrature", "(n\n+ 2)/(2*pi)", "none"][i % 3]
            m["params"] = {"n": param}
        models.append(m)
    return models


# Ids at the edge of the rules: each becomes a C++ namespace and a GLSL function name.
ODD_IDS = ["9lives", "x__y", "_lead", "trail_", "a.b.c", "class", "int", "main", "namespace", "specula_brdf",
           "gl_x", "a-b", "a_b", "x" * 64, "-x", "e", "pi"]


def odd_id_models():
    models = []
    for i, ident in enumerate(ODD_IDS):
        models.append({"id": ident, "name": f"odd id {i}", "kind": "lobe", "form": "rv",
                       "lobe": "c^n", "normalization": "none", "params": N_PARAM})
    return models


def heavy_models():
    """Formulas at the limits: 4095 characters, 60 deep, an oscillating lobe normalized by quadrature."""
    return [
        {"id": "long-lobe", "name": "4095 characters", "kind": "lobe", "form": "rv", "lobe": LONG_LOBE,
         "normalization": "quadrature"},
        {"id": "long-brdf", "name": "4095 characters", "kind": "brdf", "brdf": LONG_BRDF},
        {"id": "oscillating", "name": "sin(1000 n acos c)", "kind": "lobe", "form": "rv", "lobe": OSCILLATING,
         "normalization": "quadrature", "params": {"n": {"default": 20, "min": 1, "max": 1000}}},
        {"id": "deep", "name": "60 deep", "kind": "lobe", "form": "nh", "lobe": DEEP_LOBE,
         "normalization": "quadrature", "params": N_PARAM},
    ]


# A directory whose name would leave a comment: exports name the model file they come from.
HOSTILE_DIR = "dir\n#error pwned-path\nstatic int pwned = 4; //"


def write_model_files(top, repo):
    """The model files, by name; returns {name: path}: hostile.toml (and a copy of it in HOSTILE_DIR,
    'hostile-path'), heavy.toml, one file per odd id ('odd:ID'), the repository's builtin-copies.toml."""
    os.makedirs(os.path.join(top, HOSTILE_DIR), exist_ok=True)
    files = {"hostile": hostile_models(), "heavy": heavy_models(),
             os.path.join(HOSTILE_DIR, "hostile"): hostile_models()[:2]}
    files.update({f"odd:{m['id']}": [m] for m in odd_id_models()})
    paths = {}
    for name, models in files.items():
        path = os.path.join(top, (name if not name.startswith("odd:") else f"odd{len(paths)}") + ".toml")
        paths["hostile-path" if name.startswith(HOSTILE_DIR) else name] = path
        with open(path, "w", encoding="utf-8", newline="") as f:
            f.write("\n".join(model_toml(m) for m in models))
    paths["copies"] = os.path.join(repo, "examples", "models", "builtin-copies.toml")
    return paths


# Inline models: (definition, -p arguments).
INLINE = [
    ("lobe: max(0, 1 - n*(1-c)/4)^4", ["-p", "n=20"]),
    ("brdf: rho/pi", ["-p", "rho=0.5"]),
    ("lobe: c\n^n", []),
    ("lobe: c\r^n", []),
    ("brdf: nl*nv\n*rho", []),
    ("lobe: exp(-n*u)", ["-p", "n=1e6"]),
]
INLINE_HEAVY = [("lobe: " + LONG_LOBE, []), ("brdf: " + LONG_BRDF, []), ("lobe: " + OSCILLATING, ["-p", "n=20"])]


# ----------------------------------------------------------------------------- mutations

BASE_FILE = model_toml({"id": "mut-lobe", "name": "a lobe", "source": "hostile", "summary": "to be mutated",
                        "kind": "lobe", "form": "rv", "let": ["d = 1 - c"], "lobe": "max(0, 1 - n*d/4)^4",
                        "lobe_u": "max(0, 1 - n*expm1(-u)*(-1)/4)^4", "normalization": "quadrature",
                        "params": N_PARAM}) + "\n" + model_toml(
    {"id": "mut-brdf", "name": "a BRDF", "kind": "brdf", "let": ["D = rho/pi"], "brdf": "D*max(0, nh)",
     "params": RHO_PARAM})

VALUES = ['""', '"x"', "nan", "inf", "-inf", "1e999", "-1e308", "0", "-0", "1e-320", "true", "[]", "{}", "[1, 2]",
          '"nan"', "2147483648", "9223372036854775807", "0x10", "1_000", "'lit'", '"""multi\nline"""',
          toml_string("x" * 5000), toml_string("c" + "*c" * 2048), toml_string("(" * 70 + "c" + ")" * 70),
          toml_string("c^n^n^n^n^n^n^n^n^n^n^n^n^n^n^n^n^n^n^n^n"), toml_string("sqrt(-1)"), toml_string("1/0"),
          toml_string("exp(1000)"), toml_string("0*c"), toml_string("-c"), toml_string("k*c"),
          toml_string("max(c)"), toml_string("pow(c, n, 1)"), toml_string("c^"), toml_string("asin(2)"),
          toml_string("log1p(-1)"), toml_string("expm1(1000)"), toml_string("phong"), toml_string("ggx+ms"),
          toml_string("lobe"), toml_string("brdf"), toml_string("nh"), toml_string("quadrature"),
          toml_string("none"), toml_string("n - n"), toml_string("-1"), toml_string("a" * 65),
          toml_string("bad id!"), toml_string(HOSTILE_TEXTS[0]), toml_string("\u00e9"), '"\\ud800"', '"\\u0000"',
          '["a = b", "b = a"]', '["pi = 1"]', '["sin = c"]', '["_x = c"]', '["a__b = c"]', '["c = 1"]',
          '[1, "x"]', "{ default = 1 }", "1979-05-27T07:32:00Z"]
INSERTS = ["\x00", "\xff", "\udcff", '"', "'", "[", "]", "[[", "]]", "{", "}", "=", "\n", "\r", "\r\n", "#", "\\", ",", ".",
           " ", "\t", "\ufeff", "[[model]]\n", "[model.params.x]\n", "[model.params]\n", "x = 1\n",
           "[model]\n", "[[model.params.n]]\n", "a.b.c.d = 1\n"]


def mutated_file(rng, base=BASE_FILE):
    """One seeded mutation of a valid model file (as bytes)."""
    lines = base.split("\n")
    for _ in range(rng.choices([1, 2, 3], [60, 30, 10])[0]):
        roll = rng.random()
        lines = lines or [""]
        i = rng.randrange(len(lines))
        if roll < 0.45 and "=" in lines[i]:
            lines[i] = lines[i].split("=", 1)[0] + "= " + rng.choice(VALUES)
        elif roll < 0.55:
            del lines[i]
        elif roll < 0.65:
            lines.insert(i, lines[rng.randrange(len(lines))])
        elif roll < 0.85:
            at = rng.randrange(len(lines[i]) + 1)
            lines[i] = lines[i][:at] + rng.choice(INSERTS) + lines[i][at:]
        elif roll < 0.92 and "=" in lines[i]:
            key = rng.choice(["from", "ID", "id ", "params", "let", "kind", "lobe", "min_exclusive", "x.y", '"q"'])
            lines[i] = key + " = " + lines[i].split("=", 1)[1]
        else:
            lines = lines[:rng.randrange(len(lines))]
    return "\n".join(lines).encode("utf-8", "surrogatepass")


def structural_files():
    """Whole files that are wrong in shape or size: (name, bytes)."""
    many = "".join(model_toml({"id": f"m{i}", "name": "m", "kind": "lobe", "form": "rv", "lobe": "c",
                               "normalization": "none"}) for i in range(1001))
    params = {f"p{i}": {"default": 1, "min": 0, "max": 2} for i in range(65)}
    return [
        ("empty.toml", b""),
        ("no-models.toml", b"x = 1\n"),
        ("model-not-array.toml", b"[model]\nid = \"x\"\n"),
        ("models-1001.toml", many.encode()),
        ("params-65.toml", model_toml({"id": "p65", "name": "p", "kind": "lobe", "form": "rv", "lobe": "c",
                                       "normalization": "none", "params": params}).encode()),
        ("duplicate-id.toml", (model_toml(heavy_models()[1]) * 2).encode()),
        ("builtin-id.toml", model_toml({"id": "phong", "name": "p", "kind": "brdf", "brdf": "nl"}).encode()),
        ("ms-id.toml", model_toml({"id": "x+ms", "name": "p", "kind": "brdf", "brdf": "nl"}).encode()),
        ("deep-tables.toml", ("a" + ".a" * 5000 + " = 1\n").encode()),
        ("deep-arrays.toml", ("x = " + "[" * 5000 + "]" * 5000 + "\n").encode()),
        ("deep-inline.toml", ("x = " + "{a = " * 3000 + "1" + "}" * 3000 + "\n").encode()),
        ("long-line.toml", ("# " + "x" * 1_000_000 + "\n").encode() + BASE_FILE.encode()),
        ("bom-crlf.toml", b"\xef\xbb\xbf" + BASE_FILE.replace("\n", "\r\n").encode()),
        ("latin1.toml", BASE_FILE.replace("a lobe", "\xe9t\xe9").encode("latin-1")),
        ("binary.toml", bytes(random.Random(7).randrange(256) for _ in range(4096))),
        ("nul.toml", BASE_FILE.encode().replace(b"kind", b"ki\x00nd", 1)),
        ("nul-in-name.toml", model_toml({"id": "nul", "name": "a\x00\n#error pwned-nul", "kind": "brdf",
                                         "brdf": "nl"}).encode()),
        ("huge-string.toml", model_toml({"id": "h", "name": "x" * 2_000_000, "kind": "brdf", "brdf": "nl"}).encode()),
    ]


FORMULA_TOKENS = ["c", "u", "n", "nl", "nv", "nh", "vh", "lv", "rho", "pi", "e", "+", "-", "*", "/", "^", "(", ")",
                  "max(", "min(", "pow(", "log(", "log2(", "exp(", "sqrt(", "abs(", "sin(", "cos(", "acos(",
                  "asin(", "expm1(", "log1p(", ",", "0", "1", "2", "0.5", "1e308", "1e-308", "1e999", "nan",
                  "inf", " ", "\n", "\t", "\r", "\x0b", "\u00e9", ".", "..", "1.2.3", "_x", "a__b", "#", ";", "'"]


def mutated_formula(rng):
    """A random token string: 'lobe: …' or 'brdf: …'."""
    kind = rng.choice(["lobe", "lobe", "brdf"])
    tokens = [rng.choice(FORMULA_TOKENS) for _ in range(rng.randint(1, 14))]
    return f"{kind}: " + "".join(tokens)
