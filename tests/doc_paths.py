#!/usr/bin/python3
"""Every repository path named in the docs and in comments must exist.

  tests/doc_paths.py [SOURCE_DIR]

Reads every *.md file, and the comments of the sources under rtl/ sim/ model/ host/ derive/
explore/ tests/ scripts/ cmake/ bench/ and of every CMakeLists.txt (// and /* */ in C++ and SystemVerilog, # in
shell, Python and CMake). A path is a token with a '/' that either ends in a file extension
(notes/rtl.md) or starts with a top-level entry of the repository (scenes/hard/). It must exist
relative to the repository root, to the file naming it, or to an installed package's files
(assimp-testmodels' invalid/OutOfMemory.off; scripts/setup installs it). A name without its
extension (host/specular_setup) names its .h/.cpp; a glob (model/*.cpp) must match a file.
Outputs (out/, build/), placeholders (scenes/<scene>.json), URLs and absolute paths are not
repository paths. A mention of the "design brief" or design.md (not in the repository) counts as
missing too. Exits 1 naming file:line and the path for each that does not exist.

Markdown links: every [text](target) in a *.md file must name an existing file, and
its #anchor a heading of that file (GitHub's anchors).

Commands and options: in the code of every *.md file (fenced and indented blocks and
`inline spans`), each `shadesim COMMAND` must be a subcommand that `shadesim --help` lists, and
each --option after it (up to the end of the shell command: newline, ;, |, &&, a # comment or
the next shadesim) must appear in `shadesim COMMAND --help`. The binary is --shadesim PATH (ctest
passes the built one), else build/shadesim under SOURCE_DIR; without either the check says so
and only paths are checked. Scripts (scripts/x) are paths, checked above.

  tests/doc_paths.py [SOURCE_DIR] [--shadesim PATH]
  tests/doc_paths.py --self-test

The self-test checks the checker on a small tree it writes, with a stand-in shadesim: it must
name each missing path, unknown command, made-up option and broken link there and pass the paths, commands
and options that exist, ignoring paths in code (string literals), outputs and shell comments.
"""
import glob
import os
import re
import sys

ARGS = [a for a in sys.argv[1:]]
SHADESIM = None
if "--shadesim" in ARGS:
    i = ARGS.index("--shadesim")
    SHADESIM = os.path.abspath(ARGS[i + 1]) if i + 1 < len(ARGS) else ""
    del ARGS[i:i + 2]
ROOT = os.path.abspath(ARGS[0] if ARGS and ARGS[0] != "--self-test" else
                       os.path.join(os.path.dirname(__file__), ".."))
SOURCE_DIRS = ["rtl", "sim", "model", "host", "derive", "explore", "tests", "scripts", "cmake",
               "bench"]
C_LIKE = {".h", ".hpp", ".cpp", ".cc", ".c", ".sv", ".svh", ".v", ".vlt"}
HASH = {".py", ".sh", ".cmake", ".txt", ".yml", ".yaml"}
SKIP_DIRS = {".git", "build", "out", "Testing", "__pycache__"}
# Written by the tools, not part of the repository.
GENERATED = ("out/", "build/", "build-", "Testing/")
# Paths of other projects that comments cite on purpose: path -> whose.
EXTERNAL = {
    "dv/cosim/cosim.h": "lowRISC ibex",
}
# Installed packages whose files the docs name by their own relative paths (scripts/setup
# installs them): a path found there is theirs.
PACKAGE_ROOTS = ["/usr/share/assimp/models"]  # assimp-testmodels: invalid/OutOfMemory.off
# Documents a comment may cite but the repository does not hold: phrase -> what to cite instead.
MISSING_DOCUMENTS = {
    "design brief": 'is not in the repository; cite a README section (e.g. "Checked numerical facts")',
    "design.md": 'is not in the repository; cite a README section (e.g. "Checked numerical facts")',
}
TOKEN = re.compile(r"[A-Za-z0-9_.*<>{}$~\-]*(?:/[A-Za-z0-9_.*<>{}$\-]*)+")
EXTENSION = re.compile(r"\.[a-z][a-z0-9]{0,4}$")


