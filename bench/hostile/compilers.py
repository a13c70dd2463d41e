"""The exports compiled: g++ for the C++ headers and (against a shim of Metal's types) the Metal
functions, glslangValidator for GLSL, HLSL and BRDF Explorer files inside its shader templates —
as tests/exports/ and tests/glsl/ compile them — and a scan for injected lines.

Every check returns None when the text is good, else one line saying why. Many texts are compiled
in one g++ run (one translation unit each, so that each error names its own file) to keep the
hostile run short; a compiler that is missing makes its checks return None and is noted once.
"""
import os
import re
import shutil
import subprocess
import tempfile

CXX = shutil.which("g++") or shutil.which("c++")
GLSLANG = shutil.which("glslangValidator")
CAP_S = 120  # one compiler run

# The hostile model texts carry the word "pwned" on lines of their own ("innocent\n#error pwned\n
# static int pwned = 1; //"): in an export, a line that starts with "#error" or holds the word
# before any "//" is text that left its comment.
MARKER_WORD = "pwned"
LINE_ENDS = re.compile(r"\r\n|\r|\n")  # where compilers end a line (Python's splitlines has more)


def missing():
    """The compilers not found, as words for a note."""
    return [name for name, path in (("g++", CXX), ("glslangValidator", GLSLANG)) if not path]


def skipped_formats():
    """The formats whose compiler is missing (their checks pass without looking)."""
    return (set() if CXX else {"cpp", "msl"}) | (set() if GLSLANG else {"hlsl", "brdf", "glsl", "frag", "vert"})


def injected_lines(text, fmt=""):
    """Lines that start with "#error" or hold the marker word outside a // comment (and, in a
    .brdf file, outside a '#' comment line): the first few, shown."""
    bad = []
    for number, line in enumerate(LINE_ENDS.split(text), 1):
        stripped = line.strip()
        comment_line = fmt == "brdf" and stripped.startswith("#") and not stripped.startswith("#error")
        if stripped.startswith("#error") or (MARKER_WORD in line.split("//", 1)[0] and not comment_line):
            bad.append(f"line {number}: {stripped[:70]!r}")
    return bad[:3]


def _run(argv, cwd):
    try:
        p = subprocess.run(argv, cwd=cwd, capture_output=True, timeout=CAP_S)
        return p.returncode, (p.stdout + p.stderr).decode("utf-8", "replace")
    except subprocess.TimeoutExpired:
        return None, f"{os.path.basename(argv[0])} ran past {CAP_S} s"


def _first_error(log, word=None):
    lines = log.splitlines()
    for line in lines:
        if ("error" in line or "ERROR" in line) and (word is None or word in line):
            return line.strip()[:200]
    return lines[0].strip()[:200] if lines else "(no output)"


