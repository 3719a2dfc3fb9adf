#!/usr/bin/env python3
"""lsdem's test plan, read from the code: for each source file of the libraries, the tools and
the Python module, the tests that cover it — a test file named after it (Test<Name>.cpp), the
test files that include its header, or, for a source no test reaches directly, the sources that
use it (whose tests exercise it through them).

    python3 scripts/test_plan.py          # write tests/TEST_PLAN.md
    python3 scripts/test_plan.py --check  # exit 1 if tests/TEST_PLAN.md is out of date (ctest)
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PLAN = os.path.join("tests", "TEST_PLAN.md")
SOURCE_FOLDERS = ["libls", "libcontact", "tools", "python/src"]
TEST_FOLDERS = ["tests", "fuzz"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def files_under(folders, suffixes):
    found = []
    for folder in folders:
        for parent, dirs, names in os.walk(os.path.join(ROOT, folder)):
            dirs.sort()
            for name in sorted(names):
                if name.endswith(suffixes):
                    found.append(os.path.relpath(os.path.join(parent, name), ROOT))
    return found


def includes(path):
    with open(os.path.join(ROOT, path), encoding="utf-8") as f:
        return INCLUDE.findall(f.read())


def header_of(source, headers):
    """The header declaring @source: the same name beside it or in its library's include/."""
    stem = os.path.splitext(os.path.basename(source))[0] + ".h"
    beside = os.path.join(os.path.dirname(source), stem)
    if beside in headers:
        return beside
    library = source.split("/src/")[0] if "/src/" in source else None
    if library:
        for h in headers:
            if h.startswith(library + "/include/") and os.path.basename(h) == stem:
                return h
    return None


def names_header(include, including_file, header):
    """Whether the include string @include, written in @including_file, names @header."""
    if os.path.normpath(os.path.join(os.path.dirname(including_file), include)) == header:
        return True
    return header.endswith("/" + include)


def plan():
    sources = [s for s in files_under(SOURCE_FOLDERS, (".cpp",))]
    headers = set(files_under(SOURCE_FOLDERS, (".h",)))
    tests = [t for t in files_under(TEST_FOLDERS, (".cpp", ".h"))]
    test_includes = {t: includes(t) for t in tests}
    source_includes = {s: includes(s) for s in sources}
    header_includes = {h: includes(h) for h in headers}

    def tests_including(header):
        return [t for t, incs in test_includes.items()
                if any(names_header(i, t, header) for i in incs)]

    def users_of(header):
        """Sources (through their own file or their header) that include @header."""
        users = []
        for s in sources:
            own = header_of(s, headers)
            if own == header:
                continue
            incs = source_includes[s] + (header_includes.get(own, []) if own else [])
            if any(names_header(i, s, header) for i in incs):
                users.append(s)
        return users

    def own_headers(s):
        """The header declaring @s; without one, the private headers beside it that it
        includes (a sub-model implementing a registry's declarations, say)."""
        header = header_of(s, headers)
        if header:
            return [header]
        # A class split over files (SimulationForces.cpp of Simulation.h): the header whose
        # name begins the source's, among those it includes.
        stem = os.path.splitext(os.path.basename(s))[0]
        included = [h for h in headers if any(names_header(i, s, h) for i in source_includes[s])]
        prefixed = [h for h in included
                    if stem.startswith(os.path.splitext(os.path.basename(h))[0])]
        if prefixed:
            return [max(prefixed, key=len)]
        folder = os.path.dirname(s)
        return sorted(h for h in included if os.path.dirname(h) == folder)

    def program_name(path):
        stem = os.path.splitext(os.path.basename(path))[0]
        return stem.replace("-", "").replace("_", "").lower()

    test_text = {t: open(os.path.join(ROOT, t), encoding="utf-8").read() for t in tests}

    def direct_tests(s):
        named = [t for t in tests
                 if program_name(t) == "test" + program_name(s) and t.endswith(".cpp")]
        stem = os.path.splitext(os.path.basename(s))[0]
        if s.startswith("tools/") and stem.startswith("lsdem-"):
            # A program: the tests that run it by name.
            macro = stem.upper().replace("-", "_") + "_EXE"  # tests/CMakeLists.txt passes it
            named += [t for t in tests
                      if '"' + stem in test_text[t] or "/" + stem in test_text[t]
                      or macro in test_text[t]]
        return sorted(set(named + [t for h in own_headers(s) for t in tests_including(h)]))

    direct = {s: direct_tests(s) for s in sources}
    rows = []
    for s in sources:
        if s.startswith("python/src/"):
            rows.append((s, "the module, through `python/tests/*.py` (pytest)"))
        elif direct[s]:
            rows.append((s, ", ".join("`%s`" % t for t in direct[s])))
        else:
            users = sorted(set(u for h in own_headers(s) for u in users_of(h) if u != s))
            # Name the users that tests reach directly, where there are some.
            tested = [u for u in users if direct[u]]
            if tested or users:
                rows.append((s, "through " + ", ".join("`%s`" % u for u in (tested or users))))
            else:
                rows.append((s, "**none found**"))
    return rows


def render(rows):
    named = sum(1 for s, t in rows
                if "/Test" + os.path.splitext(os.path.basename(s))[0] + ".cpp`" in t)
    through = sum(1 for s, t in rows if t.startswith("through"))
    out = ["# Test plan",
           "",
           "Generated by `python3 scripts/test_plan.py` from the code (ctest's `TestPlan.IsCurrent`",
           "fails when it is out of date): for each source file, the test files that cover it —",
           "one named after it, or those that include its header — and, for a source no test",
           "includes, the sources that use it, whose tests reach it through them.",
           "",
           "%d sources: %d have a test file of their own name; %d are reached only through the"
           % (len(rows), named, through),
           "sources that use them.",
           "",
           "| source | covered by |",
           "|---|---|"]
    out += ["| `%s` | %s |" % (s, t) for s, t in rows]
    return "\n".join(out) + "\n"


def main():
    text = render(plan())
    path = os.path.join(ROOT, PLAN)
    if "--check" in sys.argv[1:]:
        current = open(path, encoding="utf-8").read() if os.path.exists(path) else ""
        if current != text:
            sys.stderr.write("%s is out of date: run python3 scripts/test_plan.py and commit it\n"
                             % PLAN)
            return 1
        return 0
    temporary = path + ".tmp"
    with open(temporary, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(temporary, path)
    print("wrote %s" % PLAN)
    return 0


if __name__ == "__main__":
    sys.exit(main())