def c_comments(text):
    """(line number, comment text) of // and /* */ comments, skipping string and char literals."""
    out, i, line, n = [], 0, 1, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append((line, text[i + 2:j]))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j
            for k, part in enumerate(text[i + 2:j].split("\n")):
                out.append((line + k, part))
            line += text.count("\n", i, j)
            i = j + 2
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            i = j + 1
        else:
            i += 1
    return out


def hash_comments(text):
    """(line number, comment text) after a # that is not inside quotes (shell, Python, CMake)."""
    out = []
    for number, line in enumerate(text.split("\n"), 1):
        quote = None
        for k, c in enumerate(line):
            if quote:
                if c == quote:
                    quote = None
            elif c in "\"'":
                quote = c
            elif c == "#" and (k == 0 or line[k - 1] in " \t(;"):
                if not line.startswith("#!"):
                    out.append((number, line[k + 1:]))
                break
    return out


def files():
    for dirpath, dirnames, filenames in os.walk(ROOT):
        dirnames[:] = sorted(d for d in dirnames if d not in SKIP_DIRS)
        rel_dir = os.path.relpath(dirpath, ROOT)
        top = rel_dir.split(os.sep)[0]
        for name in sorted(filenames):
            path = os.path.join(dirpath, name)
            ext = os.path.splitext(name)[1]
            if ext == ".md":
                yield path, "doc"
            elif name == "CMakeLists.txt":
                yield path, "hash"
            elif top in SOURCE_DIRS:
                if ext in C_LIKE:
                    yield path, "c"
                elif ext in HASH or (ext == "" and first_line(path).startswith("#!")):
                    yield path, "hash"


def first_line(path):
    try:
        with open(path, errors="replace") as f:
            return f.readline()
    except OSError:
        return ""


def candidates(text, top_level):
    for m in TOKEN.finditer(text):
        start = m.start()
        if start > 0 and (text[start - 1].isalnum() or text[start - 1] in ":/@"):
            continue  # part of a URL, an absolute path or a longer word
        tok = m.group(0).rstrip(".,;:)")
        if "/" not in tok or tok.startswith(("/", "~", "./")) and not tok.startswith("../"):
            continue
        if any(ch in tok for ch in "<>{}$") or "..." in tok.replace("../", "") or "//" in tok:
            continue
        if tok.startswith(GENERATED) or tok in EXTERNAL:
            continue
        first = tok.lstrip("./").split("/")[0] if not tok.startswith("../") else ".."
        if EXTENSION.search(tok.rstrip("/")) or first in top_level:
            yield tok


def exists(tok, base_dir):
    for base in [ROOT, base_dir] + PACKAGE_ROOTS:
        p = os.path.normpath(os.path.join(base, tok))
        if "*" in tok:
            if glob.glob(p):
                return True
        elif os.path.exists(p) or glob.glob(p + ".*"):
            return True  # host/specular_setup names host/specular_setup.{h,cpp}
    return False


# --- shadesim commands and options cited in the docs --------------------------------------------

FENCE = re.compile(r"^\s*(```|~~~)")
INLINE = re.compile(r"`([^`\n]+(?:\n[^`\n]+)*?)`")
CITED = re.compile(r"(?:^|(?<=[\s(/]))shadesim\s+([a-z][a-z0-9-]*)")
OPTION = re.compile(r"(?<![A-Za-z0-9_-])--[a-z][a-z0-9-]*")
SEGMENT_END = re.compile(r";|&&|\|\||\||(?:^|\s)#|\n")


def code_texts(text):
    """(line number, code text) of a markdown file: each line of a fenced or indented block (a
    line ending in a backslash joined with the next), and each inline `span` (which may run over
    a line break within its paragraph)."""
    out, prose, fenced, pending = [], [], False, None
    lines = text.split("\n")
    for number, line in enumerate(lines, 1):
        if FENCE.match(line):
            fenced = not fenced
            prose.append("")
            continue
        if fenced or (line.startswith("    ") and line.strip() and
                      (number == 1 or not lines[number - 2].strip() or pending)):
            start, body = pending if pending else (number, "")
            body += line.rstrip("\\") + " "
            pending = (start, body) if line.endswith("\\") else None
            if pending is None:
                out.append((start, body))
            prose.append("")
        else:
            prose.append(line)
    joined = "\n".join(prose)
    for m in INLINE.finditer(joined):
        # an inline span is a command on one line: its line breaks are spaces
        out.append((joined.count("\n", 0, m.start()) + 1, m.group(1).replace("\n", " ")))
    return out


