"""Garbage for the CLI's options: a common pool, one per kind of option, and each command's options.

Every value here is either invalid or cheap when valid: a command given one of them must end
within its cap. (Valid but expensive values, such as --size 16384x16384, are left out on purpose:
they are documented to take long.)
"""

COMMON = [
    "", " ", "nan", "NaN", "-nan", "inf", "-inf", "-1", "0", "-0", "1e308", "-1e308", "1e-400",
    "1e999", "2147483647", "2147483648", "-2147483649", "9223372036854775808", "18446744073709551616",
    "1:1e7", "1:", ":1", ":", "a:b@c", "1:2@", "0:1@0", "0:1@-5", "1:1000@50:cubic", "1,,2", ",",
    "0x10", "1e", "1.2.3", "--", "-", "1 2", "1\n2", "1\r", "\x1b[2J\x1b[31m", "\x07\x08", "é",
    "\udcff\udcfe", "%s%n%x", "{}", "$(id)", "`id`", "A" * 5000, "100000x100000", "paper50",
    "paper", "true", "[1,2]", "\u202e1", "0:1:1e-300", "1:1e308@3",
]

MODELS = ["log", "ggx", "nope", "LOG", "log ", " log", "log\n", "log\r\x1b[2J", "", "phong,ggx",
          "../log", "log-normalized\udcff", "a" * 300, "lambert", "cook-torrance-1982",
          # inline models, M+ms, model-file ids (valid only with --models)
          "lobe: c^n", "brdf: rho/pi", "lobe: c\n^n", "lobe: ", "brdf:", "lobe: c^", "lobe: k*c", "brdf: nl/0",
          "lobe: " + "c*" * 2048 + "c", "lobe:c", "LOBE: c", "brdf: sqrt(-1)", "phong+ms",
          "nope+ms", "ggx+ms+ms", "+ms", "my-log", "hostile-0"]
PARAMS = ["n=nan", "n=inf", "n=-1", "n=0", "n=1e308", "n=1e9", "n=1e10", "n=", "=1", "n", "n=1=2",
          "n==1", "alpha=0", "alpha=nan", "alpha=2", "f0=-1", "nope=1", "n=1e-400", "n=1:7", "n=\n1",
          "n=0x10", "rho=1e308", "n=1e-3", "m=0"]
FORMS = ["rv", "nh", "RV", "xx", "", "rv\n"]
FORMATS = ["csv", "json", "xml", "", "JSON", "table"]
ROUNDS = ["-1", "18", "17", "nan", "1e308", "2147483647", "x", "0"]
RANGES = ["1:1e7", "1:1e9", "1:1000000000@1000000000", "0", "-1", "nan", "1:7", "paper50", "paper51",
          "1e10", "0.5,1:4", "1:1000@0:log", "1:0:1", "1:2:0", "1:2:-1", "1:1000@50:log", "0:1@1e7",
          "1:1e308", "1,nan", "1,,", "1e-400"]
COSINES = ["0:1@5", "1:-1@3", "2", "-2", "0:1@10000001", "0:1@20000000", "0.9:1@5:log", "0:1@5:log",
           "1,", ",1", "0:1:0", "0:1:-0.1", "0:1:1e-300", "-1:1@3", "1e-400", "0:1@1e307"]
ANGLES = ["0:90:10", "0:90:1e-300", "-1", "91", "90", "nan", "0:1e308", "89.9999999", "0:89@10001",
          "1:1e7", "0:89:1e-9", "360"]
NUMBERS = ["nan", "inf", "-inf", "1e308", "-1e308", "x", "0", "-1", "1e-400", "1000"]
SEEDS = ["-1", "18446744073709551616", "nan", "x", "1e308", "0", "18446744073709551615"]
OUTS = ["", "out.csv", ".", "/dev/full", "no/such/dir/x", "a\nb", "-", "--", "x.tmp", " ",
        "\x1b[2J", "/dev/null", "out.csv/"]
IMAGES = ["y.png", "y.exr", "y.bmp", "y", ".png", "", ".", "a\nb.png", "/dev/full", "no/such/y.png",
          "y.PNG", "y.png/", "y.exr.png"]
SIZES = ["100000x100000", "0x0", "-1x-1", "1x", "x1", "16385x1", "2147483647x2147483647", "1e3x1e3",
         "3x3x3", "32X32", " 32x32", "32x32 ", "1x1", "4294967297x1", "x", "", "0x32", "32x-0"]
