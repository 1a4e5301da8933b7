#!/usr/bin/env python3
"""Checks that the README and docs/ say nothing that does not hold.

* Every relative link and image (`[text](path#anchor)`, `[name]: path`) resolves to a file of
  the repository, and an anchor to a heading of the Markdown file it points to (GitHub's
  heading slugs).
* Every command of a fenced `sh` block or an indented block that calls a script of
  `scripts/` names one that exists; `rosrun`/`rostest`/`roslaunch sap_broadphase X` name an
  executable the CMake files build, a test or a launch file that exists.
* The quick commands, those made only of the ROS-free tools `sap_scene` and `sap_pairs`
  (synopses such as `sap_pairs [--threads N] ...` excepted), are run with --bin's tools
  first on PATH and must exit 0. Without --bin they are only listed.
* The README's C++ example is examples/find_package/main.cpp verbatim (that file is built
  and run against the installed package by scripts/test_no_ros.sh).
* Every table of docs/BENCHMARKS.md cites the CSV it comes from (a `name.csv` in the table or
  in the text since the heading or table before it), and every CSV the page names exists
  under bench/results/<machine>/.
* docs/ARCHITECTURE.md's import rule holds for every `#include` of src/core/ and
  include/sap_broadphase/core/: the parts' includes form no cycle, only the facade's .cpp
  and the oracle's header include the facade, API headers include only API headers, the
  floor's headers include only the floor, and every part is named in the page's drawing.

Usage: scripts/check_docs.py [--bin DIR]   exits 1 and lists the problems when any.
"""
import argparse
import os
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOCUMENTS = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
QUICK_TOOLS = {"sap_scene", "sap_pairs"}
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
REFERENCE = re.compile(r"^\[[^\]]+\]:\s*(\S+)", re.M)
FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.M | re.S)


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def anchors(path):
    text = FENCE.sub("", path.read_text(encoding="utf-8"))
    return {slug(m.group(1)) for m in re.finditer(r"^#+\s+(.*)$", text, re.M)}


def link_problems(doc):
    text = doc.read_text(encoding="utf-8")
    targets = LINK.findall(FENCE.sub("", text)) + REFERENCE.findall(text)
    for target in targets:
        if re.match(r"^[a-z]+:", target):
            continue  # http(s), mailto: not checked offline
        path_part, _, anchor = target.partition("#")
        path = (doc.parent / path_part).resolve() if path_part else doc
        if not path.exists():
            yield f"{doc.relative_to(ROOT)}: link to missing {target}"
        elif anchor and path.suffix == ".md" and anchor not in anchors(path):
            yield f"{doc.relative_to(ROOT)}: no heading for #{anchor} in {path.relative_to(ROOT)}"


def command_lines(doc):
    """Lines of fenced sh blocks and of indented blocks, without comments."""
    text = doc.read_text(encoding="utf-8")
    blocks = [body for info, body in FENCE.findall(text) if info in ("sh", "bash")]
    unfenced = FENCE.sub("", text)
    blocks += [m.group(0) for m in re.finditer(r"(?:^(?: {4}|\t).*\n)+", unfenced, re.M)]
    for block in blocks:
        for line in block.splitlines():
            line = re.sub(r"(^|\s)#.*$", "", line).strip()
            if line:
                yield line


def built_executables():
    """Names of the executables the CMake files build (OUTPUT_NAME where one is set)."""
    names = set()
    for cmake in list(ROOT.glob("**/*.cmake")) + [ROOT / "CMakeLists.txt"]:
        if "build" in cmake.relative_to(ROOT).parts:
            continue
        text = cmake.read_text(encoding="utf-8")
        names |= {re.sub(r"\$\{PROJECT_NAME\}", "sap_broadphase", n)
                  for n in re.findall(r"add_executable\((\S+)", text)}
        names |= set(re.findall(r"OUTPUT_NAME\s+(\S+)", text))
        names |= set(re.findall(r"(?:catkin_add_gtest|sap_add_gtest|add_rostest_gtest)\((\S+)", text))
        for programs in re.findall(r"catkin_install_python\(PROGRAMS(.*?)DESTINATION", text, re.S):
            names |= {pathlib.Path(path).name for path in programs.split()}
    return names


def reference_problems(doc, line, executables):
    for word in re.findall(r"(?:^|[\s;&|(])((?:\./)?scripts/[\w./-]+)", line):
        if not (ROOT / word).is_file():
            yield f"{doc.relative_to(ROOT)}: `{line}` calls missing {word}"
    for tool, name in re.findall(r"\b(rosrun|rostest|roslaunch) sap_broadphase (\S+)", line):
        found = {
            "rosrun": lambda: name in executables,
            "rostest": lambda: any(ROOT.glob(f"test/**/{name}")),
            "roslaunch": lambda: (ROOT / "launch" / name).is_file(),
        }[tool]()
        if not found:
            yield f"{doc.relative_to(ROOT)}: `{line}`: no {name} for {tool}"


def is_quick(line):
    words = re.findall(r"(?:^|\|)\s*(\S+)", line)
    return bool(words) and all(w in QUICK_TOOLS for w in words) and " [" not in line


def run_quick(doc, line, bin_dir):
    env = dict(os.environ, PATH=f"{bin_dir}{os.pathsep}{os.environ['PATH']}")
    env.setdefault("OMP_WAIT_POLICY", "passive")
    result = subprocess.run(["bash", "-o", "pipefail", "-c", line], cwd=ROOT, env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=300)
    if result.returncode != 0:
        yield (f"{doc.relative_to(ROOT)}: `{line}` exited {result.returncode}: "
               f"{result.stderr.decode(errors='replace').strip()[-300:]}")