def citations(code):
    """(command, [options]) for each `shadesim COMMAND ...` in a piece of code."""
    for m in CITED.finditer(code):
        rest = code[m.end():]
        end = SEGMENT_END.search(rest)
        rest = rest[:end.start()] if end else rest
        nxt = re.search(r"(?:^|[\s(/])shadesim\s", rest)
        rest = rest[:nxt.start()] if nxt else rest
        yield m.group(1), OPTION.findall(rest)


def run_help(binary, *args):
    import subprocess
    r = subprocess.run([binary, *args, "--help"], capture_output=True, text=True, timeout=60)
    return r.returncode, r.stdout + r.stderr


def subcommands(binary):
    code, text = run_help(binary)
    names, inside = set(), False
    for line in text.split("\n"):
        if re.match(r"^\S.*:\s*$", line):
            inside = line.strip().lower().startswith("subcommands")
        elif inside and line.strip():
            names.add(line.split()[0])
    return names


def check_commands(binary, docs):
    """Findings for every cited command and option; docs is [(relative path, text)]."""
    commands = subcommands(binary)
    if not commands:
        return [f"{binary} --help lists no subcommands"], 0
    helps, found, checked = {}, [], 0
    for rel, text in docs:
        for number, code in code_texts(text):
            for command, options in citations(code):
                checked += 1
                if command not in commands:
                    found.append(f"{rel}:{number}: shadesim {command} is not a command of "
                                 f"shadesim --help")
                    continue
                if command not in helps:
                    helps[command] = run_help(binary, command)[1]
                for option in options:
                    checked += 1
                    if not re.search(re.escape(option) + r"(?![A-Za-z0-9_-])", helps[command]):
                        found.append(f"{rel}:{number}: shadesim {command} {option} is not an "
                                     f"option of shadesim {command} --help")
    return found, checked


# --- markdown links ------------------------------------------------------------------------------

LINK = re.compile(r"\]\(([^)\s]+)\)")


def anchor(heading):
    """GitHub's anchor of a markdown heading: lower case, punctuation dropped, spaces to '-'."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def check_links(path, text):
    """Findings for each [text](target) in a markdown file whose file or #anchor does not exist."""
    found = []
    for number, line in enumerate(text.split("\n"), 1):
        for m in LINK.finditer(line):
            target = m.group(1)
            if re.match(r"^[a-z]+:", target):
                continue  # https:, mailto:
            file, _, frag = target.partition("#")
            full = os.path.normpath(os.path.join(os.path.dirname(path), file)) if file else path
            rel = os.path.relpath(path, ROOT)
            if not os.path.exists(full):
                found.append(f"{rel}:{number}: link {target} does not resolve")
            elif frag and full.endswith(".md"):
                with open(full, errors="replace") as f:
                    heads = {anchor(h) for h in re.findall(r"^#+\s+(.*)$", f.read(), re.M)}
                if frag not in heads:
                    found.append(f"{rel}:{number}: link {target}: no heading with that anchor")
    return found