LIGHTS = ["dir:", "dir:0,0,0", "dir:nan,nan,nan", "point:0,0,0", "point:0,0,1e308",
          "dir:1,1,1:1,1,1:1e308", "dir:1,1,1:-1,-1,-1", "spot:1,1,1", "dir:1,1", "dir:1,1,1:1,1",
          "point:1,1,1:1,1,1:inf", "dir:1,1,1:1,1,1:1:1", ":", "dir:1e-320,0,0"]
COLOURS = ["1,1", "nan,0,0", "-1,-1,-1", "1e308,1e308,1e308", "1,1,1,1", "", "x", "inf,inf,inf"]

MODEL_OPTS = {"-m": MODELS, "--model": MODELS, "-p": PARAMS, "--param": PARAMS, "--form": FORMS}
MU = ["0:1@5", "1e-10", "0.5:1@1025", "1,0.5", "nan", "2", "0.5,0.5", "", "0.25:1@4", "1e-9", "-1", "1:1e7"]
SWEEPS = ["alpha=0.05:1@1025", "alpha=", "nope=0:1@3", "alpha=1:0.05@3", "alpha=nan", "alpha=0.1,0.1", "=1",
          "alpha=0.05:1@4", "f0=0:1@3", "alpha=0:1@3", "alpha", "alpha=1e308"]
SAMPLING_COUNTS = ["999", "100000001", "0", "-1", "nan", "1e308", "x", "1000", "18446744073709551616"]
OUTPUT_OPTS = {"--format": FORMATS, "--round": ROUNDS, "-o": OUTS, "--out": OUTS}


def _merge(*dicts):
    out = {}
    for d in dicts:
        out.update(d)
    return out