def example_problems():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    example = (ROOT / "examples/find_package/main.cpp").read_text(encoding="utf-8")
    for info, body in FENCE.findall(readme):
        if info == "cpp" and body.strip() not in example:
            yield "README.md: the C++ example differs from examples/find_package/main.cpp"


BENCHMARKS = ROOT / "docs" / "BENCHMARKS.md"
RESULTS = ROOT / "bench" / "results"
CSV_NAME = re.compile(r"[\w.*/-]*\w\.csv\b")


def tables_with_context(text):
    """(first line number, table and the text before it since the last heading or table)."""
    context, table, first = [], [], 0
    unfenced = FENCE.sub(lambda block: "\n" * block.group(0).count("\n"), text)  # lines kept
    for number, line in enumerate(unfenced.splitlines(), 1):
        if line.startswith("|"):
            if not table:
                first = number
            table.append(line)
            continue
        if table:
            yield first, "\n".join(context + table)
            context, table = [], []
        if line.startswith("#"):
            context = []
        context.append(line)
    if table:
        yield first, "\n".join(context + table)


def result_exists(name):
    return any(any(machine.glob(name)) for machine in RESULTS.iterdir() if machine.is_dir())


def benchmark_table_problems():
    text = BENCHMARKS.read_text(encoding="utf-8")
    for line, block in tables_with_context(text):
        if not CSV_NAME.search(block):
            yield f"docs/BENCHMARKS.md:{line}: a table that cites no CSV of bench/results/"
    for name in sorted(set(CSV_NAME.findall(FENCE.sub("", text)))):
        if not result_exists(name):
            yield f"docs/BENCHMARKS.md: {name} is in no folder of bench/results/"


CORE = ROOT / "src" / "core"
API = ROOT / "include" / "sap_broadphase" / "core"
INCLUDE = re.compile(r'^\s*#\s*include\s+"(?:sap_broadphase/)?core/(?:\w+/)?(\w+)\.h"', re.M)
FACADE = "broadphase"
ALLOWED_FACADE_INCLUDERS = {CORE / "broadphase.cpp", API / "brute_force.h"}


def core_includes():
    """{file: [part it includes]} over the engine's sources and API headers."""
    files = sorted(CORE.rglob("*.h")) + sorted(CORE.rglob("*.cpp")) + sorted(API.glob("*.h"))
    return {f: INCLUDE.findall(f.read_text(encoding="utf-8")) for f in files}


def part_cycle(includes):
    """A cycle of parts (a part: a file name without extension), or None."""
    graph = {}
    for source, parts in includes.items():
        graph.setdefault(source.stem, set()).update(p for p in parts if p != source.stem)
    done, on_path = set(), []

    def visit(part):
        if part in on_path:
            return on_path[on_path.index(part):] + [part]
        if part in done:
            return None
        on_path.append(part)
        for successor in sorted(graph.get(part, ())):
            cycle = visit(successor)
            if cycle:
                return cycle
        on_path.pop()
        done.add(part)
        return None

    for part in sorted(graph):
        cycle = visit(part)
        if cycle:
            return cycle
    return None


def drawing_of_parts(architecture):
    """The fenced drawing under "The parts and their imports": its text and its floor's parts."""
    section = architecture.split("## The parts and their imports", 1)[1]
    drawing = FENCE.search(section).group(2)
    lines = drawing.splitlines()
    floor_at = next(i for i, line in enumerate(lines) if "the floor" in line)
    floor_line = next(line for line in lines[floor_at + 1:] if "[api]" in line)
    return drawing, set(re.findall(r"(\w+)(?: \[api\])?", floor_line))


def import_problems():
    includes = core_includes()
    architecture = (ROOT / "docs" / "ARCHITECTURE.md").read_text(encoding="utf-8")
    drawing, floor = drawing_of_parts(architecture)
    api_parts = {f.stem for f in API.glob("*.h")}
    cycle = part_cycle(includes)
    if cycle:
        yield "src/core: an include runs back up: " + " -> ".join(cycle)
    for source, parts in includes.items():
        where = source.relative_to(ROOT)
        if FACADE in parts and source.stem != FACADE and source not in ALLOWED_FACADE_INCLUDERS:
            yield f"{where}: includes the facade (broadphase.h)"
        if source.parent == API:
            for part in sorted(set(parts) - api_parts):
                yield f"{where}: an API header includes the private core/{part}.h"
        if source.suffix == ".h" and source.stem in floor:
            for part in sorted(set(parts) - floor):
                yield f"{where}: a floor header includes core/{part}.h, above the floor"
    named = set(re.findall(r"\w+", drawing))
    for part in sorted({f.stem for f in includes} - named):
        yield f"docs/ARCHITECTURE.md: the drawing of the parts does not name {part}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bin", help="folder holding sap_scene and sap_pairs")
    args = parser.parse_args()
    executables = built_executables()
    problems, ran = [], 0
    for doc in DOCUMENTS:
        problems += link_problems(doc)
        for line in command_lines(doc):
            problems += reference_problems(doc, line, executables)
            if is_quick(line):
                if args.bin:
                    problems += run_quick(doc, line, args.bin)
                    ran += 1
                else:
                    print(f"not run (no --bin): {line}")
    problems += example_problems()
    problems += benchmark_table_problems()
    problems += import_problems()
    for problem in problems:
        print(problem, file=sys.stderr)
    print(f"check_docs: {len(DOCUMENTS)} documents, {ran} quick commands run, "
          f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