def _gxx(files, tu, flags, workdir):
    """Compiles one translation unit `tu` (with `files` beside it): (ok, log)."""
    for name, text in list(files.items()) + [("unit.cpp", tu)]:
        with open(os.path.join(workdir, name), "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(text)
    code, log = _run([CXX] + flags + ["-fsyntax-only", "-fmax-errors=200", "unit.cpp"], workdir)
    return code == 0, log


def _batch_gxx(texts, prologue, wrap, flags, suffix):
    """Every text in one translation unit (each in a namespace of its own, so that one parse of the
    standard headers serves all); the texts an error names are compiled again alone, so that one
    text cannot be blamed for another's: [None or error] per text."""
    results = [None] * len(texts)
    with tempfile.TemporaryDirectory(prefix="hostile-gxx-") as d:
        files = {f"case{i}{suffix}": t for i, t in enumerate(texts)}
        tu = prologue + "".join(wrap(i, f"case{i}{suffix}") for i in range(len(texts)))
        ok, log = _gxx(files, tu, flags, d)
        if ok:
            return results
        named = sorted({int(m) for m in re.findall(r"case(\d+)" + re.escape(suffix) + r":\d+", log)})
        for i in (named or range(len(texts))):
            alone_ok, alone_log = _gxx({f"case{i}{suffix}": texts[i]}, prologue + wrap(i, f"case{i}{suffix}"), flags, d)
            if not alone_ok:
                results[i] = _first_error(alone_log, "error")
    return results


def cpp_headers(headers):
    """headers: [text]; compiled by g++ -std=c++20, a // comment continued onto the next line (a
    backslash at its end) an error too: [None or error]."""
    if not CXX or not headers:
        return [None] * len(headers)
    return _batch_gxx(headers, "#include <cmath>\n",
                      lambda i, name: f'namespace case{i} {{\n#include "{name}"\n}}\n',
                      ["-std=c++20", "-Werror=comment"], ".h")


METAL_SHIM = r"""#include <cmath>
#define constant const
struct float2 { float x, y; float2(float a, float b) : x(a), y(b) {} };
struct float3 { float x, y, z; float3(float a, float b, float c) : x(a), y(b), z(c) {} };
struct float4 { float x, y, z, w; float4(float a, float b, float c, float d) : x(a), y(b), z(c), w(d) {} };
inline float2 operator/(float2 a, float s) { return float2(a.x / s, a.y / s); }
inline float3 operator+(float3 a, float3 b) { return float3(a.x + b.x, a.y + b.y, a.z + b.z); }
inline float3 operator-(float3 a, float3 b) { return float3(a.x - b.x, a.y - b.y, a.z - b.z); }
inline float3 operator*(float s, float3 a) { return float3(s * a.x, s * a.y, s * a.z); }
inline float3 operator*(float3 a, float s) { return s * a; }
namespace metal {
inline float abs(float x) { return std::fabs(x); }
inline float acos(float x) { return std::acos(x); }
inline float asin(float x) { return std::asin(x); }
inline float cos(float x) { return std::cos(x); }
inline float sin(float x) { return std::sin(x); }
inline float exp(float x) { return std::exp(x); }
inline float exp2(float x) { return std::exp2(x); }
inline float log(float x) { return std::log(x); }
inline float log2(float x) { return std::log2(x); }
inline float sqrt(float x) { return std::sqrt(x); }
inline float rsqrt(float x) { return 1 / std::sqrt(x); }
inline float pow(float x, float y) { return std::pow(x, y); }
inline float min(float a, float b) { return b < a ? b : a; }
inline float max(float a, float b) { return a < b ? b : a; }
inline float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }
inline float dot(float3 a, float3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float3 cross(float3 a, float3 b) { return float3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x); }
inline float3 normalize(float3 a) { return a * rsqrt(dot(a, a)); }
}  // namespace metal
"""


def metal(texts):
    """Metal exports against the shim of tests/exports/shaders_test.cpp (g++ -std=c++14, so with
    trigraphs; a comment continued by a backslash or ??/ an error): [None or error]."""
    if not CXX or not texts:
        return [None] * len(texts)
    return _batch_gxx(texts, METAL_SHIM,
                      lambda i, name: (f'namespace case{i} {{\n#include "{name}"\n'
                                       "float call() {\n  float3 N(0, 0, 1), L(0.6f, 0, 0.8f), V(-0.6f, 0, 0.8f);\n"
                                       "  return specula_brdf(N, L, V, float4(20, 1, 1, 1));\n}\n}\n"),
                      ["-std=c++14", "-Werror=comment", "-Werror=trigraphs"], ".metal")


def _glslang(source, stage, options=()):
    if not GLSLANG:
        return None
    with tempfile.TemporaryDirectory(prefix="hostile-glsl-") as d:
        path = os.path.join(d, "shader." + stage)
        with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(source)
        code, log = _run([GLSLANG] + list(options) + [path], d)
    if code == 0:
        return None
    return _first_error(log) if code is not None else log


def glslang_batch(items):
    """items: [(GLSL source, 'frag' or 'vert')], compiled as separate units by one glslangValidator
    run (it prints each file's name, then its errors): [None or error]."""
    results = [None] * len(items)
    if not GLSLANG or not items:
        return results
    with tempfile.TemporaryDirectory(prefix="hostile-glsl-") as d:
        names = []
        for i, (source, stage) in enumerate(items):
            names.append(f"s{i}.{stage}")
            with open(os.path.join(d, names[-1]), "w", encoding="utf-8", errors="surrogateescape") as f:
                f.write(source)
        code, log = _run([GLSLANG] + names, d)
    if code == 0:
        return results
    index = {n: i for i, n in enumerate(names)}
    current = None
    for line in log.splitlines():
        if line.strip() in index:
            current = index[line.strip()]
        elif current is not None and "ERROR" in line and results[current] is None:
            results[current] = line.strip()[:200]
    if code is None or not any(results):
        return [log[:200]] * len(items)
    return results


GLSL330 = "#version 330 core\n"


def glsl_function_shader(text):
    """`specula glsl` output (functions, no #version) inside a fragment shader calling specula_brdf."""
    return (GLSL330 + text + "uniform vec4 u_params;\nout vec4 colour;\nvoid main() {\n"
            "  vec3 N = vec3(0.0, 0.0, 1.0), L = normalize(vec3(1.0, 0.0, 1.0));\n"
            "  colour = vec4(specula_brdf(N, L, normalize(vec3(-1.0, 0.2, 1.0)), u_params));\n}\n")


def glsl_function(text):
    return glslang_batch([(glsl_function_shader(text), "frag")])[0]


def glsl_stage(text, stage):
    """A whole shader (`glsl --shader`, /api/glsl's shaders): stage 'frag' or 'vert'."""
    return glslang_batch([(text, stage)])[0]


def hlsl(text):
    shader = (text + "float4 u_params;\nfloat4 main(float4 position : SV_Position) : SV_Target {\n"
              "  float3 N = float3(0.0, 0.0, 1.0), L = normalize(float3(1.0, 0.0, 1.0));\n"
              "  return float4(specula_brdf(N, L, normalize(float3(-1.0, 0.2, 1.0)), u_params), 0.0, 0.0, 1.0);\n}\n")
    return _glslang(shader, "frag", ["-D", "-V", "-S", "frag", "-e", "main", "-o", os.devnull])


def read_brdf(text):
    """A .brdf file as BRDF Explorer's loader reads it: (ok, [slider names], shader text)."""
    lines = text.split("\n")
    kind = lines[0].split(" ")[0] if lines else ""
    ok, section, sliders, shader = kind == "analytic", "", [], ""
    for line in lines[1:]:
        words = line.split()
        if not words or words[0].startswith("#"):
            continue
        if words[0] in ("::begin", "::end"):
            name = words[1] if len(words) > 1 else ""
            ok &= (section == "") if words[0] == "::begin" else (name == section)
            section = name if words[0] == "::begin" else ""
        elif section == "parameters":
            ok &= words[0] == "float" and len(words) >= 5
            sliders.append(words[1] if len(words) > 1 else "")
        elif section == "shader":
            shader += line + "\n"
    return ok and section == "", sliders, shader


def brdf_shader(text):
    """A .brdf file as BRDF Explorer loads it, its shader in the lit-sphere template: (fragment
    shader, None) or (None, why it would not load)."""
    ok, sliders, shader = read_brdf(text)
    if not ok:
        return None, "BRDF Explorer's loader would not read it (sections or parameter lines malformed)"
    body = "".join(f"uniform float {s};\n" for s in sliders) + "\n" + shader
    return ("#version 410\nuniform vec3 incidentVector;\nuniform float incidentTheta;\nuniform float incidentPhi;\n"
            "uniform float brightness;\nuniform float gamma;\nuniform float exposure;\nuniform float useNDotL;\n"
            "in vec4 worldSpaceVert;\nin vec4 eyeSpaceVert;\nout vec4 fragColor;\n" + body +
            "\nvoid main(void) {\n  vec3 normal = normalize(worldSpaceVert.xyz);\n"
            "  vec3 tangent = normalize(cross(vec3(0, 1, 0), normal));\n"
            "  vec3 bitangent = normalize(cross(normal, tangent));\n"
            "  vec3 b = max(BRDF(incidentVector, vec3(0, 0, 1), normal, tangent, bitangent), vec3(0.0));\n"
            "  fragColor = vec4(clamp(b, vec3(0.0), vec3(1.0)), 1.0);\n}\n"), None


def check_exports(items):
    """items: [(format, text)], format one of cpp, msl, hlsl, brdf, glsl (functions), frag, vert:
    [None or why it does not compile], batched per compiler."""
    results = [None] * len(items)
    for fmt, check in (("cpp", cpp_headers), ("msl", metal)):
        idx = [i for i, (f, _) in enumerate(items) if f == fmt]
        for i, err in zip(idx, check([items[i][1] for i in idx])):
            results[i] = err
    glsl = []  # (item index, source, stage)
    for i, (fmt, text) in enumerate(items):
        if fmt == "glsl":
            glsl.append((i, glsl_function_shader(text), "frag"))
        elif fmt in ("frag", "vert"):
            glsl.append((i, text, fmt))
        elif fmt == "brdf":
            source, why = brdf_shader(text)
            if why:
                results[i] = why
            else:
                glsl.append((i, source, "frag"))
        elif fmt == "hlsl":
            results[i] = hlsl(text)
    for (i, _, _), err in zip(glsl, glslang_batch([(s, st) for _, s, st in glsl])):
        results[i] = err
    return results