def self_test():
    import subprocess
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        def write(rel, text):
            os.makedirs(os.path.dirname(os.path.join(tmp, rel)), exist_ok=True)
            with open(os.path.join(tmp, rel), "w") as f:
                f.write(text)
        write("README.md", "See `model/a.h`, `notes/rtl.md` and `scenes/hard/`; out/x/compare.png is made.\n")
        write("model/a.h", '// see model/*.h and sim/gone.cpp\nconst char* p = "sim/code_only.cpp";\n')
        write("scenes/hard/x.json", "{}\n")
        write("scripts/run", "#!/bin/sh\n# reads scenes/hard/x.json and scenes/none.json\necho '# not/a_comment.txt'\n")
        write("sim/b.cpp", "/* the design brief says\n   so, in host/setup.h */\nint x;\n")
        # commands and options, against a stand-in shadesim with two subcommands
        write("docs/use.md", "Run `shadesim render scenes/hard/x.json --json a.json` or\n"
              "`build/shadesim cycles x --config\nunit.json --made-up-option 3`.\n\n"
              "```sh\nbuild/shadesim render x --series s4.20 --bogus  # --config is a comment\n"
              "build/shadesim frobnicate --json x | grep --count\nscripts/run --any-option\n```\n\n"
              "    shadesim cycles x --config f \\\n      --no-such\n\n"
              "[ok](../README.md) [ok](#links) [gone](gone.md) [bad](../README.md#nowhere)\n\n## Links\n")
        write("fake/shadesim", "#!/bin/sh\ncase \"$1\" in\n"
              "--help) printf 'shadesim\\nOptions:\\n  -h,--help  help\\nSubcommands:\\n"
              "  render    Render a scene\\n  cycles    Count cycles\\n';;\n"
              "render) printf 'Options:\\n  --json FILE\\n  --series FMT\\n';;\n"
              "cycles) printf 'Options:\\n  --config FILE\\n';;\nesac\n")
        os.chmod(os.path.join(tmp, "fake/shadesim"), 0o755)
        r = subprocess.run([sys.executable, __file__, tmp, "--shadesim", os.path.join(tmp, "fake/shadesim")],
                           capture_output=True, text=True)
        expected = ["README.md:1: notes/rtl.md does not exist", "model/a.h:1: sim/gone.cpp does not exist",
                    "scripts/run:2: scenes/none.json does not exist", "sim/b.cpp:1: the design brief",
                    "sim/b.cpp:2: host/setup.h does not exist",
                    "docs/use.md:2: shadesim cycles --made-up-option is not an option",
                    "docs/use.md:6: shadesim render --bogus is not an option",
                    "docs/use.md:7: shadesim frobnicate is not a command",
                    "docs/use.md:11: shadesim cycles --no-such is not an option",
                    "docs/use.md:14: link gone.md does not resolve",
                    "docs/use.md:14: link ../README.md#nowhere: no heading with that anchor"]
        lines = r.stdout.strip().split("\n")
        problems = [e for e in expected if not any(line.startswith(e) for line in lines)]
        if r.returncode != 1:
            problems.append(f"exit {r.returncode}, expected 1")
        if len(lines) != len(expected) + 1:
            problems.append(f"{len(lines) - 1} finding(s), expected {len(expected)}")
        if problems:
            print("doc_paths self-test FAILED:", *problems, "output:", r.stdout, sep="\n  ")
            return 1
        print(f"doc_paths self-test: the {len(expected)} missing paths, commands and options named, "
              "nothing else")
        return 0


def main():
    if "--self-test" in sys.argv[1:]:
        return self_test()
    top_level = {e for e in os.listdir(ROOT) if e not in SKIP_DIRS}
    missing = []
    checked = 0
    for path, kind in files():
        with open(path, errors="replace") as f:
            text = f.read()
        if kind == "doc":
            lines = list(enumerate(text.split("\n"), 1))
            missing += check_links(path, text)
        elif kind == "c":
            lines = c_comments(text)
        else:
            lines = hash_comments(text)
        for number, line in lines:
            for phrase, fix in MISSING_DOCUMENTS.items():
                if phrase in line.lower():
                    missing.append(f"{os.path.relpath(path, ROOT)}:{number}: the {phrase} {fix}")
            for tok in candidates(line, top_level):
                checked += 1
                if not exists(tok, os.path.dirname(path)):
                    missing.append(f"{os.path.relpath(path, ROOT)}:{number}: {tok} does not exist")
    binary = SHADESIM if SHADESIM is not None else os.path.join(ROOT, "build", "shadesim")
    commands_note = ""
    if SHADESIM is not None and not os.access(binary, os.X_OK):
        missing.append(f"--shadesim {binary}: not an executable")
    elif os.access(binary, os.X_OK):
        docs = []
        for path, kind in files():
            if kind == "doc":
                with open(path, errors="replace") as f:
                    docs.append((os.path.relpath(path, ROOT), f.read()))
        found, cited = check_commands(binary, docs)
        missing += found
        commands_note = f"; {cited} shadesim command(s) and option(s) cited, checked against {binary}"
    else:
        commands_note = f"; commands and options NOT checked: no {binary} (build it, or --shadesim PATH)"
    for m in missing:
        print(m)
    print(f"doc_paths: {checked} path(s) named in docs and comments, {len(missing)} missing"
          + commands_note)
    return 1 if missing or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