def commands(fixtures):
    """{command: (base argv, {option: pool}, [flags])}; base argvs are cheap valid invocations.
    A key "check --sampling" is the command check with --sampling in its base."""
    csv = [fixtures.get(k, k) for k in ("D.csv", "ragged.csv", "text.csv", "empty.csv", "nan.csv")]
    csv += ["", "/dev/null", "nonexistent.csv"]
    model_files = [fixtures.get(k, k) for k in ("copies.toml", "hostile.toml", "heavy.toml")]
    model_files += ["", "/dev/zero", "nonexistent.toml", fixtures.get("a_directory", ".")]
    with_files = dict(MODEL_OPTS, **{"--models": model_files})
    specs = {
        "lut": (["-m", "ggx", "--mu", "0.5,1", "-q"],
                _merge(with_files, {"--sweep": SWEEPS, "--mu": MU, "--round": ROUNDS, "-o": OUTS + IMAGES,
                                    "--out": OUTS + IMAGES,
                                    "--format": ["csv", "json", "exr", "png16", "cpp", "glsl", "x", "", "PNG16"]}),
                ["--average", "--quiet"]),
        "sample": (["-m", "ggx", "--count", "10"],
                   _merge(with_files, {"--coef": NUMBERS, "--theta-i": NUMBERS + ["90", "89.999999", "0:10"],
                                       "--count": ["0", "1000001", "-1", "nan", "x", "1"], "-n": ["0", "-1"],
                                       "--seed": SEEDS, "-o": OUTS, "--out": OUTS}), []),
        "check --sampling": (["--sampling", "-m", "ggx", "--samples", "1000", "--theta-i", "30"],
                             _merge(with_files, {"--coef": NUMBERS, "--samples": SAMPLING_COUNTS,
                                                 "--theta-i": ANGLES + ["0:89@21", "0,30,60", "90"],
                                                 "--bins": ["3", "129", "0", "nan", "x", "4", "128"],
                                                 "-o": IMAGES, "--out": IMAGES}), ["--json"]),
        "render --env": (["-m", "ggx", "--env", "white", "--samples", "2", "--size", "16x16", "-o", "y.exr"],
                         _merge(with_files, {"--env": ["white", "", "nope.exr", "/dev/zero", "WHITE", "black",
                                                       fixtures.get("binary.csv", "x.png")],
                                             "--samples": ["0", "65537", "-1", "nan", "x", "1"], "--seed": SEEDS,
                                             "--size": SIZES, "--light": LIGHTS, "-o": IMAGES, "--out": IMAGES}), []),
        "models": ([], {"-o": OUTS, "--out": OUTS}, ["--json"]),
        "eval": (["-m", "log", "--cos", "0:1@5"],
                 _merge(MODEL_OPTS, OUTPUT_OPTS, {"--coef": NUMBERS, "--cos": COSINES, "-c": COSINES,
                                                  "--theta-i": NUMBERS + ["91"], "--theta-o": ANGLES,
                                                  "--phi-o": NUMBERS}), ["--lobe"]),
        "normalize": (["-m", "log", "--n", "1:3"],
                      _merge(MODEL_OPTS, OUTPUT_OPTS, {"--n": RANGES, "--compare": MODELS,
                                                       "--method": ["auto", "exact", "both", "x", ""],
                                                       "--condition": ["normal", "strict", "x"],
                                                       "--step": ["0", "0.001", "46", "nan", "-1", "inf"]}), []),
        "albedo": (["-m", "log-normalized", "--theta", "0,45"],
                   _merge(MODEL_OPTS, OUTPUT_OPTS, {"--coef": NUMBERS, "--theta": ANGLES, "-t": ANGLES,
                                                    "--method": ["cubature", "monte-carlo", "mc", ""],
                                                    "--samples": ["0", "-1", "1000000001", "nan", "1e308",
                                                                  "18446744073709551616", "x"],
                                                    "--seed": SEEDS}), []),
        "check": (["-m", "phong", "--n", "1,20", "--pairs", "100", "--step", "5"],
                  _merge(MODEL_OPTS, {"--coef": NUMBERS, "--n": RANGES,
                                      "--sweep": ["n=1:1e7", "alpha=nan", "n=", "=1:2", "n", "nope=1:2",
                                                  "alpha=0.05:0.5@4", "n=1:3"],
                                      "--pairs": ["0", "-1", "100000000", "10000001", "nan", "2147483647"],
                                      "--seed": SEEDS, "--step": ["0", "0.001", "46", "nan", "-1", "inf", "1e-308"],
                                      "--grazing": ["90", "89.9999999", "nan", "-1", "1:1e7", "0:89:1e-9", ""],
                                      "-o": OUTS, "--out": OUTS}), ["--json"]),
        "error": (["-m", "log", "--n", "1:3"],
                  _merge({k: v for k, v in MODEL_OPTS.items() if k != "--form"}, OUTPUT_OPTS,
                         {"--reference": ["phong", "nope", "ggx", "", "log"], "-r": MODELS, "--n": RANGES,
                          "--zone": ["0", "1", "nan", "-1", "1e-308", "2"]}), []),
        "fit": (["--data", fixtures["D.csv"], "--target", "coef", "--time", "1", "--generations", "20", "-q"],
                {"--data": csv, "--target": ["coef", "n", "nope", "", "coef,n", "\n"],
                 "--vars": ["n", "coef", "n,n", "", ",", "nope", "n,coef"],
                 "--ops": ["+", "+,+", "^", "nope", "", ",", "sin\n",
                           "+,-,*,/,^,neg,pow,min,max,log,log2,exp,sqrt,abs,sin,cos,acos"],
                 "--constants": ["fitted", "integer", "none", "x", ""],
                 "--max-size": ["0", "101", "1", "100", "-1", "nan", "2147483647"],
                 "--size-weights": ["turingbot", "/=2,exp=3", "/=nan", "/=-1", "x=2", "/=1e308", "/=", "="],
                 "--metric": ["rms", "r2", "max-abs", "x", ""], "--split": ["random", "last", "x"],
                 "--test-fraction": ["1", "0.99", "-0.1", "nan", "inf", "0.5"], "--seed": SEEDS,
                 "--time": ["0", "-1", "nan", "inf", "1e6", "1e-9", "1e-300", "1000001"],
                 "--generations": ["-1", "0", "nan", "1e308", "x"], "--evaluations": ["-1", "0", "nan", "x", "5"],
                 "--target-error": ["nan", "-inf", "inf", "1e308", "-1"],
                 "--threads": ["1025", "-1", "0", "100000", "64"], "--islands": ["0", "65", "2147483647", "64"],
                 "--population": ["3", "20001", "1000000", "-4"], "--enumerate-size": ["31", "2147483647", "-1", "6"],
                 "--choose": ["knee", "best", "x", ""], "--choose-factor": ["0.5", "1e7", "nan", "inf"],
                 "--format": ["table", "json", "x"], "--emit": ["cpp", "glsl", "latex", "python", "rust", ""],
                 "--out": OUTS}, []),
        "render": (["-m", "phong", "--size", "32x32", "-o", "y.png"],
                   _merge(MODEL_OPTS, {"--coef": NUMBERS, "--size": SIZES, "--light": LIGHTS,
                                       "--diffuse": COLOURS, "--specular": COLOURS, "--ambient": COLOURS,
                                       "--exposure": NUMBERS, "--tonemap": ["aces", "x", ""],
                                       "--exr-pixel": ["half", "float", "double"], "--backend": ["cpu", "vulkan", "GL"],
                                       "--scene": ["", "nope.obj", "sphere ", "SPHERE"], "-o": IMAGES,
                                       "--out": IMAGES}), ["--verbose"]),
        "compare": (["--size", "32x32", "-o", "c.png", "-q"],
                    {"--models": ["", ",", "log,", "nope", ",".join(["log"] * 40), "ggx,lambert", "log\n"],
                     "-p": PARAMS, "--form": FORMS, "--diff": ["nope", "", "ggx", "log\n"],
                     "--size": SIZES, "--light": LIGHTS, "--diffuse": COLOURS, "--specular": COLOURS,
                     "--ambient": COLOURS, "--exposure": NUMBERS, "--tonemap": ["aces", "x"],
                     "--scale": ["0", "-1", "nan", "inf", "1e308"], "--backend": ["cpu", "x"],
                     "-o": IMAGES, "--out": IMAGES}, []),
        "glsl": (["-m", "ggx"],
                 _merge(MODEL_OPTS, {"--coef": NUMBERS,
                                     "--dialect": ["glsl330", "gles300", "webgl2", "hlsl", "", "glsl330\n"],
                                     "-o": OUTS, "--out": OUTS}), ["--shader", "--vertex"]),
        "export": (["-m", "ggx", "--format", "cpp"],
                   _merge(MODEL_OPTS, {"--coef": NUMBERS,
                                       "--format": ["hlsl", "msl", "brdf", "cpp", "glsl", "", "cpp\n"],
                                       "-o": OUTS, "--out": OUTS}), []),
        "design": (["--range", "n=1:100", "--ops", "fma,mul", "--max-cost", "2", "--time", "5", "--no-timing",
                    "--out", "d", "-q"],
                   {"--target": MODELS, "-p": PARAMS, "--form": FORMS,
                    "--range": ["n=1:1e7", "n=0:1", "n=1:1", "n=2:1", "n=1:1e13", "n=nan:2", "nope=1:2", "n=",
                                "=1:2", "n=1", "alpha=0.1:0.5", "n=1:10", "n=1:2:3"],
                    "--objective": ["max-abs", "max-rel", "both", "x", "", "MAX-ABS"],
                    "--zone": ["0", "1", "nan", "-1", "0.5", "1e-300"],
                    "--ops": ["all", "", "nope", "fma,mul", "exp\n", "fma,fma", ",", "fma,"],
                    "--max-cost": ["0", "25", "-1", "nan", "x", "24", "1", "3"],
                    "--max-forms": ["0", "1000001", "-1", "nan", "x", "10", "1"],
                    "--time": ["0", "-1", "nan", "inf", "86401", "1e-9", "x", "0.5"],
                    "--threads": ["1025", "-1", "0", "100000", "2"], "--seed": SEEDS,
                    "--shard": ["0/0", "1/1", "-1/2", "2/1", "0/10001", "x", "1/2", "0/1", "", "1/", "/2", "0/2/3"],
                    "--merge": ["", "nope", ".", "/dev/null", "d"], "--out": OUTS}, ["--no-timing", "--quiet"]),
        "bench": (["--quick"], {"--n": ["0", "1e-4", "1e10", "nan", "inf", "-1", "x"],
                                "--format": ["table", "json", "x", ""]}, []),
    }
    for _, options, _ in specs.values():  # a model file wherever a model is taken (--models may follow the command)
        if "-m" in options or "--models" in options:
            options.setdefault("--models", model_files)
    specs["models"][1]["--models"] = model_files
    return specs


# Commands whose valid runs take minutes or never end: only invocations that fail parsing.
REPORT_CASES = [["--quick", "--bogus"], ["--quick", "extra"], ["--out"], ["--quick=nan"], ["--quick", "--out"],
                ["-o"], ["--quick", "-o"], ["--quick", "--out", "R", "--out"]]
SERVE_CASES = [["--port", "-1"], ["--port", "65536"], ["--port", "nan"], ["--port", "1e308"],
               ["--port", "2147483647"], ["--port", ""], ["--host", "not an address", "--port", "0"],
               ["--host", "127.0.0.1\n", "--port", "0"], ["--host", "256.256.256.256", "--port", "0"],
               ["--host", "127.0.0.1", "--port", "0", "--bogus"], ["--port", "0", "extra"]]
